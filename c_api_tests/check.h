/* The C and C++ tests' kit: checks (each failed check prints where and what, and the program exits
 * with status 1 if any failed, see CHECK_DONE) and the seeded random numbers of every C and C++ test
 * (c_api_tests/, and c_tests/harness, which seeds its generator with them). Usable from C99 and
 * C++98 on, with -pedantic. */
#ifndef PQP_TEST_CHECK_H
#define PQP_TEST_CHECK_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>

static int check_failures = 0;

/* The failures so far (also keeps check_failures used in programs that only take the generator). */
static inline int check_failure_count(void) { return check_failures; }

/* A 64-bit constant from its two 32-bit halves (C++98 has no long long literals). */
#define CHECK_U64(hi, lo) (((uint64_t)(hi) << 32) | (uint64_t)(lo))

/* SplitMix64 (Steele, Lea and Flood 2014), the same stream as the Rust tests' Rng
 * (src/test_rng.rs): the next 64 random bits of the generator whose state is *state. */
static inline uint64_t check_splitmix64(uint64_t *state)
{
    uint64_t z = (*state += CHECK_U64(0x9E3779B9, 0x7F4A7C15));
    z = (z ^ (z >> 30)) * CHECK_U64(0xBF58476D, 0x1CE4E5B9);
    z = (z ^ (z >> 27)) * CHECK_U64(0x94D049BB, 0x133111EB);
    return z ^ (z >> 31);
}

/* Uniform in [0, 1) (53 bits). */
static inline double check_unit(uint64_t *state)
{
    return (double)(check_splitmix64(state) >> 11) * (1.0 / 9007199254740992.0);
}

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
