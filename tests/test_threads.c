/* test_threads.c - the tools' parallel-for (tools/pn_threads.c): its pool of kept workers
 * hands every item of every job out exactly once, for job sizes from 1 item up and thread
 * counts that grow the pool, while a second host thread runs jobs of its own at the same
 * time (one of the two then finds the pool busy and starts threads of its own). */
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "pn_test.h"
#include "pn_threads.h"

enum { ITEMS = 3000, JOBS = 2000 };

typedef struct host_run {
    uint32_t hits[ITEMS];
    uint32_t wrong; /* jobs with an item not run exactly once */
    uint32_t items; /* items run in all */
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
        pn_threads_parallel_for(&th, n, count_items, r);
        for (i = 0; i < n; i++) {
            r->items += r->hits[i];
            if (r->hits[i] != 1u) {
                r->wrong++;
                break;
            }
        }
    }
    return NULL;
}

static host_run runs[2];

static void test_pool(void)
{
    pthread_t other;
    uint64_t expect = 0;
    uint32_t j;
    REQUIRE(pthread_create(&other, NULL, host, &runs[1]) == 0);
    host(&runs[0]);
    REQUIRE(pthread_join(other, NULL) == 0);
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
