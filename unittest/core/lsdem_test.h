/* lsdem_test.h -- a tiny check harness for the core tests (no framework needed).
 * CHECK(cond, ...) records a failure with file:line and a printf message;
 * CHECK_NEAR(a, b, tol) compares with an absolute tolerance, CHECK_REL with a relative one.
 * End main() with `return lsdem_test_summary();` which prints
 * "N passed, M failed" and returns non-zero on any failure. */
#ifndef LSDEM_TEST_H
#define LSDEM_TEST_H
#include <math.h>
#include <stdint.h>
#include <stdio.h>

#include "lsdem.h"

/* Random test inputs from the core's splitmix64 stream, same sequence on every run.
 * urand() is uniform in (0, 1], srand1() in (-1, 1]. */
static inline uint64_t *lsdem_test_rng(void)
{
  static uint64_t state = 0x5eedu;
  return &state;
}
static inline double urand(void) { return lsdem_uniform01(lsdem_test_rng()); }
static inline double srand1(void) { return 2.0 * urand() - 1.0; }

static int lsdem_test_pass_ = 0, lsdem_test_fail_ = 0;

#define CHECK(cond, ...)                                                          \
  do {                                                                            \
    if (cond) {                                                                   \
      lsdem_test_pass_++;                                                         \
    } else {                                                                      \
      lsdem_test_fail_++;                                                         \
      fprintf(stderr, "FAIL %s:%d: %s: ", __FILE__, __LINE__, #cond);             \
      fprintf(stderr, __VA_ARGS__);                                               \
      fprintf(stderr, "\n");                                                      \
    }                                                                             \
  } while (0)

#define CHECK_NEAR(a, b, tol)                                                     \
  do {                                                                            \
    double a_ = (a), b_ = (b), t_ = (tol);                                        \
    CHECK(fabs(a_ - b_) <= t_, "%s = %.17g, %s = %.17g, |diff| %.3g > %.3g", #a, a_, \
          #b, b_, fabs(a_ - b_), t_);                                             \
  } while (0)

#define CHECK_REL(a, b, rtol)                                                     \
  do {                                                                            \
    double a_ = (a), b_ = (b), t_ = (rtol) * fabs(b_);                            \
    CHECK(fabs(a_ - b_) <= t_, "%s = %.17g, %s = %.17g, rel diff %.3g > %.3g", #a, a_, \
          #b, b_, fabs(a_ - b_) / (fabs(b_) > 0 ? fabs(b_) : 1), (rtol));         \
  } while (0)

static int lsdem_test_summary(void)
{
  printf("%d passed, %d failed\n", lsdem_test_pass_, lsdem_test_fail_);
  return lsdem_test_fail_ != 0;
}
#endif
