/* pn_prims.cl - OpenCL entry points of the port primitives that are kernels on a device
 * (kernels/pn_sort.h): the exclusive prefix sum in blocks, and the sort of (key, value)
 * pairs by key: a histogram of keys (atomic increments), its prefix sum, every pair into
 * the next slot of its key (atomic cursors: any order), then each key's run of values
 * sorted, which is the one ascending (key, value) order. Offsets are bytes into the arena
 * buffer A; no algorithm is named here. */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_sort.h"

#define PN_AT(o) ((__global uint *)(A + (o)))

/* Scan of a[0 .. n) at o_a; nb block partials at o_part. */
__kernel void pn_k_scan_sum(__global uchar *A, ulong o_a, uint n, uint blk, ulong o_part, uint nb)
{
    uint b = (uint)get_global_id(0);
    if (b >= nb) return;
    pn_scan_block_sum(PN_AT(o_a), n, blk, b, PN_AT(o_part));
}

__kernel void pn_k_scan_partials(__global uchar *A, ulong o_a, uint n, ulong o_part, uint nb)
{
    if (get_global_id(0) != 0 || nb == 0u) return;
    pn_scan_partials(PN_AT(o_part), nb, PN_AT(o_a) + n);
}

__kernel void pn_k_scan_apply(__global uchar *A, ulong o_a, uint n, uint blk, ulong o_part, uint nb)
{
    uint b = (uint)get_global_id(0);
    if (b >= nb) return;
    pn_scan_block_apply(PN_AT(o_a), n, blk, b, PN_AT(o_part));
}

/* Pairs (key, value) at o_pairs, n of them: one more pair per key into the counts at
 * o_cur (zeroed beforehand). */
__kernel void pn_k_pairs_hist(__global uchar *A, ulong o_pairs, uint n, ulong o_cur)
{
    uint p = (uint)get_global_id(0);
    if (p >= n) return;
    atomic_inc(PN_AT(o_cur) + PN_AT(o_pairs)[(size_t)p * 2u]);
}

/* Each pair's value into the next free slot of its key (o_cur: the keys' starts). */
__kernel void pn_k_pairs_fill(__global uchar *A, ulong o_pairs, uint n, ulong o_cur, ulong o_values)
{
    uint p = (uint)get_global_id(0), slot;
    if (p >= n) return;
    slot = atomic_inc(PN_AT(o_cur) + PN_AT(o_pairs)[(size_t)p * 2u]);
    PN_AT(o_values)[slot] = PN_AT(o_pairs)[(size_t)p * 2u + 1u];
}

/* Key c: its run of values, offsets[c] .. offsets[c + 1], sorted ascending. */
__kernel void pn_k_pairs_sort_runs(__global uchar *A, ulong o_offsets, uint keys, ulong o_values)
{
    uint c = (uint)get_global_id(0), e0;
    if (c >= keys) return;
    e0 = PN_AT(o_offsets)[c];
    pn_sort_u32(PN_AT(o_values) + e0, PN_AT(o_offsets)[c + 1u] - e0);
}

/* The same with scratch: key c's run sorted with the words at the same offsets from
 * o_scratch (pn_sort_u32_merge; the sort of pairs passes the pairs' own buffer, dead once
 * every value is in its key's run). */
__kernel void pn_k_pairs_merge_runs(__global uchar *A, ulong o_offsets, uint keys, ulong o_values, ulong o_scratch)
{
    uint c = (uint)get_global_id(0), e0;
    if (c >= keys) return;
    e0 = PN_AT(o_offsets)[c];
    pn_sort_u32_merge(PN_AT(o_values) + e0, PN_AT(o_scratch) + e0, PN_AT(o_offsets)[c + 1u] - e0);
}
