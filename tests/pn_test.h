/* pn_test.h - minimal test harness: CHECK records a failure and goes on, REQUIRE returns
 * from the test function. Each test program ends with pn_test_summary(), which prints the
 * plain closing line "N passed, N failed" and returns the exit code. */
#ifndef PN_TEST_H
#define PN_TEST_H

#include <stdio.h>

static int pn_test_passed_;
static int pn_test_failed_;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (cond) {                                                                   \
            pn_test_passed_++;                                                        \
        } else {                                                                      \
            pn_test_failed_++;                                                        \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond);  \
        }                                                                             \
    } while (0)

#define CHECK_MSG(cond, ...)                                                          \
    do {                                                                              \
        if (cond) {                                                                   \
            pn_test_passed_++;                                                        \
        } else {                                                                      \
            pn_test_failed_++;                                                        \
            fprintf(stderr, "%s:%d: CHECK failed: %s: ", __FILE__, __LINE__, #cond);  \
            fprintf(stderr, __VA_ARGS__);                                             \
            fputc('\n', stderr);                                                      \
        }                                                                             \
    } while (0)

#define REQUIRE(cond)                                                                 \
    do {                                                                              \
        if (!(cond)) {                                                                \
            pn_test_failed_++;                                                        \
            fprintf(stderr, "%s:%d: REQUIRE failed: %s\n", __FILE__, __LINE__, #cond);\
            return;                                                                   \
        }                                                                             \
        pn_test_passed_++;                                                            \
    } while (0)

#define RUN(fn)                                                                       \
    do {                                                                              \
        int before_ = pn_test_failed_;                                                \
        fn();                                                                         \
        fprintf(stderr, "%s %s\n", pn_test_failed_ == before_ ? "ok  " : "FAIL", #fn);\
    } while (0)

static int pn_test_summary(void)
{
    printf("%d passed, %d failed\n", pn_test_passed_, pn_test_failed_);
    return pn_test_failed_ ? 1 : 0;
}

#endif
