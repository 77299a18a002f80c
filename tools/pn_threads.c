#define _POSIX_C_SOURCE 200809L
#include "pn_threads.h"

#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <time.h>
#include <unistd.h>

#define PN_THREADS_MAX 256

typedef struct pn_job {
    uint32_t count;
    uint32_t next; /* atomic */
    uint32_t done; /* atomic */
    pn_task_fn fn;
    void *task;
} pn_job;

uint64_t pn_threads_now_ns(void *user)
{
    struct timespec ts;
    (void)user;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

int pn_threads_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : (n > PN_THREADS_MAX ? PN_THREADS_MAX : (int)n);
}

static void pn_job_work(pn_job *job)
{
    for (;;) {
        uint32_t i = __atomic_fetch_add(&job->next, 1u, __ATOMIC_RELAXED);
        if (i >= job->count) return;
        job->fn(job->task, i, i + 1u);
        __atomic_fetch_add(&job->done, 1u, __ATOMIC_RELEASE);
    }
}

/* The workers, started once and kept: a pass's launch then costs a broadcast and a wait,
 * not a pthread_create and pthread_join per thread (about 45 us a launch here: MCSM's frame
 * launches 16 passes). One pool for the process; a parallel-for that finds it busy (another
 * host thread's) starts threads of its own as before. Workers end with the process.
 *
 * Between jobs a worker first watches the job counter for up to PN_POOL_SPIN_NS, then
 * blocks on a condition variable; the launching thread likewise watches for the job's end
 * before it blocks. A frame's passes follow one another within microseconds, and a
 * sleeping thread took tens of them to wake: an empty 64-item job on 2 threads cost 63 us
 * a launch blocking at once, 2 us watching first (MCSM's frame: 17 launches). Game
 * engines' job systems do the same. The counters are read and written atomically; the
 * mutex still orders the condition variables. */
#define PN_POOL_SPIN_NS 200000u

static void pn_cpu_relax(void)
{
#if defined(__x86_64__) || defined(__i386__)
    __builtin_ia32_pause();
#elif defined(__aarch64__)
    __asm__ __volatile__("yield");
#endif
}

/* Watches *v for up to PN_POOL_SPIN_NS while it is (is_value 1) or is not (0) `value`. */
static void pn_spin(const uint64_t *v, uint64_t value, int is_value)
{
    uint64_t t0 = pn_threads_now_ns(NULL);
    uint32_t k = 0;
    while ((__atomic_load_n(v, __ATOMIC_ACQUIRE) == value) == is_value) {
        pn_cpu_relax();
        if ((++k & 63u) == 0u && pn_threads_now_ns(NULL) - t0 > PN_POOL_SPIN_NS) return;
    }
}
#define pn_spin_while(v, same) pn_spin((v), (same), 1)
#define pn_spin_until(v, value) pn_spin((v), (value), 0)
typedef struct pn_pool {
    pthread_mutex_t mu;
    pthread_cond_t wake, idle;
    pn_job *job;    /* the current job */
    uint64_t gen;   /* jobs posted so far (atomic) */
    int workers;    /* threads started */
    int want;       /* workers that take part in the current job (index < want) */
    uint64_t active; /* of those, still working (atomic) */
    int busy;       /* a parallel-for owns the pool */
    uint64_t start[PN_THREADS_MAX]; /* gen when worker i was started: it serves the jobs after */
} pn_pool;

static pn_pool pn_the_pool = {PTHREAD_MUTEX_INITIALIZER, PTHREAD_COND_INITIALIZER, PTHREAD_COND_INITIALIZER, NULL, 0, 0, 0, 0, 0, {0}};

static void *pn_pool_worker(void *arg)
{
    pn_pool *p = &pn_the_pool;
    int index = (int)(intptr_t)arg;
    uint64_t seen;
    pthread_mutex_lock(&p->mu);
    seen = p->start[index];
    for (;;) {
        pn_job *job;
        if (__atomic_load_n(&p->gen, __ATOMIC_ACQUIRE) == seen) {
            pthread_mutex_unlock(&p->mu);
            pn_spin_while(&p->gen, seen);
            pthread_mutex_lock(&p->mu);
        }
        while (__atomic_load_n(&p->gen, __ATOMIC_ACQUIRE) == seen) pthread_cond_wait(&p->wake, &p->mu);
        seen = p->gen;
        if (index >= p->want) continue;
        job = p->job;
        pthread_mutex_unlock(&p->mu);
        pn_job_work(job);
        pthread_mutex_lock(&p->mu);
        if (__atomic_sub_fetch(&p->active, 1u, __ATOMIC_ACQ_REL) == 0u) pthread_cond_signal(&p->idle);
    }
    return NULL;
}

/* Takes the pool with at least `helpers` workers for one job; 0: busy, or no threads. */
static int pn_pool_begin(pn_job *job, int helpers)
{
    pn_pool *p = &pn_the_pool;
    pthread_mutex_lock(&p->mu);
    if (p->busy) {
        pthread_mutex_unlock(&p->mu);
        return 0;
    }
    while (p->workers < helpers) {
        pthread_t t;
        p->start[p->workers] = p->gen;
        if (pthread_create(&t, NULL, pn_pool_worker, (void *)(intptr_t)p->workers) != 0) break;
        pthread_detach(t);
        p->workers++;
    }
    if (p->workers < helpers) helpers = p->workers;
    p->busy = 1;
    p->job = job;
    p->want = helpers;
    __atomic_store_n(&p->active, (uint64_t)helpers, __ATOMIC_RELEASE);
    __atomic_store_n(&p->gen, p->gen + 1u, __ATOMIC_RELEASE);
    pthread_cond_broadcast(&p->wake);
    pthread_mutex_unlock(&p->mu);
    return 1;
}

/* Waits for the job's workers and frees the pool. */
static void pn_pool_end(void)
{
    pn_pool *p = &pn_the_pool;
    pn_spin_until(&p->active, 0u);
    pthread_mutex_lock(&p->mu);
    while (__atomic_load_n(&p->active, __ATOMIC_ACQUIRE) > 0u) pthread_cond_wait(&p->idle, &p->mu);
    p->job = NULL;
    p->busy = 0;
    pthread_mutex_unlock(&p->mu);
}

static void *pn_job_thread(void *arg)
{
    pn_job_work((pn_job *)arg);
    return NULL;
}

void pn_threads_parallel_for(void *user, uint32_t count, pn_task_fn fn, void *task)
{
    pn_threads *th = (pn_threads *)user;
    pthread_t tid[PN_THREADS_MAX];
    int n = th ? th->count : 1, started = 0, pooled = 0, i;
    pn_job job;
    uint64_t t0 = pn_threads_now_ns(NULL), last = t0;
    int shown = 0;
    if (n < 1) n = 1;
    if (n > PN_THREADS_MAX) n = PN_THREADS_MAX;
    if ((uint32_t)n > count) n = (int)count;
    job.count = count;
    job.next = 0;
    job.done = 0;
    job.fn = fn;
    job.task = task;
    if (n > 1) pooled = pn_pool_begin(&job, n - 1);
    if (!pooled)
        for (i = 1; i < n; i++)
            if (pthread_create(&tid[started], NULL, pn_job_thread, &job) == 0) started++;
    if (th && th->progress) {
        /* The caller works too, but checks the clock between items. */
        for (;;) {
            uint32_t it = __atomic_fetch_add(&job.next, 1u, __ATOMIC_RELAXED);
            uint64_t now;
            if (it >= job.count) break;
            fn(task, it, it + 1u);
            __atomic_fetch_add(&job.done, 1u, __ATOMIC_RELEASE);
            now = pn_threads_now_ns(NULL);
            if (now - t0 > 1000000000u && now - last > 500000000u) {
                uint32_t d = __atomic_load_n(&job.done, __ATOMIC_ACQUIRE);
                fprintf(stderr, "\r%s: %3u%%", th->label ? th->label : "working",
                        (unsigned)((uint64_t)d * 100u / job.count));
                shown = 1;
                last = now;
            }
        }
    } else {
        pn_job_work(&job);
    }
    if (pooled) pn_pool_end();
    for (i = 0; i < started; i++) pthread_join(tid[i], NULL);
    if (shown) fprintf(stderr, "\r%s: 100%%\n", th->label ? th->label : "working");
}
