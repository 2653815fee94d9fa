/*
 * status.c - versions, status texts, enum names, sizes.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <string.h>

#define STR2(x) #x
#define STR(x) STR2(x)

unsigned mcest_version_number(void)
{
    return MCEST_VERSION_NUMBER;
}

const char *mcest_version(void)
{
    return STR(MCEST_VERSION_MAJOR) "." STR(MCEST_VERSION_MINOR) "." STR(MCEST_VERSION_PATCH);
}

const char *mcest_strerror(int status)
{
    switch (status) {
    case MCEST_OK: return "success";
    case MCEST_EINVAL: return "invalid argument (NULL pointer, unknown option, non-finite or out-of-range parameter)";
    case MCEST_EUNSUPPORTED: return "option not supported here (the planted bugs apply to estimator A only)";
    case MCEST_ELIMIT: return "a rejection sampler reached its cap on trials per sample";
    case MCEST_ENUMERIC: return "numerical failure: a quadrature missed its tolerance or an envelope was exceeded";
    case MCEST_ENOTREADY: return "the plan lacks the albedo: call mcest_brdf_plan_albedo first";
    default: return "unknown status code";
    }
}

int mcest_method_parse(const char *name, int *method)
{
    if (!name || !method || !name[0] || name[1])
        return MCEST_EINVAL;
    switch (name[0]) {
    case 'U': case 'u': *method = MCEST_U; return MCEST_OK;
    case 'C': case 'c': *method = MCEST_C; return MCEST_OK;
    case 'A': case 'a': *method = MCEST_A; return MCEST_OK;
    case 'S': case 's': *method = MCEST_S; return MCEST_OK;
    default: return MCEST_EINVAL;
    }
}

const char *mcest_method_name(int method)
{
    switch (method) {
    case MCEST_U: return "U";
    case MCEST_C: return "C";
    case MCEST_A: return "A";
    case MCEST_S: return "S";
    default: return NULL;
    }
}

int mcest_bug_parse(const char *name, int *bug)
{
    if (!bug)
        return MCEST_EINVAL;
    if (!name || !name[0] || !strcmp(name, "none"))
        *bug = MCEST_BUG_NONE;
    else if (!strcmp(name, "no_cosine"))
        *bug = MCEST_BUG_NO_COSINE;
    else if (!strcmp(name, "barycentric"))
        *bug = MCEST_BUG_BARYCENTRIC;
    else if (!strcmp(name, "no_jacobian"))
        *bug = MCEST_BUG_NO_JACOBIAN;
    else
        return MCEST_EINVAL;
    return MCEST_OK;
}

const char *mcest_bug_name(int bug)
{
    switch (bug) {
    case MCEST_BUG_NONE: return "none";
    case MCEST_BUG_NO_COSINE: return "no_cosine";
    case MCEST_BUG_BARYCENTRIC: return "barycentric";
    case MCEST_BUG_NO_JACOBIAN: return "no_jacobian";
    default: return NULL;
    }
}

size_t mcest_sizeof_scene(void) { return sizeof(mcest_scene); }
size_t mcest_sizeof_irradiance_plan(void) { return sizeof(mcest_irradiance_plan); }
size_t mcest_sizeof_brdf(void) { return sizeof(mcest_brdf); }
size_t mcest_sizeof_brdf_plan(void) { return sizeof(mcest_brdf_plan); }
