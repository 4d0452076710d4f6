/* The floating-point-environment guard, tested on each architecture's own control register
 * (ffi/src/guard.rs; docs/firmware.md, "Floating-point environment"):
 *
 *  1. In the default environment a few calls (F4, a Möbius mesh level, a curve, an F4 that
 *     overflows inside) give the reference statuses and bits.
 *  2. Each mode that changes f64 results is set in turn — flush-to-zero, default-NaN (Arm),
 *     denormals-are-zero (x86), each directed rounding mode — and the calls are repeated:
 *     where f64 arithmetic runs on the FPU they must return NLS_STATUS_FP_ENVIRONMENT; on a
 *     Cortex-M4F, whose FPU is single precision only (f64 in software, which the register
 *     does not reach), they must succeed with the reference bits. Either way the register
 *     must be as the host set it after each call.
 *  3. Exception traps (x86 MXCSR masks, aarch64 FPCR trap enables): unmasked, the calls must
 *     give the reference statuses and bits, and the register must come back as the host set
 *     it. Cores whose trap-enable bits read as zero (most aarch64 cores, and QEMU) cannot
 *     unmask anything: that is reported, and the register is checked unchanged.
 *  4. Back in the default environment the calls give the reference bits again.
 *
 * Lines start with "fpenv": they differ between architectures by design and are not part of
 * the cross-architecture comparison. */
#include <stdio.h>
#include <string.h>

#include "arena.h"
#include "calls.h"
#include "harness.h"
#include "meshes.h"
#include "nlsubdiv.h"

#if defined(__x86_64__)
#include <xmmintrin.h>
#define FW_FP_REGISTER "MXCSR"
typedef uint32_t fpreg;
static fpreg fp_read(void) { return _mm_getcsr(); }
static void fp_write(fpreg v) { _mm_setcsr(v); }
static const struct mode {
    const char *name;
    fpreg bits;
} MODES[] = {{"flush-to-zero (FTZ)", 1u << 15}, {"denormals-are-zero (DAZ)", 1u << 6},
             {"round down", 1u << 13},         {"round up", 2u << 13},
             {"round toward zero", 3u << 13}};
#define MODES_REFUSED 1
/* the sticky exception flags, bits 0-5 */
#define FLAGS ((fpreg)0x3F)
/* clearing the invalid, divide-by-zero and overflow masks unmasks those traps */
#define TRAP_UNMASK(v) ((v) & ~(fpreg)((1u << 7) | (1u << 9) | (1u << 10)))
#define TRAPS_ACTIVE(v) (((v) & ((1u << 7) | (1u << 9) | (1u << 10))) == 0)

#elif defined(__aarch64__)
#define FW_FP_REGISTER "FPCR"
typedef uint64_t fpreg;
static fpreg fp_read(void) {
    fpreg v;
    __asm volatile("mrs %0, fpcr" : "=r"(v));
    return v;
}
static void fp_write(fpreg v) { __asm volatile("msr fpcr, %0" : : "r"(v)); }
static const struct mode {
    const char *name;
    fpreg bits;
} MODES[] = {{"flush-to-zero (FZ)", 1u << 24}, {"default NaN (DN)", 1u << 25},
             {"round toward +inf (RP)", 1u << 22}, {"round toward -inf (RM)", 2u << 22},
             {"round toward zero (RZ)", 3u << 22}};
#define MODES_REFUSED 1
/* the flags live in FPSR */
#define FLAGS ((fpreg)0)
/* IOE, DZE, OFE set: those exceptions trap (where the core implements trapping) */
#define TRAP_UNMASK(v) ((v) | (fpreg)((1u << 8) | (1u << 9) | (1u << 10)))
#define TRAPS_ACTIVE(v) (((v) & ((1u << 8) | (1u << 9) | (1u << 10))) != 0)

#elif defined(__arm__) && defined(__ARM_FP)
#define FW_FP_REGISTER "FPSCR"
typedef uint32_t fpreg;
static fpreg fp_read(void) {
    fpreg v;
    __asm volatile("vmrs %0, fpscr" : "=r"(v));
    return v;
}
static void fp_write(fpreg v) { __asm volatile("vmsr fpscr, %0" : : "r"(v)); }
static const struct mode {
    const char *name;
    fpreg bits;
} MODES[] = {{"flush-to-zero (FZ)", 1u << 24}, {"default NaN (DN)", 1u << 25},
             {"round toward +inf (RP)", 1u << 22}, {"round toward -inf (RM)", 2u << 22},
             {"round toward zero (RZ)", 3u << 22}};
/* bit 3 of __ARM_FP: the FPU computes in double precision (Cortex-M7 with -mfpu=fpv5-d16);
 * without it (Cortex-M4F) f64 runs in software and FPSCR does not reach it */
#define MODES_REFUSED ((__ARM_FP & 8) != 0)
/* the condition flags N, Z, C, V and the sticky exception flags IDC, IXC, UFC, OFC, DZC, IOC */
#define FLAGS ((fpreg)0xF000009Fu)
/* M-profile FPSCR has no trap enables (the bits are reserved, RES0) */

#endif

#if defined(__x86_64__) || defined(__aarch64__) || (defined(__arm__) && defined(__ARM_FP))

/* What the calls returned: one status and hash per call. */
typedef struct outcome {
    uint32_t status[4];
    uint64_t hash[4];
} outcome;

static void calls(outcome *o) {
    static const double A[3] = {0.1, 0.2, 0.3}, B[3] = {1.1, -0.4, 0.25}, C[3] = {2.3, 0.9, -0.6},
                        D[3] = {3.2, -0.1, 0.45};
    /* coordinates near the top of the range: F4's intermediate products overflow */
    static const double BA[3] = {1e308, -1e308, 1e308}, BB[3] = {-1e308, 1e308, 0}, BC[3] = {1e308, 1e308, -1e308},
                        BD[3] = {-1e308, -1e308, 1e308};
    double out[3];
    fw_mesh_result m;
    fw_curve_result c;
    fw_hash h;
    memset(o, 0, sizeof *o);

    h.h = 0;
    memset(out, 0, sizeof out);
    o->status[0] = nls_f4(A, B, C, D, out);
    fw_hash_f64s(&h, out, 3);
    o->hash[0] = h.h;

    h.h = 0;
    fw_arena_reset();
    o->status[1] = fw_mesh_subdivide(NLS_SCHEME_CATMULL_CLARK, NLS_SUBDIVIDE_MOBIUS, 1, &fw_meshes[6].mesh, &m);
    if (o->status[1] == NLS_STATUS_OK) fw_hash_f64s(&h, m.positions, 3 * m.vertex_count);
    o->hash[1] = h.h;

    h.h = 0;
    fw_arena_reset();
    o->status[2] = fw_curve_subdivide(NLS_CURVE_MOBIUS_APPROXIMATING, fw_curve_closed, 6, 1, 2, &c);
    if (o->status[2] == NLS_STATUS_OK) fw_hash_f64s(&h, c.points, 3 * c.count);
    o->hash[2] = h.h;

    h.h = 0;
    memset(out, 0, sizeof out);
    o->status[3] = nls_f4(BA, BB, BC, BD, out);
    fw_hash_f64s(&h, out, 3);
    o->hash[3] = h.h;
}

static const char *const CALL_NAMES[4] = {"nls_f4", "Möbius Catmull–Clark level", "Möbius curve", "nls_f4 at 1e308"};

static int same(const outcome *a, const outcome *b) { return memcmp(a, b, sizeof *a) == 0; }

static void expect(int ok, const char *what) {
    if (ok) {
        fw_note_pass();
        printf("fpenv ok   %s\n", what);
    } else {
        char line[192];
        snprintf(line, sizeof line, "fpenv: %.160s", what);
        fw_fail(line);
    }
}

void fw_fpenv_tests(void) {
    outcome ref, got;
    fpreg saved = fp_read(), set, after;
    size_t k, i;
    char what[160];

    fw_meshes_init();
    printf("fpenv register %s = 0x%08llx; modes that change f64 results are %s\n", FW_FP_REGISTER,
           (unsigned long long)saved,
           MODES_REFUSED ? "refused (NLS_STATUS_FP_ENVIRONMENT)"
                         : "accepted: f64 runs in software here, the register does not reach it");
    calls(&ref);
    for (i = 0; i < 3; i++) {
        snprintf(what, sizeof what, "default environment: %s succeeds", CALL_NAMES[i]);
        expect(ref.status[i] == NLS_STATUS_OK, what);
    }

    for (k = 0; k < sizeof MODES / sizeof MODES[0]; k++) {
        fp_write(saved | MODES[k].bits);
        set = fp_read();
        calls(&got);
        after = fp_read();
        fp_write(saved);
        if ((set & MODES[k].bits) != MODES[k].bits) {
            snprintf(what, sizeof what, "%s: the mode can be set", MODES[k].name);
            expect(0, what);
            continue;
        }
        if (MODES_REFUSED) {
            for (i = 0; i < 4; i++) {
                snprintf(what, sizeof what, "%s: %s is refused with NLS_STATUS_FP_ENVIRONMENT (got %u)",
                         MODES[k].name, CALL_NAMES[i], (unsigned)got.status[i]);
                expect(got.status[i] == NLS_STATUS_FP_ENVIRONMENT, what);
            }
        } else {
            snprintf(what, sizeof what, "%s: every call gives the default environment's status and bits",
                     MODES[k].name);
            expect(same(&got, &ref), what);
        }
        snprintf(what, sizeof what, "%s: the register's modes are as the host set them after the calls",
                 MODES[k].name);
        expect((after & ~FLAGS) == (set & ~FLAGS), what);
    }

#ifdef TRAP_UNMASK
    fp_write(TRAP_UNMASK(saved));
    set = fp_read();
    if (!TRAPS_ACTIVE(set)) {
        fp_write(saved);
        printf("fpenv note %s trap enables read back as zero on this core: nothing can be unmasked\n",
               FW_FP_REGISTER);
        calls(&got);
        expect(same(&got, &ref) && (fp_read() & ~FLAGS) == (saved & ~FLAGS),
               "traps: calls give the reference bits and leave the register's modes unchanged");
    } else {
        calls(&got);
        after = fp_read();
        fp_write(saved);
        expect(same(&got, &ref), "unmasked traps: every call gives the default environment's status and bits");
        expect(after == set, "unmasked traps: the host's register (traps, flags) is restored after the calls");
    }
#else
    printf("fpenv note %s has no trap enables on this core (M-profile: reserved bits)\n", FW_FP_REGISTER);
#endif

    calls(&got);
    expect(same(&got, &ref) && (fp_read() & ~FLAGS) == (saved & ~FLAGS),
           "restored default environment: the calls give the reference bits again");
}

#else

void fw_fpenv_tests(void) {
    printf("fpenv note no floating-point control register on this target (f64 in software)\n");
}

#endif
