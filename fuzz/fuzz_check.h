/* fuzz_check.h - the one assertion fuzz targets use, and their byte reader. An invariant
 * violation must stop the process whatever NDEBUG says: libFuzzer saves the input as a
 * crash, and replay_main.c names the file that aborted. */
#ifndef PN_FUZZ_CHECK_H
#define PN_FUZZ_CHECK_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/* An input read byte by byte; bytes past its end read as zero. */
typedef struct fuzz_rd {
    const uint8_t *p;
    size_t n, i;
} fuzz_rd;

static inline uint32_t fuzz_byte(fuzz_rd *r) { return r->i < r->n ? r->p[r->i++] : (r->i++, 0u); }

#define FUZZ_CHECK(cond, ...)                                                       \
    do {                                                                            \
        if (!(cond)) {                                                              \
            fprintf(stderr, "%s:%d: FUZZ_CHECK failed: %s: ", __FILE__, __LINE__, #cond); \
            fprintf(stderr, __VA_ARGS__);                                           \
            fputc('\n', stderr);                                                    \
            abort();                                                                \
        }                                                                           \
    } while (0)

#endif
