/* Minimal test harness for the C suites: CHECK counts, the summary line is the one CI reads. */
#ifndef NLS_CHECK_H
#define NLS_CHECK_H
#include <math.h>
#include <stdio.h>
#include <string.h>

static int nls_passed = 0;
static int nls_failed = 0;

#define CHECK(cond)                                                                 \
    do {                                                                            \
        if (cond) {                                                                 \
            nls_passed++;                                                           \
        } else {                                                                    \
            nls_failed++;                                                           \
            fprintf(stderr, "%s:%d: CHECK failed: %s\n", __FILE__, __LINE__, #cond); \
        }                                                                           \
    } while (0)

#define CHECK_STATUS(call, expected)                                                   \
    do {                                                                               \
        nls_status s_ = (call);                                                        \
        if (s_ == (expected)) {                                                        \
            nls_passed++;                                                              \
        } else {                                                                       \
            nls_failed++;                                                              \
            fprintf(stderr, "%s:%d: %s returned %u (%s), expected %u\n", __FILE__,     \
                    __LINE__, #call, (unsigned)s_, nls_status_str((uint32_t)s_),       \
                    (unsigned)(expected));                                             \
        }                                                                              \
    } while (0)

static int nls_summary(const char *suite) {
    printf("%s: %d passed, %d failed\n", suite, nls_passed, nls_failed);
    return nls_failed == 0 ? 0 : 1;
}

static double nls_dist3(const double a[3], const double b[3]) {
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}
#endif
