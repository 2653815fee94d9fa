/*
 * test_p_adjust.c - mcstat_p_adjust against R's p.adjust (the records of
 * tests/data/p_adjust_ref.txt, made by tools/refgen/make_p_adjust_ref.R),
 * Hommel against R's O(n^2) loop transcribed here on random inputs with
 * ties, e-BH (mcstat_e_bh and the method "e-BH") against a direct
 * implementation of Wang & Ramdas' k* rule and hand-computed cases, and the
 * statuses of bad input.
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


/* e-BH oracles on e-values, NaN ones skipped.  ebh_reject: the rule itself,
 * reject[i] <- whether e[i] is among the k* largest, k* = max{k : k e_(k) /
 * m >= 1/alpha}; ebh_adjusted: min over k >= rank of m / (k e_(k)), capped
 * at 1, by the O(m^2) definition (rank among ties: the last one). */
static int cmp_desc(const void *a, const void *b)
{
    return cmp_double(b, a);
}

static size_t ebh_sorted(const double *e, size_t n, double *s)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (!isnan(e[i]))
            s[m++] = e[i];
    qsort(s, m, sizeof *s, cmp_desc);
    return m;
}

static void ebh_reject(const double *e, size_t n, double alpha, int *reject)
{
    double *s = malloc((n ? n : 1) * sizeof *s);
    size_t m = ebh_sorted(e, n, s), kstar = 0;
    for (size_t k = 1; k <= m; k++)
        if ((double)k * s[k - 1] / (double)m >= 1.0 / alpha)
            kstar = k;
    for (size_t i = 0; i < n; i++)
        reject[i] = !isnan(e[i]) && kstar > 0 && e[i] >= s[kstar - 1];
    free(s);
}

static void ebh_adjusted(const double *e, size_t n, double *adj)
{
    double *s = malloc((n ? n : 1) * sizeof *s);
    size_t m = ebh_sorted(e, n, s);
    for (size_t i = 0; i < n; i++) {
        if (isnan(e[i])) {
            adj[i] = e[i];
            continue;
        }
        size_t r = 0; /* 1-based rank of e[i]: the last of its ties */
        while (r < m && s[r] >= e[i])
            r++;
        double q = 1.0;
        for (size_t k = r; k <= m; k++)
            q = fmin(q, (double)m / ((double)k * s[k - 1]));
        adj[i] = q;
    }
    free(s);
}

static void run_e_bh(void)
{
    /* by hand: m = 4, descending 20, 10, 1, 0.5: 4/(k e_(k)) = 0.2, 0.2,
     * 4/3, 2; the minimum from each rank on, capped at 1 */
    {
        const double e[] = {20, 10, 1, 0.5}, want[] = {0.2, 0.2, 1, 1};
        double got[4];
        CHECK_INT(mcstat_e_bh(e, 4, NULL, 0, got), MCSTAT_OK);
        for (int i = 0; i < 4; i++)
            CHECK_REL(got[i], want[i], 1e-15, "hand 1 [%d]", i);
    }
    /* NaN not counted (m = 5), e = inf (0), e = 0 (1), tied 5s (5/(4*5)
     * = 0.25 for both; 5/(3*5) = 1/3 is not the minimum from rank 3 on) */
    {
        const double e[] = {40, 5, 5, NAN, 0, INFINITY, -0.0};
        const double want[] = {5.0 / 80, 0.25, 0.25, NAN, 1, 0, 1};
        double got[7];
        /* m = 6 with -0: redo the hand values: descending inf, 40, 5, 5, 0, 0
         * -> 6/(2*40) = 0.075, 6/(4*5) = 0.3 */
        const double want6[] = {0.075, 0.3, 0.3, NAN, 1, 0, 1};
        CHECK_INT(mcstat_e_bh(e, 6, NULL, 0, got), MCSTAT_OK);
        for (int i = 0; i < 6; i++)
            CHECK_MSG(isnan(want[i]) ? isnan(got[i]) : fabs(got[i] - want[i]) <= 1e-15, "hand 2 [%d] %g", i, got[i]);
        CHECK_INT(mcstat_e_bh(e, 7, NULL, 0, got), MCSTAT_OK);
        for (int i = 0; i < 7; i++)
            CHECK_MSG(isnan(want6[i]) ? isnan(got[i]) : fabs(got[i] - want6[i]) <= 1e-15, "hand 3 [%d] %g", i,
                      got[i]);
    }
    /* m = 1: the single e-value test, min(1, 1/e); in place */
    {
        double e[] = {NAN, 4, NAN};
        CHECK_INT(mcstat_e_bh(e, 3, NULL, 0, e), MCSTAT_OK);
        CHECK(isnan(e[0]) && e[1] == 0.25 && isnan(e[2]));
        double f[] = {0.5};
        CHECK_INT(mcstat_e_bh(f, 1, NULL, 0, f), MCSTAT_OK);
        CHECK(f[0] == 1.0);
        CHECK_INT(mcstat_e_bh(NULL, 0, NULL, 0, NULL), MCSTAT_OK);
    }
    /* random inputs against the O(m^2) definition and the k* rule */
    for (int rep = 0; rep < 200; rep++) {
        size_t n = 1 + (size_t)(unif() * (rep < 150 ? 40 : 600));
        double *e = malloc(n * sizeof *e), *want = malloc(n * sizeof *want), *got = malloc(n * sizeof *got);
        int *rej = malloc(n * sizeof *rej);
        int kind = rep % 4;
        for (size_t i = 0; i < n; i++) {
            double u = unif();
            e[i] = 1.0 / u - 1.0; /* heavy tail, many near 0 */
            if (kind == 1)
                e[i] = floor(e[i] * 2) / 2; /* ties, zeros */
            else if (kind == 2 && i % 5 == 0)
                e[i] = i % 10 == 0 ? NAN : INFINITY;
            else if (kind == 3)
                e[i] *= 1e3;
        }
        ebh_adjusted(e, n, want);
        CHECK_INT(mcstat_e_bh(e, n, NULL, 0, got), MCSTAT_OK);
        for (size_t i = 0; i < n; i++) {
            if (isnan(e[i]))
                CHECK(isnan(got[i]));
            else
                CHECK_REL(got[i], want[i], 1e-13, "rep %d n %zu [%zu]", rep, n, i);
        }
        const double alphas[] = {0.01, 0.05, 0.1, 0.2, 0.5};
        for (int a = 0; a < 5; a++) {
            ebh_reject(e, n, alphas[a], rej);
            for (size_t i = 0; i < n; i++)
                CHECK_MSG(rej[i] == (got[i] <= alphas[a]), "rep %d alpha %g [%zu]: rule %d, adjusted %g", rep,
                          alphas[a], i, rej[i], got[i]);
        }
        free(e);
        free(want);
        free(got);
        free(rej);
    }
    /* huge m (2^21 + 3): the k* rule at several alphas, with a workspace */
    {
        size_t n = (1u << 21) + 3, bytes = 0;
        double *e = malloc(n * sizeof *e), *got = malloc(n * sizeof *got);
        int *rej = malloc(n * sizeof *rej);
        for (size_t i = 0; i < n; i++)
            e[i] = i % 97 == 0 ? 1e8 * unif() : 1.0 / unif() - 1.0;
        CHECK_INT(mcstat_p_adjust_work_size(n, MCSTAT_P_ADJUST_E_BH, &bytes), MCSTAT_OK);
        double *work = malloc(bytes);
        CHECK_INT(mcstat_e_bh(e, n, work, bytes - 8, got), MCSTAT_EBUFSIZE);
        CHECK_INT(mcstat_e_bh(e, n, work, bytes, got), MCSTAT_OK);
        const double alphas[] = {0.01, 0.05, 0.3};
        for (int a = 0; a < 3; a++) {
            ebh_reject(e, n, alphas[a], rej);
            size_t bad = 0, nrej = 0;
            for (size_t i = 0; i < n; i++) {
                bad += rej[i] != (got[i] <= alphas[a]);
                nrej += rej[i];
            }
            CHECK_MSG(bad == 0, "huge m, alpha %g: %zu disagree", alphas[a], bad);
            CHECK_MSG(nrej > 0 && nrej < n, "huge m, alpha %g: %zu rejections", alphas[a], nrej);
        }
        free(work);
        free(e);
        free(got);
        free(rej);
    }
    /* the method "e-BH": e-BH on e = p^(-9/10) / 10; p = 0 -> e = inf; one
     * p-value comes back unchanged, as in every method */
    for (int rep = 0; rep < 50; rep++) {
        size_t n = 2 + (size_t)(unif() * 300);
        double *p = malloc(n * sizeof *p), *e = malloc(n * sizeof *e), *want = malloc(n * sizeof *want),
               *got = malloc(n * sizeof *got), *by = malloc(n * sizeof *by);
        for (size_t i = 0; i < n; i++) {
            double u = unif();
            p[i] = rep % 2 ? u * u * u * u * u * u : u;
            if (i % 17 == 3)
                p[i] = 0.0;
            if (i % 23 == 4)
                p[i] = 1.0;
            if (i % 29 == 5)
                p[i] = NAN;
            e[i] = isnan(p[i]) ? p[i] : p[i] == 0 ? INFINITY : 0.1 * pow(p[i], -0.9);
        }
        ebh_adjusted(e, n, want);
        CHECK_INT(mcstat_p_adjust(p, n, MCSTAT_P_ADJUST_E_BH, NULL, 0, got), MCSTAT_OK);
        CHECK_INT(mcstat_p_adjust(p, n, MCSTAT_P_ADJUST_BY, NULL, 0, by), MCSTAT_OK);
        for (size_t i = 0; i < n; i++) {
            if (isnan(p[i])) {
                CHECK(isnan(got[i]));
                continue;
            }
            CHECK_REL(got[i], want[i], 1e-12, "p rep %d n %zu [%zu]", rep, n, i);
            CHECK_MSG(got[i] >= p[i] && got[i] <= 1.0, "p rep %d [%zu]: %g from %g", rep, i, got[i], p[i]);
        }
        free(p);
        free(e);
        free(want);
        free(got);
        free(by);
    }
    {
        double p[] = {NAN, 0.003};
        double out[2];
        CHECK_INT(mcstat_p_adjust(p, 2, MCSTAT_P_ADJUST_E_BH, NULL, 0, out), MCSTAT_OK);
        CHECK(isnan(out[0]) && out[1] == 0.003);
    }
    /* names */
    int m = -1;
    const char *names[] = {"e-BH", "E-BH", "ebh", "e_bh", "EBH"};
    for (int i = 0; i < 5; i++) {
        m = -1;
        CHECK_INT(mcstat_p_adjust_method_parse(names[i], &m), MCSTAT_OK);
        CHECK_MSG(m == MCSTAT_P_ADJUST_E_BH, "%s parsed as %d", names[i], m);
    }
    CHECK(mcstat_p_adjust_method_parse("e-B", &m) == MCSTAT_EINVAL);
    CHECK(!strcmp(mcstat_p_adjust_method_name(MCSTAT_P_ADJUST_E_BH), "e-BH"));
    /* bad e-values: nothing written */
    const double bad[] = {-1.0, -INFINITY, -1e-300};
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
        double e[3] = {1.0, bad[i], 2.0}, out[3] = {-1, -1, -1};
        CHECK_INT(mcstat_e_bh(e, 3, NULL, 0, out), MCSTAT_EINVAL);
        CHECK(out[0] == -1 && out[1] == -1 && out[2] == -1);
    }
    double e2[2] = {1.0, 2.0}, o2[2], w[8];
    CHECK_INT(mcstat_e_bh(NULL, 2, NULL, 0, o2), MCSTAT_EINVAL);
    CHECK_INT(mcstat_e_bh(e2, 2, NULL, 0, NULL), MCSTAT_EINVAL);
    CHECK_INT(mcstat_e_bh(e2, 2, (char *)w + 1, 60, o2), MCSTAT_EINVAL);
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
        for (int meth = 0; meth <= MCSTAT_P_ADJUST_E_BH; meth++) {
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

/* BH and Holm by the textbook: qsort of (p, index), then the step-up /
 * step-down loops, with fmin/fmax. */
typedef struct {
    double p;
    size_t i;
} pi_pair;

static int cmp_pair(const void *x, const void *y)
{
    double a = ((const pi_pair *)x)->p, b = ((const pi_pair *)y)->p;
    return (a > b) - (a < b);
}

static void adjust_by_qsort(const double *p, size_t n, int holm, double *adj)
{
    pi_pair *s = malloc(n * sizeof *s);
    for (size_t k = 0; k < n; k++)
        s[k] = (pi_pair){p[k], k};
    qsort(s, n, sizeof *s, cmp_pair);
    double nd = (double)n, run = holm ? 0.0 : INFINITY;
    if (holm) {
        for (size_t i = 0; i < n; i++) {
            run = fmax(run, (nd - (double)i) * s[i].p);
            adj[s[i].i] = fmin(1.0, run);
        }
    } else {
        for (size_t i = n; i-- > 0;) {
            run = fmin(run, nd / (double)(i + 1) * s[i].p);
            adj[s[i].i] = fmin(1.0, run);
        }
    }
    free(s);
}

/* Large inputs whose values the sort's distribution passes handle each
 * way: uniform (a few per bucket), clustered (a crowded bucket: radix),
 * few distinct values (a bucket that does not spread), a geometric spread
 * (one value per octave), and one huge outlier among tiny values. */
static void run_large_shapes(void)
{
    const size_t n = 60000;
    double *p = malloc(n * sizeof *p), *got = malloc(n * sizeof *got), *want = malloc(n * sizeof *want);
    for (int shape = 0; shape < 5; shape++) {
        for (size_t k = 0; k < n; k++) {
            double u = unif();
            switch (shape) {
            case 0: p[k] = u; break;
            case 1: p[k] = k % 3 ? u : 0.25 + 1e-12 * u; break;
            case 2: p[k] = (double)(k % 4) / 8.0; break;
            case 3: p[k] = ldexp(1.0 + u, -1 - (int)(k % 900)); break;
            default: p[k] = k == n / 2 ? 1.0 : 1e-300 * (1.0 + u); break;
            }
        }
        for (int holm = 0; holm < 2; holm++) {
            adjust_by_qsort(p, n, holm, want);
            CHECK_INT(mcstat_p_adjust(p, n, holm ? MCSTAT_P_ADJUST_HOLM : MCSTAT_P_ADJUST_BH, NULL, 0, got),
                      MCSTAT_OK);
            size_t bad = 0;
            for (size_t k = 0; k < n; k++)
                bad += got[k] != want[k];
            CHECK_MSG(bad == 0, "shape %d %s: %zu of %zu adjusted values differ from qsort's", shape,
                      holm ? "holm" : "BH", bad, n);
        }
    }
    free(p);
    free(got);
    free(want);
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
    run_e_bh();
    run_large_shapes();
    run_bad_input();
    return h_report("test_p_adjust");
}
