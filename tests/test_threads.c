/* test_threads.c - the tools' parallel-for (tools/pn_threads.c): its pool of kept workers
 * hands every item of every job out exactly once, for job sizes from 1 item up and thread
 * counts that grow the pool, while a second host thread runs jobs of its own at the same
 * time (one of the two then finds the pool busy and starts threads of its own).
 *
 * A lost wakeup (a worker or the caller left waiting on a condition nobody signals again)
 * hangs a parallel-for forever. The two host threads therefore run under a watchdog: the
 * main thread waits for both with a deadline, and when it passes it names the job each host
 * is stuck in and fails at once, instead of leaving the hang to ctest's timeout. */
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "pn_test.h"
#include "pn_threads.h"

enum { ITEMS = 3000, JOBS = 2000 };

/* The watchdog's deadline for both hosts' 2 x JOBS jobs, which take about 0.3 s on this
 * project's two-core machine: a wide margin for a loaded or emulated one, and well inside
 * ctest's 300 s. A build can lower it (-DWATCHDOG_SECONDS=3) to try the watchdog against a
 * pool with a signal taken out. */
#ifndef WATCHDOG_SECONDS
#define WATCHDOG_SECONDS 120
#endif

typedef struct host_run {
    uint32_t hits[ITEMS];
    uint32_t wrong; /* jobs with an item not run exactly once */
    uint32_t items; /* items run in all */
    uint32_t job;   /* the job in progress (atomic; JOBS when done) */
} host_run;

static void count_items(void *task, uint32_t begin, uint32_t end)
{
    host_run *r = (host_run *)task;
    for (; begin < end; begin++) __atomic_fetch_add(&r->hits[begin], 1u, __ATOMIC_RELAXED);
}

static void *host(void *arg)
{
    host_run *r = (host_run *)arg;
    uint32_t j, i;
    for (j = 0; j < JOBS; j++) {
        uint32_t n = 1u + (j * 37u) % ITEMS;
        pn_threads th;
        memset(&th, 0, sizeof(th));
        th.count = 1 + (int)(j % 6u); /* 1 .. 6 threads: the pool grows to 5 workers */
        memset(r->hits, 0, sizeof(r->hits));
        __atomic_store_n(&r->job, j, __ATOMIC_RELEASE);
        pn_threads_parallel_for(&th, n, count_items, r);
        for (i = 0; i < n; i++) {
            r->items += r->hits[i];
            if (r->hits[i] != 1u) {
                r->wrong++;
                break;
            }
        }
    }
    __atomic_store_n(&r->job, (uint32_t)JOBS, __ATOMIC_RELEASE);
    return NULL;
}

static host_run runs[2];

/* Waits until both hosts are done or the deadline passes; on a hang, prints where each host
 * is and ends the process with a failure (the stuck threads cannot be joined). */
static void watchdog(void)
{
    struct timespec nap = {0, 10 * 1000 * 1000};
    uint64_t t0 = pn_threads_now_ns(NULL);
    for (;;) {
        uint32_t a = __atomic_load_n(&runs[0].job, __ATOMIC_ACQUIRE);
        uint32_t b = __atomic_load_n(&runs[1].job, __ATOMIC_ACQUIRE);
        if (a == (uint32_t)JOBS && b == (uint32_t)JOBS) return;
        if (pn_threads_now_ns(NULL) - t0 >= (uint64_t)WATCHDOG_SECONDS * 1000000000u) {
            fprintf(stderr,
                    "test_threads: no progress after %d s: host 0 in job %u of %d, host 1 in job %u of %d "
                    "(a parallel-for that never returns: a lost wakeup in the pool?)\n",
                    WATCHDOG_SECONDS, a, JOBS, b, JOBS);
            CHECK(a == (uint32_t)JOBS && b == (uint32_t)JOBS);
            exit(pn_test_summary());
        }
        nanosleep(&nap, NULL);
    }
}

static void test_pool(void)
{
    pthread_t th[2];
    uint64_t expect = 0;
    uint32_t j;
    REQUIRE(pthread_create(&th[0], NULL, host, &runs[0]) == 0);
    REQUIRE(pthread_create(&th[1], NULL, host, &runs[1]) == 0);
    watchdog();
    REQUIRE(pthread_join(th[0], NULL) == 0);
    REQUIRE(pthread_join(th[1], NULL) == 0);
    for (j = 0; j < JOBS; j++) expect += 1u + (j * 37u) % ITEMS;
    fprintf(stderr, "parallel-for: 2 x %d jobs, %u + %u items run, %u + %u jobs wrong\n", JOBS, runs[0].items,
            runs[1].items, runs[0].wrong, runs[1].wrong);
    CHECK(runs[0].wrong == 0u && runs[1].wrong == 0u);
    CHECK(runs[0].items == expect && runs[1].items == expect);
}

int main(void)
{
    RUN(test_pool);
    return pn_test_summary();
}
