/* Minimal test harness for the C suites: CHECK counts, the summary line is the one CI reads.
 *
 * Coverage of the bad-input catalogue is measured, not typed: every status a CHECK_STATUS
 * verified (the call returned exactly the expected status) is counted, and nls_summary
 * appends one line per status, "<suite> <code> <count> <message of nls_status_str>", to the
 * file named by the environment variable NLS_STATUS_LOG when it is set (scripts/dashboard.py
 * reads it; docs/bad-input-catalogue.md). */
#ifndef NLS_CHECK_H
#define NLS_CHECK_H
#include "nlsubdiv.h" /* nls_status_str, used by nls_summary */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int nls_passed = 0;
static int nls_failed = 0;
/* How many CHECK_STATUS verified each status code (codes are small and never reused). */
#define NLS_STATUS_SLOTS 64
static long nls_status_verified[NLS_STATUS_SLOTS];

static void nls_record_status(unsigned code) {
    if (code < NLS_STATUS_SLOTS) nls_status_verified[code]++;
}

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
            nls_record_status((unsigned)s_);                                           \
        } else {                                                                       \
            nls_failed++;                                                              \
            fprintf(stderr, "%s:%d: %s returned %u (%s), expected %u\n", __FILE__,     \
                    __LINE__, #call, (unsigned)s_, nls_status_str((uint32_t)s_),       \
                    (unsigned)(expected));                                             \
        }                                                                              \
    } while (0)

static int nls_summary(const char *suite) {
    const char *log = getenv("NLS_STATUS_LOG");
    if (log != NULL && log[0] != '\0') {
        FILE *f = fopen(log, "a");
        unsigned c;
        if (f == NULL) {
            fprintf(stderr, "%s: cannot append to NLS_STATUS_LOG=%s\n", suite, log);
            nls_failed++;
        } else {
            for (c = 0; c < NLS_STATUS_SLOTS; c++) {
                if (nls_status_verified[c] > 0) {
                    fprintf(f, "%s %u %ld %s\n", suite, c, nls_status_verified[c], nls_status_str(c));
                }
            }
            fclose(f);
        }
    }
    printf("%s: %d passed, %d failed\n", suite, nls_passed, nls_failed);
    return nls_failed == 0 ? 0 : 1;
}

static inline double nls_dist3(const double a[3], const double b[3]) {
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}
#endif
