/*
 * fpenv.h - IEEE arithmetic: the build refuses -ffast-math, and every entry
 * point computes in IEEE defaults whatever the caller's floating-point mode
 * (MCSTAT_IEEE_SCOPE).
 * Included through internal.h; nothing here is exported.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_FPENV_H
#define MCSTAT_FPENV_H

/* The algorithms rely on IEEE arithmetic as written, so the library refuses
 * to be built without it rather than give wrong numbers quietly (built with
 * -ffast-math, every variance came out 0):
 * - compensated sums and the double-double helpers below are exact only if
 *   the compiler does not reassociate them (-fassociative-math turns
 *   (a + b) - a into b);
 * - NaN and infinity checks on the caller's data are how bad input gets its
 *   status code (-ffinite-math-only deletes them);
 * - divisions are correctly rounded (-freciprocal-math is not).
 * Code that includes mcstat.h may use any flags: this is libmcstat's own. */
#if defined(__FAST_MATH__) || (defined(__FINITE_MATH_ONLY__) && __FINITE_MATH_ONLY__) || \
    defined(__ASSOCIATIVE_MATH__) || defined(__RECIPROCAL_MATH__)
#error "libmcstat must be compiled with IEEE floating-point semantics: remove -ffast-math / -Ofast (or -ffinite-math-only, -fassociative-math, -freciprocal-math, -funsafe-math-optimizations) from the flags for libmcstat; its compensated sums, double-double arithmetic and NaN checks depend on them (see src/fpenv.h)"
#endif

/* ---- the caller's floating-point environment ------------------------------
 * No result may depend on it.  A renderer may run with subnormals flushed to
 * zero and read as zero (x86 MXCSR FTZ/DAZ, ARM FPCR.FZ: what -ffast-math's
 * crtfastmath.o sets at start-up), another rounding direction or trapping
 * exceptions; the scaled moments, the double-double helpers and the tails
 * that underflow gracefully all assume IEEE defaults.  Every public function
 * that computes in floating point starts with MCSTAT_IEEE_SCOPE(): inside, the
 * defaults (round to nearest, subnormals kept, exceptions masked); on return,
 * by any path, the caller's mode again (exception flags raised inside are not
 * kept).  In the default environment the cost is one register read.  Threads
 * started inside inherit the defaults. */
#if defined(__x86_64__) || (defined(__i386__) && defined(__SSE2__))
#include <fenv.h>
#include <xmmintrin.h>
typedef struct {
    unsigned csr; /* MXCSR */
    int round;    /* fegetround(): the x87 control word's, which printf reads */
} mcstat__fpenv;
/* MXCSR: FTZ (bit 15), rounding (13-14), exception masks (7-12), DAZ (6);
 * the default is 0x1f80 plus whatever exception flags (0-5) are set.
 * fesetround() sets the rounding of SSE and x87 together, so a caller's
 * rounding direction shows in MXCSR. */
static inline mcstat__fpenv mcstat__fpenv_enter(void)
{
    mcstat__fpenv e = {_mm_getcsr(), FE_TONEAREST};
    if (__builtin_expect((e.csr & ~0x3fu) != 0x1f80u, 0)) {
        e.round = fegetround();
        if (e.round != FE_TONEAREST)
            fesetround(FE_TONEAREST);
        _mm_setcsr((e.csr & 0x3fu) | 0x1f80u);
    }
    return e;
}
static inline void mcstat__fpenv_leave(const mcstat__fpenv *e)
{
    if (__builtin_expect((e->csr & ~0x3fu) != 0x1f80u, 0)) {
        if (e->round != FE_TONEAREST)
            fesetround(e->round);
        _mm_setcsr(e->csr);
    }
}
#elif defined(__aarch64__)
typedef uint64_t mcstat__fpenv;
/* FPCR: rounding (bits 22-23), FZ (24), DN (25), trap enables (8-12, 15) */
#define MCSTAT__FPCR_MODES 0x03c09f00ull
static inline mcstat__fpenv mcstat__fpenv_enter(void)
{
    uint64_t c;
    __asm__ __volatile__("mrs %0, fpcr" : "=r"(c) : : "memory");
    if (__builtin_expect((c & MCSTAT__FPCR_MODES) != 0, 0)) {
        uint64_t d = c & ~MCSTAT__FPCR_MODES;
        __asm__ __volatile__("msr fpcr, %0" : : "r"(d) : "memory");
    }
    return c;
}
static inline void mcstat__fpenv_leave(const mcstat__fpenv *c)
{
    if (__builtin_expect((*c & MCSTAT__FPCR_MODES) != 0, 0))
        __asm__ __volatile__("msr fpcr, %0" : : "r"(*c) : "memory");
}
#else
/* elsewhere the rounding direction only (no portable flush-to-zero control) */
#include <fenv.h>
typedef int mcstat__fpenv;
static inline mcstat__fpenv mcstat__fpenv_enter(void)
{
    int r = fegetround();
    if (r != FE_TONEAREST)
        fesetround(FE_TONEAREST);
    return r;
}
static inline void mcstat__fpenv_leave(const mcstat__fpenv *r)
{
    if (*r != FE_TONEAREST)
        fesetround(*r);
}
#endif
#define MCSTAT_IEEE_SCOPE() \
    __attribute__((cleanup(mcstat__fpenv_leave), unused)) const mcstat__fpenv mcstat__fpenv_saved = mcstat__fpenv_enter()

#endif /* MCSTAT_FPENV_H */
