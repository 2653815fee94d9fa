/*
 * mcstat/base.h - the conventions every family shares: the export and
 * attribute macros, statuses, alternatives, decisions, options that grow.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_BASE_FAMILY_H
#define MCSTAT_BASE_FAMILY_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* mcstat_result's anonymous unions of anonymous structs are standard C11,
 * an extension in C99 and C++: marked, so that callers building with
 * -Wpedantic get no warning (tests/c/check_header.sh). */
#if defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_ANONYMOUS __extension__
#else
#  define MCSTAT_ANONYMOUS
#endif

#if defined(_WIN32) && defined(MCSTAT_SHARED_BUILD)
#  define MCSTAT_API __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_API __attribute__((visibility("default")))
#else
#  define MCSTAT_API
#endif
/* MCSTAT_NODISCARD marks the calls that return a status: the compiler warns
 * when one is ignored ([[nodiscard]] in C23 and C++17, where a (void) cast
 * says it was meant; Clang's warn_unused_result before them; nothing for
 * GCC before C23, whose attribute a (void) cast cannot silence).  Define
 * MCSTAT_NO_NODISCARD before including this header to turn it off. */
#if defined(MCSTAT_NO_NODISCARD)
#  define MCSTAT_NODISCARD
#elif defined(__cplusplus) && __cplusplus >= 201703L
#  define MCSTAT_NODISCARD [[nodiscard]]
#elif !defined(__cplusplus) && defined(__STDC_VERSION__) && __STDC_VERSION__ > 201710L
#  define MCSTAT_NODISCARD [[nodiscard]]
#elif defined(__clang__)
#  define MCSTAT_NODISCARD __attribute__((warn_unused_result))
#else
#  define MCSTAT_NODISCARD
#endif
/* MCSTAT_DEPRECATED marks a name this release replaced (mcstat/deprecated.h): it
 * still links and gives the same results, and the compiler names the
 * replacement.  Define MCSTAT_DISABLE_DEPRECATE_WARNINGS before including
 * this header to silence the warnings. */
#if defined(MCSTAT_DISABLE_DEPRECATE_WARNINGS)
#  define MCSTAT_DEPRECATED(replacement)
#elif defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_DEPRECATED(replacement) __attribute__((deprecated("use " replacement)))
#elif defined(_MSC_VER)
#  define MCSTAT_DEPRECATED(replacement) __declspec(deprecated("use " replacement))
#else
#  define MCSTAT_DEPRECATED(replacement)
#endif
/* MCSTAT_DEPRECATED_ENUMERATOR: the same for a renamed constant, where the
 * compiler can mark an enumerator (GCC 6, Clang); elsewhere it is silent. */
#if defined(MCSTAT_DISABLE_DEPRECATE_WARNINGS)
#  define MCSTAT_DEPRECATED_ENUMERATOR(replacement)
#elif (defined(__GNUC__) && __GNUC__ >= 6) || defined(__clang__)
#  define MCSTAT_DEPRECATED_ENUMERATOR(replacement) __attribute__((deprecated("use " replacement)))
#else
#  define MCSTAT_DEPRECATED_ENUMERATOR(replacement)
#endif
/* MCSTAT_EXPERIMENTAL_API marks the calls of the experimental families
 * (mcstat/power.h, mcstat/diagnostics.h, mcstat/gof.h): their names and
 * options may still change.  A program opts in by defining
 * MCSTAT_EXPERIMENTAL before including mcstat.h (or the family's header),
 * as zstd's ZSTD_STATIC_LINKING_ONLY.  Without it they still compile in
 * this release, each use warning with the opt-in; from 0.4 mcstat.h
 * declares them only with it.  MCSTAT_NO_EXPERIMENTAL leaves them out of
 * mcstat.h altogether (any use is then a compile error). */
#if defined(MCSTAT_EXPERIMENTAL) || defined(MCSTAT_DISABLE_DEPRECATE_WARNINGS)
#  define MCSTAT_EXPERIMENTAL_API MCSTAT_API
#elif defined(__GNUC__) || defined(__clang__)
#  define MCSTAT_EXPERIMENTAL_API                                                                                   \
      __attribute__((deprecated("experimental: #define MCSTAT_EXPERIMENTAL before including mcstat.h"))) MCSTAT_API
#elif defined(_MSC_VER)
#  define MCSTAT_EXPERIMENTAL_API                                                                                   \
      __declspec(deprecated("experimental: #define MCSTAT_EXPERIMENTAL before including mcstat.h")) MCSTAT_API
#else
#  define MCSTAT_EXPERIMENTAL_API MCSTAT_API
#endif

/* ======================================================================== */
/* 1. Conventions.                                                        */
/* Statuses (every fallible call returns one), alternatives (every test     */
/* takes one), and how the options structs grow and the results do not.     */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Compatibility of options and results.                                    */
/* Options structs grow.  Each starts with `uint32_t size`, which its        */
/* initialiser sets to the struct's sizeof as the caller compiled it; new    */
/* fields are only appended.  The library accepts the size of every release */
/* (MCSTAT_<NAME>_OPTIONS_SIZE_<release>), reads only that many bytes and    */
/* gives the fields the caller's version lacks their defaults: a program     */
/* built against an older header runs unchanged against a newer library.    */
/* Any other size is MCSTAT_EINVAL (a header newer than the library, or a   */
/* struct cut short).  mcstat_<name>_options_init(opt) is a macro passing   */
/* sizeof *opt to mcstat_<name>_options_init_size(opt, size), which writes  */
/* only `size` bytes; FFI callers call the latter with their struct's size. */
/*                                                                           */
/* Results do not grow.  mcstat_result (and mcstat_diagnostics) are written */
/* in full by the library, in arrays by the row-wise calls, and carry no    */
/* size field: 0.1.0 binaries allocate them without one, so the library     */
/* could not trust it.  Their size is fixed for this SOVERSION; new outputs */
/* use the per-test storage (the named unions in mcstat_result), or a new   */
/* function with its own struct.                                             */
/* ------------------------------------------------------------------------ */

/* ------------------------------------------------------------------------ */
/* Status codes.                                                             */
/* ------------------------------------------------------------------------ */
enum mcstat_status {
    MCSTAT_OK = 0,
    MCSTAT_EINVAL = 1,      /* invalid argument: NULL, bad enum, alpha outside (0,1), ... */
    MCSTAT_ETOOFEW = 2,     /* too few observations (fewer than 2 per sample) */
    MCSTAT_ENONFINITE = 3,  /* the data contain NaN or +-Inf */
    MCSTAT_EDEGENERATE = 4, /* the data have (essentially) zero spread */
    MCSTAT_ENOMEM = 5,      /* out of memory */
    MCSTAT_ENUMERIC = 6,    /* a numerical method failed to converge */
    MCSTAT_EBUFSIZE = 7,    /* the caller's buffer is too small */
    MCSTAT_ECORRUPT = 8,    /* serialized bytes are corrupt, truncated or of an unknown version */
    MCSTAT_ETOOBIG = 9,     /* the sizes are too large for the requested method (e.g. an exact
                               K-S p-value whose lattice would not fit): choose another method;
                               also an observation count that would pass 2^64 - 1 */
    MCSTAT_ECALLBACK = 10,  /* a caller's callback failed or returned invalid values (mcstat/check.h) */
    MCSTAT_EHEAVYTAIL = 11  /* the data's tails are too heavy for the method within the samples
                               seen (mcstat/sequential.h: a sequential test never allowed to decide) */
};

/* A sentence describing status (static storage; never NULL). */
MCSTAT_API const char *mcstat_strerror(int status);

/* Why the last call on this thread refused its arguments, naming the
 * argument and its value ("options.cells must be 0 (automatic) or
 * 2..1048576, got 1"), or "" when it gave no reason.  Functions that give
 * reasons clear it when they start, so after one of them it belongs to
 * that call: in 0.3.0 the renderer checks (mcstat_check_bsdf, _emitter,
 * _warp, _phase, _medium, mcstat_check_work_size), for every MCSTAT_EINVAL
 * and MCSTAT_ETOOBIG they return, and the t and variance tests
 * (mcstat_t_test_*, mcstat_var_test_*), for every MCSTAT_EINVAL.  Thread-local storage, valid until the
 * thread's next call of such a function; never NULL.  (Since 0.3.) */
MCSTAT_API const char *mcstat_last_error(void);

/* ------------------------------------------------------------------------ */
/* Alternatives and tails.                                                   */
/* An alternative is a claim about the first sample: MCSTAT_LESS means       */
/* mean(x) < mu0 (or mean(x) < mean(y), var(x) < sigma0^2, var(x)/var(y) <   */
/* ratio).  Values match across versions; FFI callers may use the integers. */
/* ------------------------------------------------------------------------ */
enum mcstat_alternative {
    MCSTAT_TWO_SIDED = 0,
    MCSTAT_LESS = 1,
    MCSTAT_GREATER = 2
};

/* Parses "two-sided" (also "two.sided", "two_sided"), "less", "greater". */
MCSTAT_NODISCARD MCSTAT_API int mcstat_alternative_parse(const char *name, int *alternative);
/* "two-sided", "less", "greater", or NULL for an invalid value. */
MCSTAT_API const char *mcstat_alternative_name(int alternative);

/* ------------------------------------------------------------------------ */
/* The numerical floor.                                                      */
/* Differences at the resolution of the caller's arithmetic are rounding,   */
/* not evidence.  The calls that take data a renderer computed (the renderer */
/* checks' options and the per-pixel options, field `resolution`) add it as */
/* a relative error of what they compare; by default it is derived from the  */
/* data: 64 units in the last place of float32 when every value is a float32 */
/* (a float formula of a few dozen operations, a normalisation rounded once, */
/* is off by up to tens of ulps), else of float64.                          */
/* ------------------------------------------------------------------------ */
#define MCSTAT_RESOLUTION_FLOAT32 0x1p-18 /* 64 * 2^-24 */
#define MCSTAT_RESOLUTION_FLOAT64 0x1p-47 /* 64 * 2^-53 */

/* Every test writes an mcstat_result ("The tests and their result"); the stream checks of
 * "Accumulators" do too. */
typedef struct mcstat_result mcstat_result;

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_BASE_FAMILY_H */
