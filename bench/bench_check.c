/*
 * bench_check.c - the cost of an embedded check per added sample.
 *
 *   add      mcstat_stream_add on values already in memory (store, counter,
 *            a flush through mcstat_moments_add_array every 492 values);
 *   loop     a Monte Carlo loop (splitmix64, a sqrt, a sum) without and with
 *            mcstat_stream_add of each estimate: the difference is what a
 *            renderer pays per sample;
 *   moments  mcstat_moments_add per value, for comparison (a full merge);
 *   frames   the same loop in frames (a stream re-initialised per frame) of
 *            1024 and 65536 samples, through mcstat/embedded.h's macros:
 *            without checks, with MCSTAT_CHECK_ADD and a fixed-n
 *            MCSTAT_CHECK_MEAN per frame, and with MCSTAT_CHECK_ADD and the
 *            sequential MCSTAT_CHECK_SEQ_PUSH per frame (one look);
 *   push     mcstat_seq_push_stream alone, per look: a frame of 65536
 *            values (100 of them still buffered), a flushed stream (the
 *            O(1) look itself), and a one-sided test (its boundary a
 *            root-find); mcstat_stream_check_mean per frame for comparison.
 * Each figure is the median of `reps` runs (default 7, at most 64), one
 * thread, with the fastest and slowest run beside it; the overhead is the
 * median of the per-run differences (each run times both loops back to
 * back, so a slow moment of the shared machine hits both).
 * usage: bench_check [reps]
 */
#define MCSTAT_CHECKS 1
/* failures are counted, not printed: the figures are the cost of checking;
 * the counts show the fixed-n check's false alarms (every frame tested
 * alone) against the sequential check's (at most alpha over a whole run) */
static long fixed_failures, seq_failures;
#define MCSTAT_CHECK_ON_FAILURE(what, file, line, status, result)                    \
    ((void)(file), (void)(line), (void)(status), (void)(result),                     \
     *(what) == 's' ? seq_failures++ : fixed_failures++) /* "sequential mean of" */
#include "mcstat/embedded.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static inline double uniform01(uint64_t *s)
{
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return ((double)(z >> 11) + 0.5) * 0x1p-53;
}

static volatile double sink;

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Prints "label median [min-max] unit" of t[0..reps-1] (sorted in place). */
static void show(const char *label, double *t, int reps, const char *unit)
{
    qsort(t, (size_t)reps, sizeof *t, cmp_double);
    double med = reps % 2 ? t[reps / 2] : 0.5 * (t[reps / 2 - 1] + t[reps / 2]);
    printf("%-38s %.2f %s [%.2f-%.2f]\n", label, med, unit, t[0], t[reps - 1]);
}

__attribute__((noinline)) static double loop_plain(long n, uint64_t seed)
{
    double sum = 0.0;
    for (long i = 0; i < n; i++) {
        double mu = sqrt(uniform01(&seed));
        sum += 3.141592653589793 * (1.0 + mu * mu);
    }
    return sum;
}

__attribute__((noinline)) static double loop_checked(long n, uint64_t seed, mcstat_stream *s)
{
    double sum = 0.0;
    for (long i = 0; i < n; i++) {
        double mu = sqrt(uniform01(&seed));
        double e = 3.141592653589793 * (1.0 + mu * mu);
        sum += e;
        mcstat_stream_add(s, e);
    }
    return sum;
}

#define REFERENCE (1.5 * 3.141592653589793) /* the loops' expected estimate */

/* n samples in frames of per_frame: mode 0 no check, 1 MCSTAT_CHECK_ADD and
 * a fixed-n MCSTAT_CHECK_MEAN per frame, 2 MCSTAT_CHECK_ADD and
 * MCSTAT_CHECK_SEQ_PUSH per frame.  The frame body is loop_plain or
 * loop_checked, the loops timed above. */
static double frames(long n, long per_frame, uint64_t seed, int mode, mcstat_stream *frame, mcstat_seq *seq)
{
    double sum = 0.0;
    for (long f = 0; f < n / per_frame; f++) {
        if (mode == 0) {
            sum += loop_plain(per_frame, seed + (uint64_t)f);
            continue;
        }
        MCSTAT_CHECK_INIT(*frame);
        sum += loop_checked(per_frame, seed + (uint64_t)f, frame);
        if (mode == 1)
            sum += MCSTAT_CHECK_MEAN(*frame, REFERENCE, 0.0, 0.001);
        else
            sum += MCSTAT_CHECK_SEQ_PUSH(*seq, *frame);
    }
    return sum;
}

/* ns per look of `looks` pushes of the same frame into a fresh test. */
static double push_ns(const mcstat_stream *frame, int alternative, long looks)
{
    mcstat_seq_options o;
    mcstat_seq_options_init(&o);
    o.alternative = alternative;
    mcstat_seq q;
    mcstat_seq_init(&q, MCSTAT_SEQ_MEAN_1, REFERENCE, &o);
    double t = now();
    for (long k = 0; k < looks; k++)
        sink = mcstat_seq_push_stream(&q, frame);
    t = now() - t;
    if (q.hold) /* a held look skips the mixture: the figure would be too low */
        fprintf(stderr, "bench_check: the pushed test still holds (%u)\n", q.hold);
    return t / (double)looks * 1e9;
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 7;
    if (reps < 1)
        reps = 1;
    if (reps > 64)
        reps = 64;
    const long n = 20000000;
    double *v = malloc(65536 * sizeof *v);
    uint64_t seed = 1;
    for (int i = 0; i < 65536; i++)
        v[i] = uniform01(&seed);
    double t_add[64], t_plain[64], t_checked[64], t_over[64], t_mom[64];
    static const long frame_sizes[2] = {1024, 65536};
    double t_fr[2][3][64], t_fr_over[2][2][64];
    double t_push[64], t_push_flushed[64], t_push_one[64], t_fixed[64];
    const long looks = 100000;
    mcstat_stream s;
    mcstat_stream pushed; /* a frame of 65536 estimates: 100 still buffered */
    mcstat_stream_init(&pushed);
    (void)loop_checked(65536, 7, &pushed);
    mcstat_stream flushed = pushed;
    mcstat_stream_flush(&flushed);
    for (int r = 0; r < reps; r++) {
        mcstat_stream_init(&s);
        double t = now();
        for (long i = 0; i < n; i++)
            mcstat_stream_add(&s, v[i & 65535]);
        t = now() - t;
        t_add[r] = t / n * 1e9;

        t = now();
        sink = loop_plain(n, 42 + r);
        t = now() - t;
        t_plain[r] = t / n * 1e9;

        mcstat_stream_init(&s);
        t = now();
        sink = loop_checked(n, 42 + r, &s);
        t = now() - t;
        t_checked[r] = t / n * 1e9;
        t_over[r] = t_checked[r] - t_plain[r];

        mcstat_moments m;
        mcstat_moments_init(&m);
        t = now();
        for (long i = 0; i < n / 10; i++)
            mcstat_moments_add(&m, v[i & 65535]);
        t = now() - t;
        t_mom[r] = t / (n / 10) * 1e9;

        for (int k = 0; k < 2; k++) {
            for (int mode = 0; mode < 3; mode++) {
                mcstat_seq seq;
                MCSTAT_CHECK_SEQ_MEAN_INIT(seq, REFERENCE, 0.001);
                long nf = n / frame_sizes[k] * frame_sizes[k];
                t = now();
                sink = frames(nf, frame_sizes[k], 42 + (uint64_t)r, mode, &s, &seq);
                t = now() - t;
                t_fr[k][mode][r] = t / (double)nf * 1e9;
            }
            t_fr_over[k][0][r] = t_fr[k][1][r] - t_fr[k][0][r];
            t_fr_over[k][1][r] = t_fr[k][2][r] - t_fr[k][0][r];
        }

        t_push[r] = push_ns(&pushed, MCSTAT_TWO_SIDED, looks);
        t_push_flushed[r] = push_ns(&flushed, MCSTAT_TWO_SIDED, looks);
        t_push_one[r] = push_ns(&pushed, MCSTAT_GREATER, looks);
        t = now();
        for (long k = 0; k < looks; k++) {
            mcstat_result res;
            sink = mcstat_stream_check_mean(&pushed, REFERENCE, 0.0, 0.001, &res);
        }
        t = now() - t;
        t_fixed[r] = t / (double)looks * 1e9;
    }
    printf("median [fastest-slowest] of %d runs\n", reps);
    show("mcstat_stream_add on stored values:", t_add, reps, "ns per value");
    show("Monte Carlo loop without checks:", t_plain, reps, "ns per sample");
    show("Monte Carlo loop with mcstat_stream:", t_checked, reps, "ns per sample");
    show("overhead of the check per sample:", t_over, reps, "ns");
    show("mcstat_moments_add (for comparison):", t_mom, reps, "ns per value");
    for (int k = 0; k < 2; k++) {
        printf("frames of %ld samples (a stream re-initialised per frame):\n", frame_sizes[k]);
        show("  without checks:", t_fr[k][0], reps, "ns per sample");
        show("  ADD + fixed-n CHECK_MEAN per frame:", t_fr[k][1], reps, "ns per sample");
        show("  ADD + CHECK_SEQ_PUSH per frame:", t_fr[k][2], reps, "ns per sample");
        show("  overhead, fixed-n check:", t_fr_over[k][0], reps, "ns per sample");
        show("  overhead, sequential check:", t_fr_over[k][1], reps, "ns per sample");
    }
    printf("one look (per frame):\n");
    show("  mcstat_seq_push_stream, 65536 values:", t_push, reps, "ns per look");
    show("  the same, stream flushed (the look):", t_push_flushed, reps, "ns per look");
    show("  the same, one-sided (root-find):", t_push_one, reps, "ns per look");
    show("  mcstat_stream_check_mean (fixed-n):", t_fixed, reps, "ns per check");
    printf("checks failed on the right estimator (silent hook): fixed-n %ld of %ld frames, sequential %ld of "
           "%d runs\n", fixed_failures, (long)reps * (n / frame_sizes[0] + n / frame_sizes[1]), seq_failures,
           2 * reps);
    free(v);
    return 0;
}
