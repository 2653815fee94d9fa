/*
 * ks_cache.c - simulated K-S null distributions kept for reuse.
 *
 * The paper's battery (1000 directions, section 3.3) tests many pairs of
 * samples at the same sizes; under H0 their simulated null distributions
 * are the same function of (nx, ny, weight, alternative, n_sim, seed, tie
 * pattern), so the first test simulates and the others look it up.  The
 * cache is an object the caller owns (the library has no global state),
 * guarded by its own mutex; entries are copied in and out, so no caller
 * ever holds a pointer into it, and eviction (least recently used, by
 * bytes) needs no reference counts.
 *
 * Copyright (C) 2026 the mcstat developers. GPL-3.0-or-later.
 */
#include "internal.h"

#include <pthread.h>
#include <stdlib.h>

typedef struct entry {
    struct entry *prev, *next;
    uint64_t n1, n2, seed;
    int64_t n_sim;
    int weight, alternative;
    size_t nblocks; /* == N when there are no ties (ends NULL) */
    uint64_t *ends;
    double *keys;
    size_t bytes;
} entry;

struct mcstat_ks_cache {
    pthread_mutex_t lock;
    size_t max_bytes, bytes;
    entry *head, *tail; /* most recently used first */
    uint64_t hits, misses, count;
};

int mcstat_ks_cache_new(size_t max_bytes, mcstat_ks_cache **cache)
{
    if (!cache)
        return MCSTAT_EINVAL;
    mcstat_ks_cache *c = calloc(1, sizeof *c);
    if (!c)
        return MCSTAT_ENOMEM;
    if (pthread_mutex_init(&c->lock, NULL) != 0) {
        free(c);
        return MCSTAT_ENOMEM;
    }
    c->max_bytes = max_bytes;
    *cache = c;
    return MCSTAT_OK;
}

static void entry_free(entry *e)
{
    free(e->ends);
    free(e->keys);
    free(e);
}

void mcstat_ks_cache_free(mcstat_ks_cache *c)
{
    if (!c)
        return;
    for (entry *e = c->head, *n; e; e = n) {
        n = e->next;
        entry_free(e);
    }
    pthread_mutex_destroy(&c->lock);
    free(c);
}

int mcstat_ks_cache_stats(const mcstat_ks_cache *cache, uint64_t *hits, uint64_t *misses, uint64_t *entries)
{
    if (!cache)
        return MCSTAT_EINVAL;
    mcstat_ks_cache *c = (mcstat_ks_cache *)cache; /* the lock is not part of the value */
    pthread_mutex_lock(&c->lock);
    if (hits)
        *hits = c->hits;
    if (misses)
        *misses = c->misses;
    if (entries)
        *entries = c->count;
    pthread_mutex_unlock(&c->lock);
    return MCSTAT_OK;
}

static int matches(const entry *e, const mcstat__ks_data *d, int64_t n_sim, uint64_t seed)
{
    if (e->n1 != d->n1 || e->n2 != d->n2 || e->weight != d->weight || e->alternative != d->alternative ||
        e->n_sim != n_sim || e->seed != seed || e->nblocks != d->nblocks)
        return 0;
    if (!d->ends)
        return e->ends == NULL;
    return e->ends && !memcmp(e->ends, d->ends, d->nblocks * sizeof *d->ends);
}

static void unlink_entry(mcstat_ks_cache *c, entry *e)
{
    if (e->prev)
        e->prev->next = e->next;
    else
        c->head = e->next;
    if (e->next)
        e->next->prev = e->prev;
    else
        c->tail = e->prev;
    e->prev = e->next = NULL;
}

static void push_front(mcstat_ks_cache *c, entry *e)
{
    e->prev = NULL;
    e->next = c->head;
    if (c->head)
        c->head->prev = e;
    c->head = e;
    if (!c->tail)
        c->tail = e;
}

int mcstat__ks_cache_get(mcstat_ks_cache *c, const mcstat__ks_data *d, int64_t n_sim, uint64_t seed, double *keys)
{
    pthread_mutex_lock(&c->lock);
    entry *e = c->head;
    while (e && !matches(e, d, n_sim, seed))
        e = e->next;
    if (e) {
        memcpy(keys, e->keys, (size_t)n_sim * sizeof *keys);
        unlink_entry(c, e);
        push_front(c, e);
        c->hits++;
    } else {
        c->misses++;
    }
    pthread_mutex_unlock(&c->lock);
    return e ? MCSTAT_OK : MCSTAT_EINVAL;
}

int mcstat__ks_cache_put(mcstat_ks_cache *c, const mcstat__ks_data *d, int64_t n_sim, uint64_t seed,
                         const double *keys)
{
    size_t nends = d->ends ? d->nblocks : 0;
    size_t bytes = sizeof(entry) + (size_t)n_sim * sizeof(double) + nends * sizeof(uint64_t);
    if (bytes > c->max_bytes)
        return MCSTAT_OK; /* would not fit even alone */
    entry *e = calloc(1, sizeof *e);
    if (!e)
        return MCSTAT_ENOMEM;
    e->keys = malloc((size_t)n_sim * sizeof *e->keys);
    e->ends = nends ? malloc(nends * sizeof *e->ends) : NULL;
    if (!e->keys || (nends && !e->ends)) {
        entry_free(e);
        return MCSTAT_ENOMEM;
    }
    memcpy(e->keys, keys, (size_t)n_sim * sizeof *keys);
    if (nends)
        memcpy(e->ends, d->ends, nends * sizeof *e->ends);
    e->n1 = d->n1;
    e->n2 = d->n2;
    e->seed = seed;
    e->n_sim = n_sim;
    e->weight = d->weight;
    e->alternative = d->alternative;
    e->nblocks = d->nblocks;
    e->bytes = bytes;

    pthread_mutex_lock(&c->lock);
    for (entry *o = c->head; o; o = o->next)
        if (matches(o, d, n_sim, seed)) { /* another thread got there first */
            pthread_mutex_unlock(&c->lock);
            entry_free(e);
            return MCSTAT_OK;
        }
    while (c->tail && c->bytes + bytes > c->max_bytes) {
        entry *old = c->tail;
        unlink_entry(c, old);
        c->bytes -= old->bytes;
        c->count--;
        entry_free(old);
    }
    push_front(c, e);
    c->bytes += bytes;
    c->count++;
    pthread_mutex_unlock(&c->lock);
    return MCSTAT_OK;
}
