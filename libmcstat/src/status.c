/*
 * status.c - status texts, the last refusal's reason and the names of the
 * enums (alternatives, decisions).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <stdarg.h>
#include <stdio.h>
#include <string.h>

const char *mcstat_strerror(int status)
{
    switch (status) {
    case MCSTAT_OK: return "success";
    case MCSTAT_EINVAL: return "invalid argument (NULL pointer, unknown option, or a parameter outside its domain)";
    case MCSTAT_ETOOFEW: return "too few observations: a sample needs at least 2 (at least 1 for the K-S test; a chi-squared goodness of fit needs observations and df >= 1 after pooling)";
    case MCSTAT_ENONFINITE: return "the data contain NaN or infinite values";
    case MCSTAT_EDEGENERATE: return "the data are essentially constant (zero spread)";
    case MCSTAT_ENOMEM: return "out of memory";
    case MCSTAT_ENUMERIC: return "numerical failure: an iteration did not converge";
    case MCSTAT_EBUFSIZE: return "the output buffer is too small";
    case MCSTAT_ECORRUPT: return "serialized data are truncated, corrupt or of an unknown version";
    case MCSTAT_ETOOBIG: return "the sizes are too large for the requested method (e.g. an exact K-S p-value): choose another; or an observation count would pass 2^64 - 1";
    case MCSTAT_ECALLBACK: return "a callback failed or returned invalid values (the check's report says which, where and what)";
    case MCSTAT_EHEAVYTAIL: return "the data's tails are too heavy for a decision within the samples seen (the kurtosis gate never opened)";
    default: return "unknown status code";
    }
}

/* One reason per thread: a refusal is written where it is decided and
 * read by the caller (or a binding) right after the call returns. */
static _Thread_local char last_error[320];

const char *mcstat_last_error(void)
{
    return last_error;
}

void mcstat__error_clear(void)
{
    last_error[0] = '\0';
}

int mcstat__refuse(int status, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(last_error, sizeof last_error, fmt, ap);
    va_end(ap);
    return status;
}

int mcstat_alternative_parse(const char *name, int *alternative)
{
    if (!name || !alternative)
        return MCSTAT_EINVAL;
    if (!strcmp(name, "two-sided") || !strcmp(name, "two.sided") || !strcmp(name, "two_sided"))
        *alternative = MCSTAT_TWO_SIDED;
    else if (!strcmp(name, "less"))
        *alternative = MCSTAT_LESS;
    else if (!strcmp(name, "greater"))
        *alternative = MCSTAT_GREATER;
    else
        return MCSTAT_EINVAL;
    return MCSTAT_OK;
}

const char *mcstat_alternative_name(int alternative)
{
    switch (alternative) {
    case MCSTAT_TWO_SIDED: return "two-sided";
    case MCSTAT_LESS: return "less";
    case MCSTAT_GREATER: return "greater";
    default: return NULL;
    }
}

const char *mcstat_decision_name(int decision)
{
    switch (decision) {
    case MCSTAT_DECISION_LESS: return "less";
    case MCSTAT_DECISION_EQUAL: return "equal";
    case MCSTAT_DECISION_GREATER: return "greater";
    default: return NULL;
    }
}

int mcstat__refuse_test_args(int alternative, double alpha, const void *out)
{
    if (!valid_alternative(alternative))
        return mcstat__refuse(MCSTAT_EINVAL,
                              "alternative must be MCSTAT_TWO_SIDED (0), MCSTAT_LESS (1) or MCSTAT_GREATER (2), got %d",
                              alternative);
    if (!valid_alpha(alpha))
        return mcstat__refuse(MCSTAT_EINVAL, "alpha must be in (0, 1), got %g", alpha);
    if (!out)
        return mcstat__refuse(MCSTAT_EINVAL, "out (the result) is NULL");
    return MCSTAT_OK;
}
