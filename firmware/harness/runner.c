/* Runs every suite and prints one line per case, the stack figures on bare metal, and the
 * closing line "harness: N cases, M failed" (the exit status is M != 0). */
#include <stdio.h>
#include <string.h>

#include "arena.h"
#include "harness.h"
#include "nlsubdiv.h"
#include "stack.h"

static fw_hash current;
static const char *current_entry, *current_name;
static const char *first_check_failure;
static unsigned check_failures;
static unsigned cases, failures, passes;

fw_hash *fw_case_begin_at(const char *entry, const char *name, uintptr_t sp) {
    current.h = 0xCBF29CE484222325ull; /* FNV-1a offset basis */
    current_entry = entry;
    current_name = name;
    first_check_failure = NULL;
    check_failures = 0;
    fw_arena_reset();
    fw_stack_paint(sp);
    return &current;
}

void fw_check(int ok, const char *what) {
    if (ok) return;
    if (first_check_failure == NULL) first_check_failure = what;
    check_failures++;
}

void fw_case_end(uint32_t status, uint32_t expected) {
    long stack = fw_stack_used();
    fw_hash_u32(&current, status);
    cases++;
    printf("case %s status=%u hash=%016llx\n", current_name, (unsigned)status, (unsigned long long)current.h);
    if (stack != -2) printf("stack %s\t%s\t%ld\n", current_entry, current_name, stack);
    if (stack == -1) {
        printf("FAIL %s: the stack overflowed its painted area\n", current_name);
        failures++;
    }
    if (status != expected) {
        printf("FAIL %s: status %u (%s), expected %u (%s)\n", current_name, (unsigned)status,
               nls_status_str(status), (unsigned)expected, nls_status_str(expected));
        failures++;
    } else if (check_failures > 0) {
        printf("FAIL %s: %s (%u failed checks)\n", current_name, first_check_failure, check_failures);
        failures++;
    } else {
        passes++;
    }
}

void fw_fail(const char *what) {
    printf("FAIL %s\n", what);
    failures++;
}

void fw_note_pass(void) { passes++; }

static const char *target_name(void) {
#if defined(__x86_64__)
    return "x86_64";
#elif defined(__aarch64__)
    return "aarch64";
#elif defined(__arm__) && defined(__ARM_FP) && (__ARM_FP & 8)
    return "arm (double-precision FPU)";
#elif defined(__arm__) && defined(__ARM_FP)
    return "arm (single-precision FPU: f64 in software)";
#elif defined(__riscv)
    return "riscv";
#else
    return "unknown";
#endif
}

int main(void) {
    printf("harness: nlsubdiv %u.%u.%u on %s, valence and face-size caps %u, %u\n",
           (unsigned)(nls_version() >> 16), (unsigned)((nls_version() >> 8) & 0xFF),
           (unsigned)(nls_version() & 0xFF), target_name(), (unsigned)nls_max_valence(),
           (unsigned)nls_max_face_size());
    if (nls_version() != ((NLS_VERSION_MAJOR << 16) | (NLS_VERSION_MINOR << 8) | NLS_VERSION_PATCH))
        fw_fail("the library's version is not the header's");
    fw_cases_primitives();
    fw_cases_curves();
    fw_cases_meshes();
    fw_cases_differential();
    fw_cases_stars();
    fw_fpenv_tests();
    printf("harness: %u cases, %u passed, %u failed\n", cases, passes, failures);
    return failures != 0;
}
