/* pn_sort.h - integer building blocks for data-parallel ports: an exclusive prefix sum in
 * blocks and an in-place sort of a short run of distinct ids.
 *
 * Both give one answer whatever the schedule: integer addition is associative, and a
 * sorted run of distinct values is unique. That is what lets the OpenCL port fill a
 * GEARS cell's triangle list with atomic cursors (any order) and still match the scalar
 * port's stable counting sort byte for byte once each list is sorted. */
#ifndef PN_SORT_H
#define PN_SORT_H

#include "pn_kernel.h"

/* ---- Exclusive prefix sum of a[0 .. n) in place, total to a[n] ------------------------
 * Three steps over nb blocks of blk elements (nb * blk >= n): each block's sum into
 * part[b]; the partials scanned in place by one work item (the total into a[n]); each
 * block scanned from its partial. */

PN_KFN void pn_scan_block_sum(PN_CONST uint32_t *a, uint32_t n, uint32_t blk, uint32_t b, PN_GLOBAL uint32_t *part)
{
    uint32_t i = b * blk, end, s = 0;
    if (i < n) {
        end = n - i < blk ? n : i + blk;
        for (; i < end; i++) s += a[i];
    }
    part[b] = s;
}

PN_KFN void pn_scan_partials(PN_GLOBAL uint32_t *part, uint32_t nb, PN_GLOBAL uint32_t *total)
{
    uint32_t b, run = 0;
    for (b = 0; b < nb; b++) {
        uint32_t v = part[b];
        part[b] = run;
        run += v;
    }
    *total = run;
}

PN_KFN void pn_scan_block_apply(PN_GLOBAL uint32_t *a, uint32_t n, uint32_t blk, uint32_t b, PN_CONST uint32_t *part)
{
    uint32_t i = b * blk, end, run = part[b];
    if (i >= n) return;
    end = n - i < blk ? n : i + blk;
    for (; i < end; i++) {
        uint32_t v = a[i];
        a[i] = run;
        run += v;
    }
}

/* ---- Sort a[0 .. n) ascending, in place ------------------------------------------------
 * Heapsort: no recursion, no extra memory, O(n log n) whatever the input; a run that is
 * already ascending (the common case when atomics happened to hand out slots in order)
 * returns after one pass. */

PN_KFN void pn_sift_down(PN_GLOBAL uint32_t *a, uint32_t root, uint32_t n)
{
    for (;;) {
        uint32_t child = 2u * root + 1u, tmp;
        if (child >= n) return;
        if (child + 1u < n && a[child] < a[child + 1u]) child++;
        if (a[root] >= a[child]) return;
        tmp = a[root];
        a[root] = a[child];
        a[child] = tmp;
        root = child;
    }
}

PN_KFN void pn_sort_u32(PN_GLOBAL uint32_t *a, uint32_t n)
{
    uint32_t i, end;
    for (i = 1; i < n && a[i - 1u] <= a[i]; i++) {
    }
    if (i >= n) return;
    for (i = n / 2u; i > 0u; i--) pn_sift_down(a, i - 1u, n);
    for (end = n - 1u; end > 0u; end--) {
        uint32_t tmp = a[0];
        a[0] = a[end];
        a[end] = tmp;
        pn_sift_down(a, 0u, end);
    }
}

#endif
