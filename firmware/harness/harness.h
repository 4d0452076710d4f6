/* The cross-architecture harness: every case computes something through the public C ABI,
 * folds its status and output bits into a 64-bit hash and prints one line
 *
 *     case <name> status=<n> hash=<16 hex digits>
 *
 * The same sources are built for x86_64 (the reference), aarch64 Linux, Cortex-M4F,
 * Cortex-M7 (and riscv32imac where the tools exist); scripts/test-firmware.sh runs each build
 * and compares the case lines with the x86_64 ones: they must be identical, line for line.
 *
 * Besides the hash, a case checks what the documentation promises independently of any
 * recorded output (the expected status; interpolating schemes keep the old vertices bit for
 * bit; Möbius schemes keep cospherical meshes on their sphere; a few closed-form values),
 * so a build that is wrong in the same way everywhere still fails. */
#ifndef FW_HARNESS_H
#define FW_HARNESS_H

#include <stddef.h>
#include <stdint.h>

#include "stack.h"

/* FNV-1a, 64 bits, over a little-endian byte stream (hash.c). Doubles are hashed by their
 * bit patterns, sizes as 64-bit integers, so 32- and 64-bit targets hash the same stream. */
typedef struct fw_hash {
    uint64_t h;
} fw_hash;

void fw_hash_u32(fw_hash *h, uint32_t v);
void fw_hash_u64(fw_hash *h, uint64_t v);
void fw_hash_f64s(fw_hash *h, const double *v, size_t n);
void fw_hash_u32s(fw_hash *h, const uint32_t *v, size_t n);

/* A case runs between these two calls (runner.c). `entry` groups cases for the stack table
 * (the C entry point or operation measured, e.g. "nls_f4"); `name` is unique. Nothing may
 * be printed in between: on bare metal the stack is painted in fw_case_begin and measured
 * in fw_case_end, and printf's own stack would count. */
fw_hash *fw_case_begin_at(const char *entry, const char *name, uintptr_t sp);
#define fw_case_begin(entry, name) fw_case_begin_at((entry), (name), fw_sp())
/* Ends the case: hashes `status`, prints the case line, and a FAIL line when `status` is
 * not `expected` or a check failed. */
void fw_case_end(uint32_t status, uint32_t expected);
/* A check of the running case: `what` is reported (at fw_case_end) when `ok` is 0. */
void fw_check(int ok, const char *what);

/* A failure outside a case (the FP-environment tests): printed at once and counted. */
void fw_fail(const char *what);
/* Counted checks outside cases (fpenv.c). */
void fw_note_pass(void);

/* The suites (cases_*.c, fpenv.c). */
void fw_cases_primitives(void);
void fw_cases_curves(void);
void fw_cases_meshes(void);
void fw_cases_differential(void);
void fw_cases_stars(void);
void fw_fpenv_tests(void);

/* The exact bits of two double arrays are equal. */
int fw_same_bits(const double *a, const double *b, size_t n);

/* A harness-only status: the case's buffers did not fit the arena (arena.c). */
#define FW_STATUS_NO_MEMORY 1000u

#endif
