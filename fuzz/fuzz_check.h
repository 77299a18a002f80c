/* fuzz_check.h - the one assertion fuzz targets use. An invariant violation must stop the
 * process whatever NDEBUG says: libFuzzer saves the input as a crash, and replay_main.c
 * names the file that aborted. */
#ifndef PN_FUZZ_CHECK_H
#define PN_FUZZ_CHECK_H

#include <stdio.h>
#include <stdlib.h>

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
