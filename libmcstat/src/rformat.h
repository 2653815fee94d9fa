/*
 * rformat.h - R's number formatting (see rformat.c); internal.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#ifndef MCSTAT_RFORMAT_H
#define MCSTAT_RFORMAT_H

#include <stddef.h>

#define MCSTAT_HIDDEN_RF __attribute__((visibility("hidden")))

/* The common layout R's format(x, digits) gives a vector: width w, d digits
 * after the point (fixed) or in the mantissa, e = 0 fixed, 1 or 2 scientific.
 * 1 <= digits <= 15 (R formats 16 and more through sprintf, not done here). */
typedef struct {
    int w, d, e;
} mcstat_rlayout;

MCSTAT_HIDDEN_RF void mcstat__rformat_layout(const double *x, int n, int digits, mcstat_rlayout *f);
/* One element in that layout, right-justified to max(width, f->w); snprintf's return. */
MCSTAT_HIDDEN_RF int mcstat__rformat_encode(double x, const mcstat_rlayout *f, int width, char *buf, size_t size);
/* format(x, digits = digits) of a single number. */
MCSTAT_HIDDEN_RF int mcstat__rformat1(double x, int digits, char *buf, size_t size);
/* format.pval(p, digits = digits): "< 2.2e-16" below machine epsilon. */
MCSTAT_HIDDEN_RF int mcstat__rformat_pval(double p, int digits, char *buf, size_t size);

#endif
