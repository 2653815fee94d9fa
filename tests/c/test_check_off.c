/*
 * test_check_off.c - with MCSTAT_CHECKS off, the macros of mcstat/embedded.h
 * expand to nothing: no argument is evaluated, no mcstat symbol is needed
 * (this file is linked without libmcstat), and the checks read as passed.
 */
#include "mcstat/embedded.h"

#include "harness.h"

static int evaluated;
double touch(double x);
double touch(double x)
{
    evaluated++;
    return x;
}

/* a declaration that exists only with checks on: here it must vanish */
MCSTAT_CHECK_ONLY(static mcstat_stream not_declared;)

struct per_thread {
    double sum;
    MCSTAT_CHECK_ONLY(mcstat_stream acc; mcstat_seq seq;)
};

int main(void)
{
    struct per_thread t = {0};
    CHECK_INT(sizeof t, sizeof(double)); /* the member is not there */
    MCSTAT_CHECK_INIT(t.acc);
    for (int i = 0; i < 100; i++) {
        t.sum += i;
        MCSTAT_CHECK_ADD(t.acc, touch(i));
    }
    MCSTAT_CHECK_MERGE(t.acc, t.acc);
    CHECK_INT(MCSTAT_CHECK_MEAN(t.acc, touch(1.0), touch(0.0), 0.01), 0);
    CHECK_INT(MCSTAT_CHECK_VAR_BELOW(t.acc, touch(1.0), 0.01), 0);
    /* the sequential mode: the test and the frame exist only with checks on */
    MCSTAT_CHECK_SEQ_MEAN_INIT(t.seq, touch(1.0), touch(0.01));
    MCSTAT_CHECK_SEQ_MEAN_INIT_EPS(t.seq, touch(1.0), touch(0.1), touch(0.01));
    CHECK_INT(MCSTAT_CHECK_SEQ_PUSH(t.seq, t.acc), 0);
    CHECK_INT(MCSTAT_CHECK_SEQ_FINISH(t.seq), 0);
    MCSTAT_CHECK_SEQ_PUSH(t.seq, t.acc); /* value ignored */
    MCSTAT_CHECK_ONLY(evaluated += 1000;)
    CHECK_INT(evaluated, 0);
    CHECK(t.sum == 4950.0);
    return h_report("test_check_off");
}
