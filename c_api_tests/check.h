/* Minimal checking for the C ABI test programs: each failed check prints where and what, and the
 * program exits with status 1 if any failed (see CHECK_DONE). Usable from C99 and C++. */
#ifndef PQP_TEST_CHECK_H
#define PQP_TEST_CHECK_H

#include <math.h>
#include <stdio.h>

static int check_failures = 0;

#define CHECK(cond)                                                                   \
    do {                                                                              \
        if (!(cond)) {                                                                \
            fprintf(stderr, "%s:%d: check failed: %s\n", __FILE__, __LINE__, #cond); \
            check_failures++;                                                         \
        }                                                                             \
    } while (0)

/* Integer equality, printing both values. */
#define CHECK_EQ(a, b)                                                                       \
    do {                                                                                     \
        long long check_a_ = (long long)(a), check_b_ = (long long)(b);                      \
        if (check_a_ != check_b_) {                                                          \
            fprintf(stderr, "%s:%d: check failed: %s == %s (%lld != %lld)\n", __FILE__,      \
                    __LINE__, #a, #b, check_a_, check_b_);                                   \
            check_failures++;                                                                \
        }                                                                                    \
    } while (0)

/* |a - b| <= tol, printing both values. */
#define CHECK_NEAR(a, b, tol)                                                                \
    do {                                                                                     \
        double check_a_ = (double)(a), check_b_ = (double)(b);                               \
        if (!(fabs(check_a_ - check_b_) <= (tol))) {                                         \
            fprintf(stderr, "%s:%d: check failed: %s ~ %s (%.17g vs %.17g)\n", __FILE__,     \
                    __LINE__, #a, #b, check_a_, check_b_);                                   \
            check_failures++;                                                                \
        }                                                                                    \
    } while (0)

/* Ends main: prints a summary and returns the exit status. */
#define CHECK_DONE(name)                                                          \
    do {                                                                          \
        if (check_failures) {                                                     \
            fprintf(stderr, "%s: %d check(s) failed\n", name, check_failures);    \
            return 1;                                                             \
        }                                                                         \
        printf("%s: all checks passed\n", name);                                  \
        return 0;                                                                 \
    } while (0)

#endif
