/*
 * version.c - the release number of the library actually linked.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#define STR2(x) #x
#define STR(x) STR2(x)

unsigned mcstat_version_number(void)
{
    return MCSTAT_VERSION_NUMBER;
}

const char *mcstat_version(void)
{
    return STR(MCSTAT_VERSION_MAJOR) "." STR(MCSTAT_VERSION_MINOR) "." STR(MCSTAT_VERSION_PATCH);
}
