/* pn_sort.h - integer building blocks for data-parallel ports: an exclusive prefix sum in
 * blocks and a sort of a short run of distinct ids (in place, or merged through scratch).
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

/* ---- The same with scratch tmp[0 .. n) --------------------------------------------------
 * A run that atomics filled from a few work-groups running side by side is a few ascending
 * sequences dealt into each other (under PoCL the two halves of the range, one a thread),
 * which the heapsort does not use. Each element goes to the ascending subsequence whose
 * last element is the largest below it (the fewest subsequences there can be: the longest
 * descending subsequence's length), at most PN_SORT_SEQS of them; counted, then placed
 * one after the other in tmp by the same choices again, then merged back into a. A run
 * that needs more subsequences takes the heapsort. Distinct values: one answer. */
#define PN_SORT_SEQS 4u

/* The subsequence (of *ns, last elements tail[]) that value v extends, a new one when none
 * ends below v; PN_SORT_SEQS when that would be one too many. */
PN_KFN uint32_t pn_sort_seq_of(uint32_t *tail, uint32_t *ns, uint32_t v)
{
    uint32_t j, best = PN_SORT_SEQS;
    for (j = 0; j < *ns; j++)
        if (tail[j] < v && (best == PN_SORT_SEQS || tail[j] > tail[best])) best = j;
    if (best == PN_SORT_SEQS) {
        if (*ns == PN_SORT_SEQS) return PN_SORT_SEQS;
        best = (*ns)++;
    }
    tail[best] = v;
    return best;
}

PN_KFN void pn_sort_u32_merge(PN_GLOBAL uint32_t *a, PN_GLOBAL uint32_t *tmp, uint32_t n)
{
    uint32_t tail[PN_SORT_SEQS], cnt[PN_SORT_SEQS], at[PN_SORT_SEQS], end[PN_SORT_SEQS], ns = 0u, i, j, k;
    for (i = 1; i < n && a[i - 1u] <= a[i]; i++) {
    }
    if (i >= n) return;
    for (j = 0; j < PN_SORT_SEQS; j++) cnt[j] = 0u;
    for (i = 0; i < n; i++) {
        if ((j = pn_sort_seq_of(tail, &ns, a[i])) == PN_SORT_SEQS) {
            pn_sort_u32(a, n);
            return;
        }
        cnt[j]++;
    }
    for (j = 0, k = 0; j < ns; k += cnt[j], j++) at[j] = end[j] = k;
    for (j = 0; j < ns; j++) end[j] += cnt[j];
    for (i = 0, ns = 0u; i < n; i++) {
        j = pn_sort_seq_of(tail, &ns, a[i]);
        tmp[at[j]++] = a[i];
    }
    for (j = 0, k = 0; j < ns; k += cnt[j], j++) at[j] = k;
    for (i = 0; i < n; i++) {
        uint32_t best = PN_SORT_SEQS;
        for (j = 0; j < ns; j++)
            if (at[j] < end[j] && (best == PN_SORT_SEQS || tmp[at[j]] < tmp[at[best]])) best = j;
        a[i] = tmp[at[best]++];
    }
}

#endif
