/**
 * @file nlsubdiv_pool.h
 * @brief A ready-made thread pool for nls_subdivide_options::executor (C99, POSIX threads).
 *
 * The library starts no thread itself: each pass of a level is split into disjoint output
 * ranges that a host's pool runs (nls_executor in nlsubdiv.h), and the output, the report
 * and the errors are the same bits for every thread count. This header is that pool for a C
 * host that has none of its own: header-only, every function `static inline`, nothing to link but
 * the C library's POSIX threads (`-pthread` on older systems).
 *
 * @code
 *   #include <nlsubdiv_pool.h>
 *   nls_pool pool;
 *   nls_pool_init(&pool, 0);                       // 0: one thread per online core
 *   nls_subdivide_options o;
 *   nls_subdivide_default_options(&o);
 *   o.executor = nls_pool_executor(&pool);         // NULL for one thread: the calling thread
 *   ... nls_mesh_subdivide(..., &o, ...) as often as wanted ...
 *   nls_pool_destroy(&pool);
 * @endcode
 *
 * The workers are started once, by nls_pool_init, and wait on a condition variable between
 * passes, so a pass costs a wake-up rather than a thread start; the calling thread takes
 * tasks too. One pool serves one pass at a time: calls from several threads that share a
 * pool take turns (each thread may also own a pool). Not async-signal-safe; do not fork
 * while a call runs.
 */
#ifndef NLSUBDIV_POOL_H
#define NLSUBDIV_POOL_H

#include <errno.h>
#include <pthread.h>
#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

#include "nlsubdiv.h"

#ifdef __cplusplus
extern "C" {
#endif

/** A persistent pool of POSIX threads; its fields are private. */
typedef struct nls_pool {
    nls_executor executor;  /**< what nls_pool_executor returns */
    unsigned threads;       /**< threads in all, the calling thread included */
    unsigned started;       /**< workers running (threads − 1 after a successful init) */
    pthread_t *workers;
    pthread_mutex_t call;  /* one pass at a time */
    pthread_mutex_t mutex; /* guards everything below */
    pthread_cond_t start, done;
    unsigned long generation;
    int stop;
    nls_task_fn task;
    void *task_context;
    uint32_t count, next;
    unsigned active;
} nls_pool;

/* Runs tasks of the current pass until none is left; called and returns with `mutex` held. */
static inline void nls_pool_take_(nls_pool *p) {
    const nls_task_fn task = p->task;
    void *const ctx = p->task_context;
    while (p->next < p->count) {
        const uint32_t i = p->next++;
        pthread_mutex_unlock(&p->mutex);
        task(ctx, i);
        pthread_mutex_lock(&p->mutex);
    }
}

/* A worker: waits for a pass (or the stop), takes its tasks, reports that it is done. */
static inline void *nls_pool_worker_(void *arg) {
    nls_pool *p = (nls_pool *)arg;
    unsigned long seen = 0;
    pthread_mutex_lock(&p->mutex);
    for (;;) {
        while (!p->stop && p->generation == seen) pthread_cond_wait(&p->start, &p->mutex);
        if (p->stop) break;
        seen = p->generation;
        nls_pool_take_(p);
        if (--p->active == 0) pthread_cond_signal(&p->done);
    }
    pthread_mutex_unlock(&p->mutex);
    return NULL;
}

/* nls_executor::run: publishes the pass, takes tasks on the calling thread, and returns once
 * every task has returned (the mutex orders the library's writes before the tasks and the
 * tasks' writes before the return). */
static inline void nls_pool_run_(void *host, uint32_t count, nls_task_fn task, void *task_context) {
    nls_pool *p = (nls_pool *)host;
    pthread_mutex_lock(&p->call);
    pthread_mutex_lock(&p->mutex);
    p->task = task;
    p->task_context = task_context;
    p->count = count;
    p->next = 0;
    p->active = p->started;
    p->generation++;
    pthread_cond_broadcast(&p->start);
    nls_pool_take_(p);
    while (p->active > 0) pthread_cond_wait(&p->done, &p->mutex);
    pthread_mutex_unlock(&p->mutex);
    pthread_mutex_unlock(&p->call);
}

/**
 * Stops and joins the workers and frees what nls_pool_init took. Call it once, when no call
 * uses the pool; after a failed nls_pool_init it is not needed (and harmless).
 */
static inline void nls_pool_destroy(nls_pool *p) {
    unsigned i;
    if (p->workers == NULL && p->started == 0) return;
    pthread_mutex_lock(&p->mutex);
    p->stop = 1;
    pthread_cond_broadcast(&p->start);
    pthread_mutex_unlock(&p->mutex);
    for (i = 0; i < p->started; i++) pthread_join(p->workers[i], NULL);
    free(p->workers);
    p->workers = NULL;
    p->started = 0;
    pthread_cond_destroy(&p->done);
    pthread_cond_destroy(&p->start);
    pthread_mutex_destroy(&p->mutex);
    pthread_mutex_destroy(&p->call);
}

/**
 * Starts a pool of `threads` threads in all, the calling thread included (0: one per online
 * core, `sysconf(_SC_NPROCESSORS_ONLN)`; at most nls_max_tasks() are used). Returns 0, or an
 * error number of pthread_create / the allocation; on failure nothing is left running and
 * nls_pool_executor returns NULL, so a call that uses it runs on the calling thread.
 */
static inline int nls_pool_init(nls_pool *p, unsigned threads) {
    unsigned i;
    int rc = 0;
    if (threads == 0) {
        const long n = sysconf(_SC_NPROCESSORS_ONLN);
        threads = n > 0 ? (unsigned)n : 1u;
    }
    if (threads > nls_max_tasks()) threads = nls_max_tasks();
    p->threads = 1;
    p->started = 0;
    p->workers = NULL;
    p->generation = 0;
    p->stop = 0;
    p->task = NULL;
    p->task_context = NULL;
    p->count = 0;
    p->next = 0;
    p->active = 0;
    p->executor.run = nls_pool_run_;
    p->executor.host_context = p;
    p->executor.max_tasks = 1;
    if (threads == 1) return 0;
    p->workers = (pthread_t *)malloc((threads - 1) * sizeof(pthread_t));
    if (p->workers == NULL) return ENOMEM;
    if ((rc = pthread_mutex_init(&p->call, NULL)) != 0) goto no_call;
    if ((rc = pthread_mutex_init(&p->mutex, NULL)) != 0) goto no_mutex;
    if ((rc = pthread_cond_init(&p->start, NULL)) != 0) goto no_start;
    if ((rc = pthread_cond_init(&p->done, NULL)) != 0) goto no_done;
    for (i = 0; i + 1 < threads; i++) {
        if ((rc = pthread_create(&p->workers[i], NULL, nls_pool_worker_, p)) != 0) {
            nls_pool_destroy(p); /* joins the ones started, frees everything */
            return rc;
        }
        p->started++;
    }
    p->threads = threads;
    p->executor.max_tasks = threads;
    return 0;
no_done:
    pthread_cond_destroy(&p->start);
no_start:
    pthread_mutex_destroy(&p->mutex);
no_mutex:
    pthread_mutex_destroy(&p->call);
no_call:
    free(p->workers);
    p->workers = NULL;
    return rc;
}

/**
 * The executor to put into nls_subdivide_options::executor: NULL when the pool has one
 * thread (every pass on the calling thread), otherwise the pool. Valid until
 * nls_pool_destroy.
 */
static inline const nls_executor *nls_pool_executor(const nls_pool *p) { return p->threads > 1 ? &p->executor : NULL; }

#ifdef __cplusplus
}
#endif

#endif
