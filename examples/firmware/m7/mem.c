/* mem.c - memcpy and memset, the only C library functions the example (and the penumbra
 * core, tests/check_symbols.cmake) may call. A firmware project has its own, usually
 * faster; the example links with -nostdlib so that anything else fails to link.
 * Built with -fno-builtin -fno-tree-loop-distribute-patterns, so that GCC does not turn
 * these loops back into calls to themselves. */
#include <stddef.h>
#include <string.h>

void *memcpy(void *restrict dst, const void *restrict src, size_t n)
{
    unsigned char *d = (unsigned char *)dst;
    const unsigned char *s = (const unsigned char *)src;
    while (n-- != 0u)
        *d++ = *s++;
    return dst;
}

void *memset(void *dst, int c, size_t n)
{
    unsigned char *d = (unsigned char *)dst;
    while (n-- != 0u)
        *d++ = (unsigned char)c;
    return dst;
}
