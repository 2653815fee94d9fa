/* ref_access.h - looks up and materialises the reference data sets. */
#ifndef MCSTAT_REF_ACCESS_H
#define MCSTAT_REF_ACCESS_H

#include "ref_data.h"

#include <stdlib.h>
#include <string.h>

static const ref_dataset *ref_find(const char *name)
{
    for (int i = 0; i < REF_NDATASETS; i++)
        if (!strcmp(REF_DATASETS[i].name, name))
            return &REF_DATASETS[i];
    fprintf(stderr, "no data set %s\n", name);
    exit(2);
}

/* The values of a data set (formula sets are generated; caller frees). */
static double *ref_values(const ref_dataset *d)
{
    double *x = malloc(d->n * sizeof *x);
    if (!x)
        exit(2);
    for (size_t i = 0; i < d->n; i++)
        x[i] = d->x ? d->x[i] : d->base + (double)((i * d->mult) % d->mod) * 0x1p-20;
    return x;
}

#endif
