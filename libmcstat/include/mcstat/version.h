/*
 * mcstat/version.h - sizes, versions and GSL's handler.
 *
 * Included by mcstat.h; a program may include this family alone.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_VERSION_FAMILY_H
#define MCSTAT_VERSION_FAMILY_H

#include "base.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ======================================================================== */
/* 8. Sizes, versions and GSL's handler.                                  */
/* Constants as functions for FFI callers (every size is                    */
/* mcstat_sizeof_<thing>), the release and ABI numbers, and the opt-in to   */
/* GSL's error handler off.                                                 */
/* ======================================================================== */

/* ------------------------------------------------------------------------ */
/* Sizes and constants as functions, for FFI callers that cannot read       */
/* macros or sizeof.  (Each options struct's size sits beside it.)          */
/* ------------------------------------------------------------------------ */
MCSTAT_API size_t mcstat_sizeof_moments(void);
MCSTAT_API size_t mcstat_sizeof_result(void);
/* MCSTAT_MOMENTS_BYTES: the size of the serialized form of one accumulator. */
MCSTAT_API size_t mcstat_sizeof_moments_bytes(void);

/* ------------------------------------------------------------------------ */
/* Versions.                                                                 */
/* MCSTAT_VERSION_MAJOR/MINOR/PATCH is the release, written here only: the   */
/* build (CMakeLists.txt), the Python package (pyproject.toml) read it from  */
/* this header, and the Rust and Go bindings' tests check theirs against it. */
/* MCSTAT_SOVERSION is the ABI: the shared library is libmcstat.so.N.  It    */
/* changes only with an incompatible change, one that breaks a binary built  */
/* against an earlier release with this SOVERSION (a function removed or its */
/* signature changed, a public struct's size or layout changed, an enum     */
/* value renumbered), never with the release number alone; additions keep   */
/* it.  libmcstat/abi/ holds the ABI (abidw) of every release of this      */
/* SOVERSION and `make abi-check` compares every build against each.        */
/* ------------------------------------------------------------------------ */
#define MCSTAT_VERSION_MAJOR 0
#define MCSTAT_VERSION_MINOR 2
#define MCSTAT_VERSION_PATCH 0
/* The shared library's ABI version (its SOVERSION; see above). */
#define MCSTAT_SOVERSION 0
#define MCSTAT_VERSION_NUMBER \
    (MCSTAT_VERSION_MAJOR * 10000 + MCSTAT_VERSION_MINOR * 100 + MCSTAT_VERSION_PATCH)

/* MCSTAT_VERSION_NUMBER of the library actually linked. */
MCSTAT_API unsigned mcstat_version_number(void);
/* "MAJOR.MINOR.PATCH" of the library actually linked (static storage). */
MCSTAT_API const char *mcstat_version(void);

/* ------------------------------------------------------------------------ */
/* GSL's error handler.                                                      */
/* GSL's default handler aborts the process.  mcstat validates every         */
/* argument before calling GSL, so the handler is never reached through      */
/* mcstat, and mcstat never changes it: it is one global shared by every     */
/* library in the process.  A program that wants GSL's own calls to return   */
/* error codes instead of aborting may opt in here.                          */
/* ------------------------------------------------------------------------ */
/* Turns GSL's error handler off (gsl_set_error_handler_off). */
MCSTAT_API void mcstat_gsl_handler_off(void);
/* Turns it off only if no handler has been installed (GSL's default is in
 * force); returns 1 if it did so, 0 if a caller's handler was left alone. */
MCSTAT_API int mcstat_gsl_handler_off_if_default(void);

#ifdef __cplusplus
}
#endif
#endif /* MCSTAT_VERSION_FAMILY_H */
