/*
 * ftz_daz.c - LD_PRELOAD shim: the process runs with subnormals flushed to
 * zero (FTZ) and read as zero (DAZ), as a renderer built with -ffast-math
 * (crtfastmath.o) or one that sets MXCSR for speed does.  make
 * portability-test runs the C tests under it: libmcstat must give the same
 * answers, or a clear status, never NaN or garbage with MCSTAT_OK.
 * Threads the process creates inherit the mode.
 */
#if defined(__x86_64__) || defined(__i386__)
#include <xmmintrin.h>

__attribute__((constructor)) static void mcstat_ftz_daz_on(void)
{
    _mm_setcsr(_mm_getcsr() | 0x8000 /* FTZ, bit 15 */ | 0x0040 /* DAZ, bit 6 */);
}
#elif defined(__aarch64__)
#include <stdint.h>

__attribute__((constructor)) static void mcstat_ftz_daz_on(void)
{
    /* FPCR.FZ (bit 24): both flushing and reading subnormals as zero */
    uint64_t fpcr;
    __asm__ volatile("mrs %0, fpcr" : "=r"(fpcr));
    fpcr |= 1ull << 24;
    __asm__ volatile("msr fpcr, %0" : : "r"(fpcr));
}
#else
#error "no flush-to-zero control known for this architecture"
#endif
