/*
 * ref_tsv.h - reads the tab-separated reference tables of tests/data/
 * (written by the R scripts in tools/refgen/): one row per line, '#' lines skipped.
 */
#ifndef MCSTAT_TEST_REF_TSV_H
#define MCSTAT_TEST_REF_TSV_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define TSV_MAX_FIELDS 32

/* Calls row(fields, nfields, ctx) for each data row; returns rows read, -1
 * if the file cannot be opened. */
static inline int tsv_read(const char *path, void (*row)(char **f, int nf, void *ctx), void *ctx)
{
    FILE *fp = fopen(path, "r");
    if (!fp)
        return -1;
    size_t cap = 1 << 20;
    char *line = malloc(cap);
    int rows = 0;
    while (line && fgets(line, (int)cap, fp)) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        line[strcspn(line, "\n")] = '\0';
        char *f[TSV_MAX_FIELDS];
        int nf = 0;
        char *p = line;
        while (nf < TSV_MAX_FIELDS) {
            f[nf++] = p;
            char *t = strchr(p, '\t');
            if (!t)
                break;
            *t = '\0';
            p = t + 1;
        }
        row(f, nf, ctx);
        rows++;
    }
    free(line);
    fclose(fp);
    return rows;
}

/* A comma-separated list of numbers (hex or decimal) into a new array. */
static inline double *tsv_doubles(const char *s, size_t *n)
{
    size_t cap = 1;
    for (const char *p = s; *p; p++)
        cap += *p == ',';
    double *v = malloc(cap * sizeof *v);
    size_t k = 0;
    const char *p = s;
    while (v && *p) {
        char *end;
        v[k++] = strtod(p, &end);
        p = *end == ',' ? end + 1 : end;
        if (end == p && *p != ',')
            break;
    }
    *n = k;
    return v;
}

#endif
