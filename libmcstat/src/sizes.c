/*
 * sizes.c - sizes of the public structs as functions, for FFI callers that
 * cannot read macros or sizeof.  Every one is mcstat_sizeof_<thing>.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

size_t mcstat_sizeof_moments(void) { return sizeof(mcstat_moments); }
size_t mcstat_sizeof_moments_bytes(void) { return MCSTAT_MOMENTS_BYTES; }
size_t mcstat_sizeof_stream(void) { return sizeof(mcstat_stream); }
size_t mcstat_sizeof_result(void) { return sizeof(mcstat_result); }
size_t mcstat_sizeof_ks_options(void) { return sizeof(mcstat_ks_options); }
size_t mcstat_sizeof_power_options(void) { return sizeof(mcstat_power_options); }
size_t mcstat_sizeof_diag_options(void) { return sizeof(mcstat_diag_options); }
size_t mcstat_sizeof_diagnostics(void) { return sizeof(mcstat_diagnostics); }
size_t mcstat_sizeof_gof_options(void) { return sizeof(mcstat_gof_options); }
