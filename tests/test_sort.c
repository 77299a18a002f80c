/* kernels/pn_sort.h compiled as C: the blocked exclusive prefix sum against a serial sum
 * for every block count the OpenCL port can choose (and ragged last blocks, empty blocks,
 * sums that wrap 2^32), and the in-place sort against qsort on runs of distinct ids,
 * sorted, reversed, nearly sorted and random, lengths 0 .. 3000. */
#include <stdlib.h>
#include <string.h>

#include "pn_sort.h"
#include "pn_test.h"

static uint32_t rng = 12345u;
static uint32_t next(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 17;
    rng ^= rng << 5;
    return rng;
}

static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return x < y ? -1 : x > y;
}

static void test_scan(void)
{
    static const uint32_t ns[] = {1, 2, 7, 64, 1000, 4097, 100000};
    static const uint32_t nbs[] = {1, 2, 3, 16, 256, 1000};
    uint32_t *a = (uint32_t *)malloc(100001u * 4u), *ref = (uint32_t *)malloc(100001u * 4u), part[1000];
    size_t i, j;
    REQUIRE(a && ref);
    for (i = 0; i < sizeof(ns) / sizeof(ns[0]); i++)
        for (j = 0; j < sizeof(nbs) / sizeof(nbs[0]); j++) {
            uint32_t n = ns[i], nb = nbs[j], blk = (n + nb - 1u) / nb, b, run = 0, k, wrap = (i + j) & 1u;
            for (k = 0; k < n; k++) {
                /* Some runs with values near 2^32: the sum wraps the same way both ways. */
                a[k] = wrap ? 0xF0000000u + (next() & 0xFFFFu) : next() & 0xFFu;
                ref[k] = run;
                run += a[k];
            }
            ref[n] = run;
            a[n] = 0xDEADBEEFu;
            for (b = 0; b < nb; b++) pn_scan_block_sum(a, n, blk, b, part);
            pn_scan_partials(part, nb, a + n);
            for (b = nb; b-- > 0;) pn_scan_block_apply(a, n, blk, b, part); /* any order */
            CHECK_MSG(memcmp(a, ref, ((size_t)n + 1u) * 4u) == 0, "scan n=%u nb=%u", n, nb);
        }
    free(a);
    free(ref);
}

static void test_sort_runs(void)
{
    uint32_t *a = (uint32_t *)malloc(3000u * 4u), *ref = (uint32_t *)malloc(3000u * 4u);
    uint32_t *b = (uint32_t *)malloc(3000u * 4u), *tmp = (uint32_t *)malloc(3000u * 4u);
    uint32_t n, kind;
    REQUIRE(a && ref && b && tmp);
    for (n = 0; n <= 3000u; n += n < 40u ? 1u : 173u)
        for (kind = 0; kind < 8u; kind++) {
            uint32_t i;
            for (i = 0; i < n; i++) ref[i] = i * 7u + (next() % 7u); /* distinct, ascending */
            memcpy(a, ref, (size_t)n * 4u);
            if (kind == 1u)
                for (i = 0; i < n / 2u; i++) {
                    uint32_t t = a[i];
                    a[i] = a[n - 1u - i];
                    a[n - 1u - i] = t;
                }
            if (kind == 2u && n > 1u) { /* two runs interleaved, as two threads hand out slots */
                uint32_t t = a[n / 3u];
                a[n / 3u] = a[n / 3u + 1u];
                a[n / 3u + 1u] = t;
            }
            if (kind == 3u)
                for (i = n; i > 1u; i--) {
                    uint32_t j = next() % i, t = a[i - 1u];
                    a[i - 1u] = a[j];
                    a[j] = t;
                }
            if (kind == 4u) /* the first and second halves dealt alternately (in order each) */
                for (i = 0; i < n; i++) a[i] = ref[(i & 1u) ? (n + 1u) / 2u + i / 2u : i / 2u];
            if (kind == 5u) /* blocks of 16 shuffled within themselves: work-groups side by side */
                for (i = n; i > 1u; i--) {
                    uint32_t b0 = (i - 1u) & ~15u, j = b0 + next() % (i - b0), t = a[i - 1u];
                    a[i - 1u] = a[j];
                    a[j] = t;
                }
            if (kind >= 6u) { /* four (five) quarters (fifths) dealt in turn: the most the merge takes, one more */
                uint32_t m = kind == 6u ? 4u : 5u, q = (n + m - 1u) / m, r, o = 0u;
                for (r = 0; r < q; r++)
                    for (i = 0; i < m; i++)
                        if (i * q + r < n && r < q) a[o++] = ref[i * q + r];
            }
            memcpy(b, a, (size_t)n * 4u);
            pn_sort_u32(a, n);
            pn_sort_u32_merge(b, tmp, n);
            qsort(ref, n, 4u, cmp_u32);
            CHECK_MSG(memcmp(a, ref, (size_t)n * 4u) == 0, "sort n=%u kind=%u", n, kind);
            CHECK_MSG(memcmp(b, ref, (size_t)n * 4u) == 0, "sort with scratch n=%u kind=%u", n, kind);
        }
    free(a);
    free(ref);
    free(b);
    free(tmp);
}

int main(void)
{
    RUN(test_scan);
    RUN(test_sort_runs);
    return pn_test_summary();
}
