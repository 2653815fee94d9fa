/*
 * threads.c - the per-pixel tests' threads (special.h): a range as a queue
 * of chunks that the threads take in turn, the first thread the caller's,
 * so that a core slowed by the machine (a shared VM's neighbour) leaves its
 * chunks to the others instead of holding up the call.
 *
 * Threads are started only when the caller asks for more than one
 * (mcstat_pixels_options.threads), and every item's work is a pure
 * function of its index, so results never depend on the number of threads
 * or on which thread took which chunk.  Threads start with the default
 * floating-point environment of this process; each worker's entry point
 * sets IEEE defaults itself.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <pthread.h>

#define MAX_THREADS 64

struct mcstat__work {
    pthread_mutex_t lock;
    size_t next, end, chunk;
};

int mcstat__work_take(mcstat__work *w, size_t *b, size_t *e)
{
    pthread_mutex_lock(&w->lock);
    size_t at = w->next;
    int some = at < w->end;
    if (some)
        w->next = w->end - at > w->chunk ? at + w->chunk : w->end;
    *b = at;
    *e = w->next;
    pthread_mutex_unlock(&w->lock);
    return some;
}

typedef struct {
    mcstat__work_fn f;
    void *ctx;
    mcstat__work *w;
    size_t first_index;
    int status;
} worker;

static void *run_worker(void *arg)
{
    worker *k = arg;
    k->first_index = SIZE_MAX;
    k->status = k->f(k->ctx, k->w, &k->first_index);
    return NULL;
}

int mcstat__run_work(size_t begin, size_t end, int threads, size_t min_per_thread, size_t granule,
                     mcstat__work_fn f, void *ctx)
{
    size_t n = end - begin, t = threads < 1 ? 1 : threads > MAX_THREADS ? MAX_THREADS : (size_t)threads;
    if (n == 0)
        return MCSTAT_OK;
    if (min_per_thread && n / min_per_thread < t)
        t = n / min_per_thread;
    if (t < 1)
        t = 1;
    /* chunks of about a sixteenth of a thread's share: a core slowed for a
     * while leaves its chunks to the others, and the last chunk to finish
     * is short; a multiple of the workers' block */
    size_t g = granule ? granule : 1, chunk = (n + 16 * t - 1) / (16 * t);
    chunk = (chunk + g - 1) / g * g;
    mcstat__work w = {PTHREAD_MUTEX_INITIALIZER, begin, end, chunk}; /* static init: cannot fail */
    worker k[MAX_THREADS];
    pthread_t th[MAX_THREADS];
    int started[MAX_THREADS] = {0};
    for (size_t i = 0; i < t; i++) {
        k[i].f = f;
        k[i].ctx = ctx;
        k[i].w = &w;
    }
    for (size_t i = 1; i < t; i++)
        started[i] = pthread_create(&th[i], NULL, run_worker, &k[i]) == 0;
    run_worker(&k[0]); /* the caller's thread; it takes whatever the others do not */
    for (size_t i = 1; i < t; i++) {
        if (started[i])
            pthread_join(th[i], NULL);
        else
            k[i].status = MCSTAT_OK; /* never ran: the others took its chunks */
    }
    pthread_mutex_destroy(&w.lock);
    int st = MCSTAT_OK;
    size_t at = SIZE_MAX;
    for (size_t i = 0; i < t; i++)
        if (k[i].status != MCSTAT_OK && k[i].first_index < at) {
            at = k[i].first_index;
            st = k[i].status;
        }
    return st;
}
