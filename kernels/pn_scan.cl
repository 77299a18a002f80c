/* pn_scan.cl - OpenCL entry points of the exclusive prefix sum (kernels/pn_sort.h) over
 * a[0 .. n) at byte offset o_a of the arena, total to a[n]; the nb block partials live at
 * o_part, in a pool the caller knows to be free at that moment. */
#pragma OPENCL FP_CONTRACT OFF
#include "pn_sort.h"

__kernel void pn_k_scan_sum(__global uchar *A, ulong o_a, uint n, uint blk, ulong o_part, uint nb)
{
    uint b = (uint)get_global_id(0);
    if (b >= nb) return;
    pn_scan_block_sum((__global const uint *)(A + o_a), n, blk, b, (__global uint *)(A + o_part));
}

__kernel void pn_k_scan_partials(__global uchar *A, ulong o_a, uint n, ulong o_part, uint nb)
{
    if (get_global_id(0) != 0 || nb == 0u) return;
    pn_scan_partials((__global uint *)(A + o_part), nb, (__global uint *)(A + o_a) + n);
}

__kernel void pn_k_scan_apply(__global uchar *A, ulong o_a, uint n, uint blk, ulong o_part, uint nb)
{
    uint b = (uint)get_global_id(0);
    if (b >= nb) return;
    pn_scan_block_apply((__global uint *)(A + o_a), n, blk, b, (__global const uint *)(A + o_part));
}
