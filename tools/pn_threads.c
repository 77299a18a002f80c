#define _POSIX_C_SOURCE 200809L
#include "pn_threads.h"

#include <pthread.h>
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

static void *pn_job_thread(void *arg)
{
    pn_job_work((pn_job *)arg);
    return NULL;
}

void pn_threads_parallel_for(void *user, uint32_t count, pn_task_fn fn, void *task)
{
    pn_threads *th = (pn_threads *)user;
    pthread_t tid[PN_THREADS_MAX];
    int n = th ? th->count : 1, started = 0, i;
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
    for (i = 0; i < started; i++) pthread_join(tid[i], NULL);
    if (shown) fprintf(stderr, "\r%s: 100%%\n", th->label ? th->label : "working");
}
