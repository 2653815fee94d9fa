/*
 * gsl_handler.c - opting in to GSL's error handler off (mcstat never changes it).
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <gsl/gsl_errno.h>

void mcstat_gsl_handler_off(void)
{
    gsl_set_error_handler_off();
}

int mcstat_gsl_handler_off_if_default(void)
{
    /* gsl_set_error_handler returns the previous handler: NULL means GSL's
     * default (abort) was in force.  Put back anything else. */
    gsl_error_handler_t *prev = gsl_set_error_handler_off();
    if (prev != NULL) {
        gsl_set_error_handler(prev);
        return 0;
    }
    return 1;
}
