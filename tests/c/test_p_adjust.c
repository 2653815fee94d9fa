/*
 * test_p_adjust.c - mcstat_p_adjust against R's p.adjust (the records of
 * tests/data/p_adjust_ref.txt, made by tools/refgen/make_p_adjust_ref.R),
 * Hommel against R's O(n^2) loop transcribed here on random inputs with
 * ties, and the statuses of bad input.
 * Usage: test_p_adjust PATH/TO/p_adjust_ref.txt
 */
#include "harness.h"

#include <stdint.h>
static uint64_t rng_state = 9;
#include "test_rng.h"

#include "mcstat.h"

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

static double *read_values(char *line, size_t n)
{
    double *v = malloc((n ? n : 1) * sizeof *v);
    char *s = strchr(line, ' ');
    for (size_t i = 0; i < n; i++) {
        v[i] = strtod(s, &s);
    }
    return v;
}

/* The p-values of the script's gen(N). */
static void gen(double *p, size_t N)
{
    for (size_t k = 0; k < N; k++) {
        double u = (double)((k * 7919 + 12345) % 1000003) / 1000003.0;
        double v = u;
        if (k % 7 == 0)
            v = floor(u * 1000) / 1000;
        if (k % 10 == 0)
            v = u * u * u * u * 1e-3;
        if (k % 5000 == 1)
            v = 0;
        if (k % 5000 == 2)
            v = 1;
        if (k % 1000 == 999)
            v = NAN;
        p[k] = v;
    }
}

static int method_of(const char *name)
{
    int m = -1;
    CHECK_INT(mcstat_p_adjust_method_parse(name, &m), MCSTAT_OK);
    return m;
}

static void run_reference(const char *path)
{
    FILE *f = fopen(path, "r");
    CHECK_MSG(f != NULL, "cannot open %s", path);
    if (!f)
        return;
    size_t cap = 1 << 20;
    char *line = malloc(cap);
    char name[64], meth[32];
    size_t n, cases = 0, large = 0;
    double *lp = NULL, *la = NULL;
    size_t ln = 0;
    while (fgets(line, (int)cap, f)) {
        if (sscanf(line, "case %63s %31s %zu", name, meth, &n) == 3) {
            char *l1 = malloc(cap), *l2 = malloc(cap);
            CHECK(fgets(l1, (int)cap, f) && fgets(l2, (int)cap, f));
            double *p = read_values(l1, n), *want = read_values(l2, n), *got = malloc(n * sizeof *got);
            int m = method_of(meth);
            /* with the caller's workspace, and in place with the library's */
            size_t bytes = 0;
            CHECK_INT(mcstat_p_adjust_work_size(n, m, &bytes), MCSTAT_OK);
            double *work = malloc(bytes + 8);
            CHECK_INT(mcstat_p_adjust(p, n, m, work, bytes, got), MCSTAT_OK);
            for (size_t i = 0; i < n; i++)
                CHECK_REL(got[i], want[i], 1e-14, "%s %s [%zu]", name, meth, i);
            CHECK_INT(mcstat_p_adjust(p, n, m, NULL, 0, p), MCSTAT_OK);
            for (size_t i = 0; i < n; i++)
                CHECK_REL(p[i], want[i], 1e-14, "in place %s %s [%zu]", name, meth, i);
            free(work);
            free(p);
            free(want);
            free(got);
            free(l1);
            free(l2);
            cases++;
        } else if (sscanf(line, "large %31s %zu", meth, &n) == 2) {
            free(lp);
            free(la);
            ln = n;
            lp = malloc(n * sizeof *lp);
            la = malloc(n * sizeof *la);
            gen(lp, n);
            CHECK_INT(mcstat_p_adjust(lp, n, method_of(meth), NULL, 0, la), MCSTAT_OK);
            large++;
        } else if (line[0] == 'a' && line[1] == 't') {
            size_t k;
            double v;
            CHECK(sscanf(line, "at %zu %lf", &k, &v) == 2 && k < ln);
            CHECK_REL(la[k], v, 1e-13, "large %s [%zu]", meth, k);
        } else if (!strncmp(line, "sum", 3)) {
            double v;
            long c05;
            CHECK(sscanf(line, "sum %lf %ld", &v, &c05) == 2);
            double s = 0;
            long c = 0;
            for (size_t k = 0; k < ln; k++) {
                if (!isnan(la[k])) {
                    s += la[k];
                    c += la[k] <= 0.05;
                }
            }
            CHECK_REL(s, v, 1e-11, "large %s sum", meth);
            CHECK_INT(c, c05);
        }
    }
    CHECK_INT(cases, 12 * 6);
    CHECK_INT(large, 6);
    free(lp);
    free(la);
    free(line);
    fclose(f);
}

/* R's hommel branch, transcribed (O(n^2)): p sorted ascending, n >= 3. */
static void hommel_r(const double *ps, size_t n, double *adj)
{
    double *q = malloc(n * sizeof *q), *pa = malloc(n * sizeof *pa);
    double mn = INFINITY;
    for (size_t i = 0; i < n; i++)
        mn = fmin(mn, (double)n * ps[i] / (double)(i + 1));
    for (size_t i = 0; i < n; i++)
        q[i] = pa[i] = mn;
    for (size_t m = n - 1; m >= 2; m--) {
        double q1 = INFINITY;
        for (size_t k = 2; k <= m; k++) /* i2 = (n-m+2):n, 1-based */
            q1 = fmin(q1, (double)m * ps[n - m + k - 1] / (double)k);
        for (size_t i = 0; i < n - m + 1; i++)
            q[i] = fmin((double)m * ps[i], q1);
        for (size_t i = n - m + 1; i < n; i++)
            q[i] = q[n - m];
        for (size_t i = 0; i < n; i++)
            pa[i] = fmax(pa[i], q[i]);
    }
    for (size_t i = 0; i < n; i++)
        adj[i] = fmax(pa[i], ps[i]);
    free(q);
    free(pa);
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void run_hommel_random(void)
{
    for (int rep = 0; rep < 300; rep++) {
        size_t n = 3 + (size_t)(unif() * (rep < 200 ? 30 : 400));
        double *p = malloc(n * sizeof *p), *s = malloc(n * sizeof *s), *want = malloc(n * sizeof *want),
               *got = malloc(n * sizeof *got);
        int kind = rep % 4;
        for (size_t i = 0; i < n; i++) {
            double u = unif();
            if (kind == 1)
                u = u * u * u * u; /* many small ones */
            else if (kind == 2)
                u = floor(u * 8) / 8; /* heavy ties */
            else if (kind == 3 && i % 3 == 0)
                u = u * 1e-6;
            p[i] = s[i] = u;
        }
        qsort(s, n, sizeof *s, cmp_double);
        hommel_r(s, n, want);
        CHECK_INT(mcstat_p_adjust(p, n, MCSTAT_P_ADJUST_HOMMEL, NULL, 0, got), MCSTAT_OK);
        /* got[i] is the adjusted p[i]: find p[i]'s sorted value */
        for (size_t i = 0; i < n; i++) {
            double *hit = bsearch(&p[i], s, n, sizeof *s, cmp_double);
            CHECK(hit != NULL);
            if (hit)
                CHECK_REL(got[i], want[hit - s], 1e-13, "rep %d n %zu [%zu]", rep, n, i);
        }
        free(p);
        free(s);
        free(want);
        free(got);
    }
}

static void run_bad_input(void)
{
    double p[4] = {0.1, 0.2, 0.3, 0.4}, out[4] = {-1, -1, -1, -1};
    int m = 0;
    size_t bytes = 0;
    CHECK_INT(mcstat_p_adjust_method_parse("nope", &m), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust_method_parse(NULL, &m), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust_method_parse("fdr", &m), MCSTAT_OK);
    CHECK_INT(m, MCSTAT_P_ADJUST_BH);
    /* statsmodels' multipletests names, and case ignored */
    static const struct {
        const char *name;
        int method;
    } alias[] = {{"fdr_bh", MCSTAT_P_ADJUST_BH},          {"FDR_BH", MCSTAT_P_ADJUST_BH},
                 {"fdr_i", MCSTAT_P_ADJUST_BH},           {"fdrp", MCSTAT_P_ADJUST_BH},
                 {"fdr_by", MCSTAT_P_ADJUST_BY},          {"fdrcorr", MCSTAT_P_ADJUST_BY},
                 {"fdr_n", MCSTAT_P_ADJUST_BY},           {"b", MCSTAT_P_ADJUST_BONFERRONI},
                 {"bonf", MCSTAT_P_ADJUST_BONFERRONI},    {"Bonferroni", MCSTAT_P_ADJUST_BONFERRONI},
                 {"h", MCSTAT_P_ADJUST_HOLM},             {"Holm", MCSTAT_P_ADJUST_HOLM},
                 {"sh", MCSTAT_P_ADJUST_HOCHBERG},        {"simes-hochberg", MCSTAT_P_ADJUST_HOCHBERG},
                 {"ho", MCSTAT_P_ADJUST_HOMMEL},          {"bh", MCSTAT_P_ADJUST_BH},
                 {"by", MCSTAT_P_ADJUST_BY},              {"None", MCSTAT_P_ADJUST_NONE}};
    for (size_t i = 0; i < sizeof alias / sizeof alias[0]; i++) {
        m = -1;
        CHECK_INT(mcstat_p_adjust_method_parse(alias[i].name, &m), MCSTAT_OK);
        CHECK_MSG(m == alias[i].method, "%s parsed as %d", alias[i].name, m);
    }
    /* statsmodels' methods this library does not implement, and near misses */
    static const char *const refused[] = {"sidak", "s", "holm-sidak", "hs", "fdr_tsbh", "fdr_2sbh",
                                          "fdr_tsbky", "fdr_twostage", "fdr_gbs", "", "fdr_", "holmx",
                                          "bonferron"};
    for (size_t i = 0; i < sizeof refused / sizeof refused[0]; i++)
        CHECK_MSG(mcstat_p_adjust_method_parse(refused[i], &m) == MCSTAT_EINVAL, "%s accepted", refused[i]);
    CHECK(mcstat_p_adjust_method_name(99) == NULL);
    CHECK(!strcmp(mcstat_p_adjust_method_name(MCSTAT_P_ADJUST_BY), "BY"));
    CHECK_INT(mcstat_p_adjust_work_size(4, 99, &bytes), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust_work_size(4, MCSTAT_P_ADJUST_BH, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust_work_size(SIZE_MAX / 2, MCSTAT_P_ADJUST_BH, &bytes), MCSTAT_ETOOBIG);
    CHECK_INT(mcstat_p_adjust_work_size(4, MCSTAT_P_ADJUST_BONFERRONI, &bytes), MCSTAT_OK);
    CHECK_INT(bytes, 0);
    CHECK_INT(mcstat_p_adjust(p, 4, 99, NULL, 0, out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust(NULL, 4, MCSTAT_P_ADJUST_BH, NULL, 0, out), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust(p, 4, MCSTAT_P_ADJUST_BH, NULL, 0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_p_adjust(NULL, 0, MCSTAT_P_ADJUST_BH, NULL, 0, NULL), MCSTAT_OK);
    double work[40];
    CHECK_INT(mcstat_p_adjust(p, 4, MCSTAT_P_ADJUST_HOLM, work, 8, out), MCSTAT_EBUFSIZE);
    CHECK_INT(mcstat_p_adjust(p, 4, MCSTAT_P_ADJUST_HOLM, (char *)work + 1, 200, out), MCSTAT_EINVAL);
    const double bad[] = {1.5, -0.1, INFINITY, -INFINITY, 1.0000000000000002};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double q[4] = {0.1, 0.2, bad[i], 0.4};
        for (int meth = 0; meth <= 6; meth++) {
            CHECK_INT(mcstat_p_adjust(q, 4, meth, NULL, 0, out), MCSTAT_EINVAL);
            CHECK(out[0] == -1); /* nothing written */
        }
    }
    /* all NaN, and -0 */
    double nn[3] = {NAN, NAN, NAN};
    CHECK_INT(mcstat_p_adjust(nn, 3, MCSTAT_P_ADJUST_HOMMEL, NULL, 0, out), MCSTAT_OK);
    CHECK(isnan(out[0]) && isnan(out[1]) && isnan(out[2]));
    double z[3] = {-0.0, 0.5, 0.0};
    CHECK_INT(mcstat_p_adjust(z, 3, MCSTAT_P_ADJUST_HOLM, NULL, 0, out), MCSTAT_OK);
    CHECK(out[0] == 0 && out[2] == 0 && out[1] == 0.5);
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: test_p_adjust p_adjust_ref.txt\n");
        return 1;
    }
    (void)normal; /* test_rng.h's, unused here */
    run_reference(argv[1]);
    run_hommel_random();
    run_bad_input();
    return h_report("test_p_adjust");
}
