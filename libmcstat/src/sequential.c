/*
 * sequential.c - anytime-valid sequential tests (mcstat.h, section "Sequential, anytime-valid tests"):
 * the asymptotic Gaussian-mixture confidence sequence on a working
 * parameter, with the hold that keeps small heavy-tailed samples from
 * deciding.
 *
 * Every look reduces to (theta_hat, theta0, se, t_eff): the estimate, the
 * null value and the standard error on the working scale, and the number
 * of observations the standard error corresponds to.  The mixture's
 * e-value and boundary depend on them only through z = (theta_hat -
 * theta0)/se and a = t_eff c / t_opt, so the same code serves the four
 * kinds.  Sums are read in the accumulator's scaled units (central sums
 * divided by powers of two), so data near 1e+-300 neither overflow nor
 * underflow before z is formed.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#define MATHLIB_STANDALONE 1
#include <Rmath.h>

#include "internal.h"

#include <float.h>

static const uint32_t SEQ_SIZES[] = {MCSTAT_SEQ_OPTIONS_SIZE_0_2};
_Static_assert(sizeof(mcstat_seq_options) == MCSTAT_SEQ_OPTIONS_SIZE_0_2,
               "a grown mcstat_seq_options needs its size appended to SEQ_SIZES");
_Static_assert(sizeof(mcstat_seq) == 448, "mcstat_seq's size is part of the ABI");

int mcstat_seq_options_init_size(mcstat_seq_options *opt, size_t size)
{
    const mcstat_seq_options d = MCSTAT_SEQ_OPTIONS_INIT;
    return mcstat__options_init(opt, size, &d, sizeof d, SEQ_SIZES, sizeof SEQ_SIZES / sizeof *SEQ_SIZES);
}

size_t mcstat_sizeof_seq_options(void) { return sizeof(mcstat_seq_options); }
size_t mcstat_sizeof_seq(void) { return sizeof(mcstat_seq); }

const char *mcstat_seq_kind_name(int kind)
{
    static const char *names[] = {NULL, "mean", "mean2", "var", "var2"};
    return kind >= MCSTAT_SEQ_MEAN_1 && kind <= MCSTAT_SEQ_VAR_2 ? names[kind] : NULL;
}

static int two_sample(int kind) { return kind == MCSTAT_SEQ_MEAN_2 || kind == MCSTAT_SEQ_VAR_2; }
static int on_variance(int kind) { return kind == MCSTAT_SEQ_VAR_1 || kind == MCSTAT_SEQ_VAR_2; }
static int finite_nonneg(double v) { return isfinite(v) && v >= 0.0; }

int mcstat_seq_init(mcstat_seq *s, int kind, double null_value, const mcstat_seq_options *opt)
{
    MCSTAT_IEEE_SCOPE();
    mcstat_seq_options o = MCSTAT_SEQ_OPTIONS_INIT;
    if (!s || !mcstat_seq_kind_name(kind))
        return MCSTAT_EINVAL;
    if (opt && mcstat__options_read(&o, sizeof o, opt, SEQ_SIZES, sizeof SEQ_SIZES / sizeof *SEQ_SIZES))
        return MCSTAT_EINVAL;
    if (!mcstat_alternative_name(o.alternative) || !(o.alpha > 0.0 && o.alpha < 1.0) || !finite_nonneg(o.eps) ||
        !(o.t_opt > 0.0) || !isfinite(o.t_opt) || !finite_nonneg(o.kurtosis_gate) || !finite_nonneg(o.var_ucb_z) ||
        o.min_n < 2 || !isfinite(null_value) || (on_variance(kind) && !(null_value > 0.0)))
        return MCSTAT_EINVAL;
    /* Equivalence is a two-sided statement about a mean. */
    if (o.eps > 0.0 && (on_variance(kind) || o.alternative != MCSTAT_TWO_SIDED))
        return MCSTAT_EINVAL;
    memset(s, 0, sizeof *s);
    s->version = MCSTAT_SEQ_VERSION;
    s->kind = kind;
    s->alternative = o.alternative;
    s->state = MCSTAT_SEQ_CONTINUE;
    s->hold = MCSTAT_SEQ_HOLD_FEW;
    mcstat_moments_init(&s->x);
    mcstat_moments_init(&s->y);
    s->null_value = null_value;
    s->alpha = o.alpha;
    s->eps = o.eps;
    s->t_opt = o.t_opt;
    s->kurtosis_gate = o.kurtosis_gate;
    s->var_ucb_z = o.var_ucb_z;
    s->min_n = o.min_n;
    s->log_e = -INFINITY;
    s->log_e_max = -INFINITY;
    s->cs[0] = -INFINITY;
    s->cs[1] = INFINITY;
    return MCSTAT_OK;
}

static int seq_valid(const mcstat_seq *s)
{
    return s && s->version == MCSTAT_SEQ_VERSION && mcstat_seq_kind_name(s->kind) &&
           mcstat_alternative_name(s->alternative) && s->x.version == MCSTAT_MOMENTS_VERSION &&
           s->y.version == MCSTAT_MOMENTS_VERSION;
}

/* An accumulator as the tests can read it: initialised, sums finite and
 * consistent (a caller's struct is not trusted). */
static int batch_valid(const mcstat_moments *m)
{
    if (!m || m->version != MCSTAT_MOMENTS_VERSION)
        return 0;
    if (m->n == 0)
        return 1;
    return isfinite(m->mean) && isfinite(m->mean_lo) && finite_nonneg(m->m2) && finite_nonneg(m->m4) &&
           isfinite(m->m3);
}

/* ---- one sample's contribution ------------------------------------------
 * What the look needs of a sample, in units of 2^scale: its hold bits, the
 * per-observation variance of the mean (made an upper bound) and that of
 * the log variance, and the n the kurtosis gate asks for. */
typedef struct {
    uint32_t hold;
    double n;
    double v_mean;  /* s^2 + z sqrt((M4/n - (M2/n)^2)/n), scaled by 2^(-2 scale) */
    double w_logv;  /* b2 - (n-3)/(n-1): n times the variance of log s^2 (asymptotically) */
    double n_gate;  /* kurtosis_gate * b2 (0 when the gate is off) */
} sample_look;

static sample_look look_at(const mcstat_seq *s, const mcstat_moments *m)
{
    sample_look r = {0, (double)m->n, NAN, NAN, 0.0};
    if (m->n < s->min_n)
        r.hold |= MCSTAT_SEQ_HOLD_FEW;
    if (m->n < 2) {
        r.hold |= MCSTAT_SEQ_HOLD_DEGENERATE;
        return r;
    }
    double n = (double)m->n, m2 = m->m2, m4 = m->m4;
    double var = m2 / (n - 1.0);
    /* No spread, or a spread within the last digits of the mean (the
     * tests' "constant to within rounding", mcstat__moments_check). */
    if (!(m2 > 0.0) || sqrt(var) < 10.0 * DBL_EPSILON * scale2(fabs(m->mean), -m->scale)) {
        r.hold |= MCSTAT_SEQ_HOLD_DEGENERATE;
        return r;
    }
    double q = m2 / n;
    double b2 = n * (m4 / m2) / m2; /* sample kurtosis; divided in two steps against underflow */
    if (s->kurtosis_gate > 0.0) {
        /* A variance's standard error rests on b2, itself a noisy estimate
         * whose spread grows with the tails (it needs the eighth moment):
         * the gate asks for b2 times more values there. */
        r.n_gate = s->kurtosis_gate * b2 * (on_variance(s->kind) ? b2 : 1.0);
        if (!(n >= r.n_gate))
            r.hold |= MCSTAT_SEQ_HOLD_KURTOSIS;
    }
    double spread = m4 / n - q * q; /* n Var(s^2) estimated; >= 0 up to rounding */
    r.v_mean = var + s->var_ucb_z * sqrt(fmax(spread, 0.0) / n);
    r.w_logv = b2 - (n - 3.0) / (n - 1.0);
    return r;
}

/* ---- the mixture -----------------------------------------------------------
 * c of the mixing variance, tuned so that the boundary is tightest at
 * t_opt for level alpha' (2 alpha one-sided, Howard et al. 2021). */
static double mixture_c(double alpha, int alternative)
{
    double a1 = alternative == MCSTAT_TWO_SIDED || 2.0 * alpha >= 1.0 ? alpha : 2.0 * alpha;
    double l = -2.0 * log(a1);
    return l + log1p(l);
}

/* log E at z for the alternative ("less" is "greater" at -z). */
static double log_e_value(double z, double a, int alternative)
{
    double base = 0.5 * z * z * (a / (1.0 + a)) - 0.5 * log1p(a);
    if (alternative == MCSTAT_TWO_SIDED)
        return base;
    double zz = alternative == MCSTAT_GREATER ? z : -z;
    return base + M_LN2 + pnorm(zz * sqrt(a / (1.0 + a)), 0.0, 1.0, 1, 1);
}

/* The z at which E reaches 1/alpha: closed form two-sided; one-sided the
 * root of log E(z) + log alpha, increasing in z, bracketed by [0, the
 * two-sided bound] (2 Phi >= 1 there): Newton's method, falling back to
 * bisection whenever a step leaves the bracket (5-6 evaluations where
 * bisection took 50). */
static double boundary(double a, double alpha, int alternative)
{
    double two = sqrt((1.0 + a) / a * (-2.0 * log(alpha) + log1p(a)));
    if (alternative == MCSTAT_TWO_SIDED)
        return two;
    double k = sqrt(a / (1.0 + a)), target = -log(alpha);
    double lo = 0.0, hi = two, z = two;
    for (int i = 0; i < 100; i++) {
        double f = log_e_value(z, a, MCSTAT_GREATER) - target;
        if (fabs(f) <= 4.0 * DBL_EPSILON * target) /* at rounding level: Newton would only oscillate */
            return z;
        if (f < 0.0)
            lo = z;
        else
            hi = z;
        /* d log E / dz = z a/(1+a) + k phi(kz)/Phi(kz) */
        double d = z * k * k + k * exp(dnorm(k * z, 0.0, 1.0, 1) - pnorm(k * z, 0.0, 1.0, 1, 1));
        double next = z - f / d;
        if (!(next > lo && next < hi))
            next = 0.5 * (lo + hi);
        if (fabs(next - z) <= 2.0 * DBL_EPSILON * z || hi - lo <= 2.0 * DBL_EPSILON * hi)
            return next;
        z = next;
    }
    return z;
}

/* ---- a look ----------------------------------------------------------------
 * The working-scale quantities of the current sums. */
typedef struct {
    uint32_t hold;
    double theta_hat, se, z, t_eff, n_gate;
} look;

/* mean + mean_lo - c in units of 2^-e, from the double-double mean. */
static double centred_scaled(const mcstat_moments *m, double c, int e)
{
    return (scale2(m->mean, -e) - scale2(c, -e)) + scale2(m->mean_lo, -e);
}

static look compute_look(const mcstat_seq *s)
{
    look L = {0, NAN, NAN, NAN, NAN, 0.0};
    int two = two_sample(s->kind);
    sample_look a = look_at(s, &s->x), b = {0, 0, 0, 0, 0};
    if (two)
        b = look_at(s, &s->y);
    L.hold = a.hold | b.hold;
    L.n_gate = fmax(a.n_gate, b.n_gate);
    if (L.hold & MCSTAT_SEQ_HOLD_DEGENERATE)
        return L;
    const mcstat_moments *x = &s->x, *y = &s->y;
    switch (s->kind) {
    case MCSTAT_SEQ_MEAN_1: {
        int e = x->scale;
        double se_s = sqrt(a.v_mean / a.n);
        L.z = centred_scaled(x, s->null_value, e) / se_s;
        L.theta_hat = x->mean + x->mean_lo;
        L.se = scale2(se_s, e);
        L.t_eff = a.n;
        break;
    }
    case MCSTAT_SEQ_MEAN_2: {
        /* both samples in the larger scale */
        int e = x->scale > y->scale ? x->scale : y->scale;
        double vx = scale2(a.v_mean, 2 * (x->scale - e)), vy = scale2(b.v_mean, 2 * (y->scale - e));
        double se2 = vx / a.n + vy / b.n;
        double d = ((scale2(x->mean, -e) - scale2(y->mean, -e)) - scale2(s->null_value, -e)) +
                   (scale2(x->mean_lo, -e) - scale2(y->mean_lo, -e));
        L.z = d / sqrt(se2);
        L.theta_hat = (x->mean - y->mean) + (x->mean_lo - y->mean_lo);
        L.se = scale2(sqrt(se2), e);
        L.t_eff = (vx + vy) / se2;
        break;
    }
    case MCSTAT_SEQ_VAR_1: {
        /* log(s^2 / sigma0^2) as the log of a quotient formed in the
         * accumulator's units: the logs themselves may be ~700 apart from
         * their difference */
        double v_s = x->m2 / (a.n - 1.0);
        L.theta_hat = log(v_s) + 2.0 * M_LN2 * x->scale;
        L.se = sqrt(a.w_logv / a.n);
        L.z = log(v_s / scale2(s->null_value, -2 * x->scale)) / L.se;
        L.t_eff = a.n;
        break;
    }
    default: { /* MCSTAT_SEQ_VAR_2 */
        double q = (x->m2 / (a.n - 1.0)) / (y->m2 / (b.n - 1.0)); /* the ratio in units of 2^(2 (ex - ey)) */
        int de = 2 * (x->scale - y->scale);
        double se2 = a.w_logv / a.n + b.w_logv / b.n;
        L.se = sqrt(se2);
        L.theta_hat = log(q) + M_LN2 * de;
        L.z = log(q / scale2(s->null_value, -de)) / L.se;
        L.t_eff = (a.w_logv + b.w_logv) / se2;
        break;
    }
    }
    /* A standard error of zero (two-point data for a variance) says nothing
     * a mixture can use: held as degenerate. */
    if (!(L.se > 0.0) || !isfinite(L.z))
        L.hold |= MCSTAT_SEQ_HOLD_DEGENERATE;
    return L;
}

/* The null value on the working scale. */
static double theta0(const mcstat_seq *s) { return on_variance(s->kind) ? log(s->null_value) : s->null_value; }

/* Takes the look at the current sums: e-value, sequence, decision. */
static void take_look(mcstat_seq *s)
{
    look L = compute_look(s);
    s->looks++;
    s->hold = L.hold;
    if (L.hold) {
        s->log_e = -INFINITY;
        return;
    }
    double a = L.t_eff * mixture_c(s->alpha, s->alternative) / s->t_opt;
    double b = boundary(a, s->alpha, s->alternative);
    s->log_e = log_e_value(L.z, a, s->alternative);
    if (s->log_e > s->log_e_max)
        s->log_e_max = s->log_e;
    double lo = s->alternative == MCSTAT_GREATER || s->alternative == MCSTAT_TWO_SIDED ? L.theta_hat - b * L.se
                                                                                          : -INFINITY;
    double hi = s->alternative == MCSTAT_LESS || s->alternative == MCSTAT_TWO_SIDED ? L.theta_hat + b * L.se
                                                                                       : INFINITY;
    /* The running intersection.  Should the looks' intervals stop
     * overlapping (the coverage is asymptotic), it shrinks to the point
     * where the last two met rather than becoming empty. */
    double nlo = fmax(s->cs[0], lo), nhi = fmin(s->cs[1], hi);
    if (nlo > nhi)
        nlo = nhi = lo > s->cs[1] ? s->cs[1] : s->cs[0];
    s->cs[0] = nlo;
    s->cs[1] = nhi;
    if (s->state == MCSTAT_SEQ_DECIDED)
        return;
    double t0 = theta0(s);
    int decision = 2;
    if (s->log_e_max >= -log(s->alpha))
        decision = s->alternative == MCSTAT_LESS      ? MCSTAT_DECISION_LESS
                   : s->alternative == MCSTAT_GREATER ? MCSTAT_DECISION_GREATER
                   : L.z < 0.0                        ? MCSTAT_DECISION_LESS
                                                      : MCSTAT_DECISION_GREATER;
    else if (s->eps > 0.0 && s->cs[0] > t0 - s->eps && s->cs[1] < t0 + s->eps)
        decision = MCSTAT_DECISION_EQUAL;
    if (decision != 2) {
        s->state = MCSTAT_SEQ_DECIDED;
        s->decision = decision;
        s->n_decided = s->x.n;
    }
}

/* ---- pushes ------------------------------------------------------------- */
static int push(mcstat_seq *s, const mcstat_moments *bx, const mcstat_moments *by)
{
    mcstat_moments x = s->x, y = s->y;
    int st = mcstat_moments_merge(&x, bx);
    if (st == MCSTAT_OK && by)
        st = mcstat_moments_merge(&y, by);
    if (st != MCSTAT_OK)
        return st;
    s->x = x;
    s->y = y;
    take_look(s);
    return MCSTAT_OK;
}

int mcstat_seq_push_moments(mcstat_seq *s, const mcstat_moments *batch)
{
    MCSTAT_IEEE_SCOPE();
    if (!seq_valid(s) || two_sample(s->kind) || !batch_valid(batch))
        return MCSTAT_EINVAL;
    return push(s, batch, NULL);
}

int mcstat_seq_push_2_moments(mcstat_seq *s, const mcstat_moments *bx, const mcstat_moments *by)
{
    MCSTAT_IEEE_SCOPE();
    if (!seq_valid(s) || !two_sample(s->kind) || !batch_valid(bx) || !batch_valid(by))
        return MCSTAT_EINVAL;
    return push(s, bx, by);
}

int mcstat_seq_push_array(mcstat_seq *s, const double *x, size_t n)
{
    MCSTAT_IEEE_SCOPE();
    if (!seq_valid(s) || two_sample(s->kind) || (!x && n > 0))
        return MCSTAT_EINVAL;
    mcstat_moments b;
    mcstat_moments_init(&b);
    int st = n ? mcstat_moments_add_array(&b, x, n) : MCSTAT_OK;
    return st ? st : push(s, &b, NULL);
}

int mcstat_seq_push_2_array(mcstat_seq *s, const double *x, size_t nx, const double *y, size_t ny)
{
    MCSTAT_IEEE_SCOPE();
    if (!seq_valid(s) || !two_sample(s->kind) || (!x && nx > 0) || (!y && ny > 0))
        return MCSTAT_EINVAL;
    mcstat_moments bx, by;
    mcstat_moments_init(&bx);
    mcstat_moments_init(&by);
    int st = nx ? mcstat_moments_add_array(&bx, x, nx) : MCSTAT_OK;
    if (st == MCSTAT_OK && ny)
        st = mcstat_moments_add_array(&by, y, ny);
    return st ? st : push(s, &bx, &by);
}

int mcstat_seq_push_stream(mcstat_seq *s, const mcstat_stream *frame)
{
    MCSTAT_IEEE_SCOPE();
    if (!seq_valid(s) || two_sample(s->kind) || !frame)
        return MCSTAT_EINVAL;
    mcstat_moments b;
    int st = mcstat__stream_moments_checked(frame, &b);
    if (st != MCSTAT_OK)
        return st;
    return push(s, &b, NULL);
}

/* ---- the result ----------------------------------------------------------- */
static const int32_t TEST_OF_KIND[] = {0, MCSTAT_TEST_SEQ_MEAN_1, MCSTAT_TEST_SEQ_MEAN_2, MCSTAT_TEST_SEQ_VAR_1,
                                       MCSTAT_TEST_SEQ_VAR_2};

int mcstat_seq_result(const mcstat_seq *s, mcstat_result *out)
{
    MCSTAT_IEEE_SCOPE();
    if (!seq_valid(s) || !out)
        return MCSTAT_EINVAL;
    mcstat_result r;
    mcstat__result_clear(&r);
    r.test = TEST_OF_KIND[s->kind];
    r.method = MCSTAT_METHOD_ASYMPTOTIC;
    r.alternative = s->alternative;
    r.n[0] = s->x.n;
    r.n[1] = two_sample(s->kind) ? s->y.n : 0;
    r.null_value = s->null_value;
    r.alpha = s->alpha;
    r.df[0] = r.df[1] = NAN;
    look L = compute_look(s);
    r.statistic = L.hold ? NAN : L.z;
    r.std_error = L.hold & MCSTAT_SEQ_HOLD_DEGENERATE ? NAN : L.se;
    r.critical[0] = -INFINITY;
    r.critical[1] = INFINITY;
    if (!L.hold) {
        double a = L.t_eff * mixture_c(s->alpha, s->alternative) / s->t_opt;
        double b = boundary(a, s->alpha, s->alternative);
        if (s->alternative != MCSTAT_GREATER)
            r.critical[0] = -b;
        if (s->alternative != MCSTAT_LESS)
            r.critical[1] = b;
    }
    r.p_value = s->log_e_max > 0.0 ? exp(-s->log_e_max) : 1.0;
    if (on_variance(s->kind)) {
        r.conf_int[0] = exp(s->cs[0]);
        r.conf_int[1] = exp(s->cs[1]);
        double vx = mcstat_moments_var(&s->x), vy = mcstat_moments_var(&s->y);
        r.estimate[0] = s->kind == MCSTAT_SEQ_VAR_1 ? vx : (isfinite(L.theta_hat) ? exp(L.theta_hat) : vx / vy);
        r.estimate[1] = NAN;
    } else {
        r.conf_int[0] = s->cs[0];
        r.conf_int[1] = s->cs[1];
        r.estimate[0] = mcstat_moments_mean(&s->x);
        r.estimate[1] = two_sample(s->kind) ? mcstat_moments_mean(&s->y) : NAN;
    }
    r.seq_state = s->state;
    r.seq_hold = (int32_t)s->hold;
    r.decision = s->state == MCSTAT_SEQ_DECIDED ? s->decision : MCSTAT_DECISION_EQUAL;
    r.reject = s->state == MCSTAT_SEQ_DECIDED && s->decision != MCSTAT_DECISION_EQUAL;
    r.seq_looks = (double)s->looks;
    r.seq_n_decided = (double)s->n_decided;
    r.seq_log_e = s->log_e;
    r.seq_log_e_max = s->log_e_max;
    r.seq_eps = s->eps;
    r.seq_t_opt = s->t_opt;
    r.seq_n_gate = s->hold & MCSTAT_SEQ_HOLD_KURTOSIS ? L.n_gate : 0.0;
    *out = r;
    return MCSTAT_OK;
}

int mcstat_seq_finish(const mcstat_seq *s, mcstat_result *out)
{
    int st = mcstat_seq_result(s, out);
    if (st != MCSTAT_OK)
        return st;
    return s->state == MCSTAT_SEQ_CONTINUE && (s->hold & MCSTAT_SEQ_HOLD_KURTOSIS) ? MCSTAT_EHEAVYTAIL : MCSTAT_OK;
}
