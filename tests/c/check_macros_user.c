/*
 * check_macros_user.c - a renderer's translation unit using every macro of
 * mcstat/embedded.h, compiled as C and as C++ with checks on and off by
 * check_macros_warnings.sh, which fails on any warning.  The values each
 * check reads are kept in variables used by nothing else: with checks off
 * they must not become "unused"; a check also stands as a statement, its
 * value ignored.
 */
#include <mcstat/embedded.h>

static double sample(int i)
{
    return 0.5 + 0.001 * i;
}

struct worker {
    double sum;
    MCSTAT_CHECK_ONLY(mcstat_stream acc;)
};

int render_frame(struct worker *w, int nworkers, int n);
int render_frame(struct worker *w, int nworkers, int n)
{
    MCSTAT_CHECK_ONLY(mcstat_stream frame;)
    const double reference = 0.5, tolerance = 0.1, bound = 1.0, alpha = 0.001;
    MCSTAT_CHECK_INIT(frame);
    for (int t = 0; t < nworkers; t++) {
        MCSTAT_CHECK_INIT(w[t].acc);
        for (int i = 0; i < n; i++) {
            double estimate = sample(i); /* read only by the check */
            MCSTAT_CHECK_ADD(w[t].acc, estimate);
            w[t].sum += sample(i);
        }
        MCSTAT_CHECK_MERGE(frame, w[t].acc);
    }
    int failed = 0;
    if (MCSTAT_CHECK_MEAN(frame, reference, tolerance, alpha))
        failed++;
    if (MCSTAT_CHECK_VAR_BELOW(frame, bound, alpha))
        failed++;
    float single = 0.25f; /* a float estimate, a set-but-only-checked variable */
    single = single * 2.0f;
    MCSTAT_CHECK_ADD(frame, single);
    MCSTAT_CHECK_MEAN(frame, reference, tolerance, alpha); /* value ignored */
    MCSTAT_CHECK_VAR_BELOW(frame, bound, alpha);
    return failed;
}

/* The sequential mode: a test kept across frames, pushed each frame. */
int render_frames(struct worker *w, int nworkers, int n, int frames);
int render_frames(struct worker *w, int nworkers, int n, int frames)
{
    MCSTAT_CHECK_ONLY(mcstat_seq bias; mcstat_seq close; mcstat_stream frame;)
    const double reference = 0.5, eps = 0.01, alpha = 0.001; /* read only by the checks */
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, reference, alpha);
    MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(close, reference, eps, alpha);
    int failed = 0;
    for (int f = 0; f < frames; f++) {
        MCSTAT_CHECK_INIT(frame);
        for (int t = 0; t < nworkers; t++) {
            MCSTAT_CHECK_INIT(w[t].acc);
            for (int i = 0; i < n; i++) {
                double estimate = sample(i + f);
                MCSTAT_CHECK_ADD(w[t].acc, estimate);
                w[t].sum += sample(i + f);
            }
            MCSTAT_CHECK_MERGE(frame, w[t].acc);
        }
        if (MCSTAT_CHECK_SEQ_PUSH(bias, frame))
            failed++;
        MCSTAT_CHECK_SEQ_PUSH(close, frame); /* value ignored */
    }
    if (MCSTAT_CHECK_SEQ_FINISH(bias))
        failed++;
    MCSTAT_CHECK_SEQ_FINISH(close);
    return failed;
}
