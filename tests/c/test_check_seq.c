/*
 * test_check_seq.c - the sequential mode of mcstat/embedded.h with checks
 * compiled in, in a renderer's frame loop (per-thread streams merged at a
 * frame's end, pushed, the frame stream re-initialised): a planted bias is
 * reported once, at the look that decided, with the n it decided at; a
 * right estimator is never reported over 200 frames; NaN frames, heavy
 * tails, the equivalence margin and bad arguments.  Fixed seeds.
 */
#define MCSTAT_CHECKS 1
#include <stdint.h>
struct report {
    int calls;
    int status;
    int has_result;
    uint64_t n;         /* the result's n[0] at the report */
    double n_decided;   /* its seq_n_decided */
    int decision;
    const char *what;
    int line;
};
static struct report rep;
struct mcstat_result;
static void record(const char *what, int line, int status, const struct mcstat_result *r);
#define MCSTAT_CHECK_ON_FAILURE(what, file, line, status, result) ((void)(file), record((what), (line), (status), (result)))
#include "mcstat/embedded.h"

#include "harness.h"

#include <string.h>

static void record(const char *what, int line, int status, const mcstat_result *r)
{
    rep.calls++;
    rep.status = status;
    rep.what = what;
    rep.line = line;
    rep.has_result = r != NULL;
    if (r) {
        rep.n = r->n[0];
        rep.n_decided = r->seq_n_decided;
        rep.decision = r->decision;
    }
}

static uint64_t rng;
static double unif(void) /* splitmix64, 53 bits, in (0, 1) */
{
    uint64_t z = (rng += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}

#define NTHREADS 4
#define PER_THREAD 250 /* samples per thread and frame: 1000 per frame */
#define PI 3.141592653589793

/* A cosine-weighted-like estimator of 1.5 pi: pi (1 + mu^2), mu = sqrt(u);
 * the bug draws mu = u^0.45 (mean pi (1 + 1/1.9), 1.7% high). */
static double estimate(int bug)
{
    double u = unif();
    double mu = bug ? pow(u, 0.45) : sqrt(u);
    return PI * (1.0 + mu * mu);
}

/* Renders `frames` frames through the macros; returns the frame at which
 * the push first evaluated to 1 (-1 if never) and counts the 1s. */
static int frame_loop(mcstat_seq *bias, int frames, int bug, int *ones)
{
    mcstat_stream acc[NTHREADS], frame;
    int first = -1;
    *ones = 0;
    for (int f = 0; f < frames; f++) {
        MCSTAT_CHECK_INIT(frame);
        for (int t = 0; t < NTHREADS; t++) {
            MCSTAT_CHECK_INIT(acc[t]);
            for (int i = 0; i < PER_THREAD; i++)
                MCSTAT_CHECK_ADD(acc[t], estimate(bug));
            MCSTAT_CHECK_MERGE(frame, acc[t]);
        }
        if (MCSTAT_CHECK_SEQ_PUSH(*bias, frame)) {
            (*ones)++;
            if (first < 0)
                first = f;
        }
    }
    return first;
}

static void test_planted_bias_fires_once(void)
{
    memset(&rep, 0, sizeof rep);
    rng = 7;
    mcstat_seq bias;
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, 1.5 * PI, 0.001);
    int ones;
    int first = frame_loop(&bias, 200, 1, &ones);
    CHECK_MSG(first >= 0, "the bias was never reported");
    CHECK_INT(rep.calls, 1);
    CHECK_INT(rep.status, MCSTAT_OK);
    CHECK(rep.has_result);
    /* reported at the deciding look, with the n it decided at */
    uint64_t n_at = (uint64_t)(first + 1) * NTHREADS * PER_THREAD;
    CHECK_INT(rep.n, n_at);
    CHECK(rep.n_decided == (double)n_at);
    CHECK_INT(bias.n_decided, n_at);
    CHECK_INT(rep.decision, MCSTAT_DECISION_GREATER);
    /* a decision is final: every later push evaluates to 1, none reports */
    CHECK_INT(ones, 200 - first);
    CHECK(strstr(rep.what, "sequential mean of") != NULL);
    printf("planted bias (1.7%%): reported once, at frame %d, n = %llu\n", first,
           (unsigned long long)rep.n);
    /* a bias certain within a few frames, not at the end of the run */
    CHECK_MSG(first < 100, "frame %d", first);
    CHECK_INT(MCSTAT_CHECK_SEQ_FINISH(bias), 1);
    CHECK_INT(rep.calls, 1); /* already reported */
}

static void test_right_estimator_never_fires(void)
{
    memset(&rep, 0, sizeof rep);
    rng = 11;
    mcstat_seq bias;
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, 1.5 * PI, 0.001);
    int ones;
    CHECK_INT(frame_loop(&bias, 200, 0, &ones), -1);
    CHECK_INT(ones, 0);
    CHECK_INT(rep.calls, 0);
    CHECK_INT(bias.looks, 200);
    CHECK_INT(bias.x.n, 200 * NTHREADS * PER_THREAD);
    CHECK_INT(bias.hold, 0);
    CHECK_INT(MCSTAT_CHECK_SEQ_FINISH(bias), 0);
    CHECK_INT(rep.calls, 0);
}

/* With a margin the check stops, passed for good, once the mean is shown
 * within reference +- eps. */
static void test_margin_passes(void)
{
    memset(&rep, 0, sizeof rep);
    rng = 13;
    mcstat_seq close;
    MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(close, 1.5 * PI, 0.05, 0.001);
    int ones;
    CHECK_INT(frame_loop(&close, 200, 0, &ones), -1);
    CHECK_INT(rep.calls, 0);
    CHECK_INT(close.state, MCSTAT_SEQ_DECIDED);
    CHECK_INT(close.decision, MCSTAT_DECISION_EQUAL);
    CHECK_INT(MCSTAT_CHECK_SEQ_FINISH(close), 0);
}

static void test_nan_frame_and_bad_arguments(void)
{
    memset(&rep, 0, sizeof rep);
    rng = 17;
    mcstat_seq bias;
    mcstat_stream frame;
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, 1.5 * PI, 0.001);
    MCSTAT_CHECK_INIT(frame);
    for (int i = 0; i < 300; i++)
        MCSTAT_CHECK_ADD(frame, estimate(0));
    CHECK_INT(MCSTAT_CHECK_SEQ_PUSH(bias, frame), 0);
    mcstat_seq before = bias;
    MCSTAT_CHECK_ADD(frame, NAN); /* buffered, not yet flushed */
    CHECK_INT(MCSTAT_CHECK_SEQ_PUSH(bias, frame), 1);
    CHECK_INT(rep.calls, 1);
    CHECK_INT(rep.status, MCSTAT_ENONFINITE);
    CHECK(!rep.has_result);
    CHECK(memcmp(&before, &bias, sizeof bias) == 0);

    /* alpha outside (0, 1): the test stays empty and every push says so */
    memset(&rep, 0, sizeof rep);
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, 1.0, 1.5);
    CHECK_INT(bias.version, 0);
    MCSTAT_CHECK_INIT(frame);
    MCSTAT_CHECK_ADD(frame, 1.0);
    CHECK_INT(MCSTAT_CHECK_SEQ_PUSH(bias, frame), 1);
    CHECK_INT(MCSTAT_CHECK_SEQ_PUSH(bias, frame), 1);
    CHECK_INT(rep.calls, 2);
    CHECK_INT(rep.status, MCSTAT_EINVAL);
    CHECK_INT(MCSTAT_CHECK_SEQ_FINISH(bias), 1);
    CHECK_INT(rep.status, MCSTAT_EINVAL);
    MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(bias, 1.0, -0.1, 0.01);
    CHECK_INT(bias.version, 0);
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, INFINITY, 0.01);
    CHECK_INT(bias.version, 0);
}

/* A run too short for its heavy tail: FINISH reports that no verdict was
 * possible. */
static void test_heavy_tail_at_finish(void)
{
    memset(&rep, 0, sizeof rep);
    rng = 19;
    mcstat_seq bias;
    mcstat_stream frame;
    MCSTAT_CHECK_SEQ_MEAN_INIT(bias, 0.0, 0.001);
    for (int f = 0; f < 6; f++) {
        MCSTAT_CHECK_INIT(frame);
        for (int i = 0; i < 100; i++) /* 99% zeros, 1% exponential of mean 100 */
            MCSTAT_CHECK_ADD(frame, unif() < 0.01 ? -100.0 * log(unif()) : 0.0);
        CHECK_INT(MCSTAT_CHECK_SEQ_PUSH(bias, frame), 0);
    }
    CHECK_INT(bias.hold, MCSTAT_SEQ_HOLD_KURTOSIS);
    CHECK_INT(rep.calls, 0);
    CHECK_INT(MCSTAT_CHECK_SEQ_FINISH(bias), 1);
    CHECK_INT(rep.calls, 1);
    CHECK_INT(rep.status, MCSTAT_EHEAVYTAIL);
}

int main(void)
{
    test_planted_bias_fires_once();
    test_right_estimator_never_fires();
    test_margin_passes();
    test_nan_frame_and_bad_arguments();
    test_heavy_tail_at_finish();
    return h_report("test_check_seq");
}
