/*
 * threads.c - the per-pixel tests' threads (special.h): a range split into
 * contiguous pieces, one per thread, the first on the caller's thread.
 *
 * Threads are started only when the caller asks for more than one
 * (mcstat_pixels_options.threads), and every piece's work is a pure
 * function of its indices, so results never depend on the number of
 * threads or on where the pieces split.  Threads start with the default
 * floating-point environment of this process; each piece's entry point
 * sets IEEE defaults itself.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <pthread.h>

#define MAX_THREADS 64

typedef struct {
    mcstat__range_fn f;
    void *ctx;
    size_t begin, end;
    int status;
} piece;

static void *run_piece(void *arg)
{
    piece *p = arg;
    p->status = p->f(p->ctx, p->begin, p->end);
    return NULL;
}

int mcstat__run_ranges(size_t begin, size_t end, int threads, size_t min_per_thread, mcstat__range_fn f, void *ctx)
{
    size_t n = end - begin, t = threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : (size_t)threads;
    if (min_per_thread && n / min_per_thread < t)
        t = n / min_per_thread;
    if (t <= 1)
        return f(ctx, begin, end);
    piece pc[MAX_THREADS];
    pthread_t th[MAX_THREADS];
    int started[MAX_THREADS] = {0};
    for (size_t i = 0; i < t; i++) {
        pc[i].f = f;
        pc[i].ctx = ctx;
        pc[i].begin = begin + n / t * i + (i < n % t ? i : n % t);
        pc[i].end = pc[i].begin + n / t + (i < n % t ? 1 : 0);
        pc[i].status = MCSTAT_OK;
    }
    for (size_t i = 1; i < t; i++)
        started[i] = pthread_create(&th[i], NULL, run_piece, &pc[i]) == 0;
    run_piece(&pc[0]);
    for (size_t i = 1; i < t; i++) {
        if (started[i])
            pthread_join(th[i], NULL);
        else
            run_piece(&pc[i]); /* could not start: here, afterwards */
    }
    for (size_t i = 0; i < t; i++)
        if (pc[i].status != MCSTAT_OK)
            return pc[i].status;
    return MCSTAT_OK;
}
