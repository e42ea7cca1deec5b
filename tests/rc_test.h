/* rc_test.h: a tiny test runner (cglm-style). A test is `TEST(name) { ... }`, listed in
 * main with RUN(name); checks print their operands on failure; main returns the number
 * of failed tests and prints "N passed, N failed". */
#ifndef RC_TEST_H
#define RC_TEST_H

#include <math.h>
#include <stddef.h>
#include <stdio.h>
#include <string.h>

static int rc_test_failed_checks;

#define TEST(name) static void test_##name(void)
#define RUN(name)                                                        \
  do {                                                                   \
    int before_ = rc_test_failed_checks;                                 \
    test_##name();                                                       \
    if (rc_test_failed_checks == before_) {                              \
      rc_test_passed++;                                                  \
    } else {                                                             \
      rc_test_failed++;                                                  \
      printf("FAIL %s\n", #name);                                        \
    }                                                                    \
  } while (0)
#define TEST_MAIN_BEGIN int rc_test_passed = 0, rc_test_failed = 0;
#define TEST_MAIN_END                                                    \
  printf("%d passed, %d failed\n", rc_test_passed, rc_test_failed);      \
  return rc_test_failed;

/* A table of named cases for a test program registered as one ctest per case. */
typedef struct {
  const char *name;
  void (*fn)(void);
} rc_test_case;

/* Runs the case named `only`, or every case when `only` is NULL, counting into passed and
 * failed; returns 0 when no case has that name. */
static inline int rc_run_cases(const rc_test_case *cases, size_t n, const char *only, int *passed, int *failed) {
  int found = 0;
  for (size_t i = 0; i < n; i++) {
    if (only && strcmp(only, cases[i].name) != 0) continue;
    found = 1;
    int before = rc_test_failed_checks;
    cases[i].fn();
    if (rc_test_failed_checks == before) {
      ++*passed;
    } else {
      ++*failed;
      printf("FAIL %s\n", cases[i].name);
    }
  }
  if (!found) fprintf(stderr, "no test case %s\n", only);
  return found;
}

#define CHECK(cond)                                                      \
  do {                                                                   \
    if (!(cond)) {                                                       \
      printf("  %s:%d: check failed: %s\n", __FILE__, __LINE__, #cond);  \
      rc_test_failed_checks++;                                           \
    }                                                                    \
  } while (0)

/* |a - b| <= tol, printing both values. */
#define CHECK_NEAR(a, b, tol)                                                              \
  do {                                                                                     \
    double a_ = (double)(a), b_ = (double)(b);                                             \
    if (!(fabs(a_ - b_) <= (tol))) {                                                       \
      printf("  %s:%d: %s = %.17g, %s = %.17g, |diff| %.3g > %.3g\n", __FILE__, __LINE__, #a, a_, #b, b_, \
             fabs(a_ - b_), (double)(tol));                                                \
      rc_test_failed_checks++;                                                             \
    }                                                                                      \
  } while (0)

#define CHECK_EQ_INT(a, b)                                                                 \
  do {                                                                                     \
    long long a_ = (long long)(a), b_ = (long long)(b);                                    \
    if (a_ != b_) {                                                                        \
      printf("  %s:%d: %s = %lld, expected %s = %lld\n", __FILE__, __LINE__, #a, a_, #b, b_); \
      rc_test_failed_checks++;                                                             \
    }                                                                                      \
  } while (0)

#endif
