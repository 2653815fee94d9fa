/*
 * rformat_stress.c - libmcstat's R-style number formatting against R's on the
 * file tools/refgen/rformat_stress.R writes (how to run: see there).
 * Prints the first differences and exits 1 if there is any.
 */
#include "rformat.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

int main(int argc, char **argv)
{
    FILE *f = argc > 1 ? fopen(argv[1], "r") : NULL;
    if (!f) {
        fprintf(stderr, "usage: %s FILE (from rformat_stress.R)\n", argv[0]);
        return 2;
    }
    char line[512], hex[128], want[256], got[256];
    int d;
    long n = 0, bad = 0;
    while (fgets(line, sizeof line, f)) {
        if (sscanf(line, "%127[^\t]\t%d\t%255[^\n]", hex, &d, want) != 3)
            continue;
        mcstat__rformat1(strtod(hex, NULL), d, got, sizeof got);
        n++;
        if (strcmp(got, want) && bad++ < 20)
            printf("%s digits=%d: \"%s\", R \"%s\"\n", hex, d, got, want);
    }
    fclose(f);
    printf("%ld values compared, %ld differ from R\n", n, bad);
    return bad != 0;
}
