/* pn_threads.h - the CLI's parallel-for on pthreads, for pn_set_parallel_for(). Work items
 * are handed out one at a time through an atomic counter, so idle cores take the next
 * one; the library's results do not depend on the schedule. The worker threads are started
 * once, for the process, and wait between jobs (a job that finds them busy with another
 * host thread's starts threads of its own). With progress on, a pass that runs longer than
 * a second prints its percentage to stderr. */
#ifndef PN_TOOLS_THREADS_H
#define PN_TOOLS_THREADS_H

#include <stdint.h>

#include "penumbra/penumbra.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pn_threads {
    int count;        /* threads, including the caller */
    int progress;     /* 1: report long passes on stderr */
    const char *label;
} pn_threads;

/* Matches pn_parallel_for_fn; user is a pn_threads*. */
void pn_threads_parallel_for(void *user, uint32_t count, pn_task_fn fn, void *task);

/* Online cores (at least 1). */
int pn_threads_cores(void);

/* Monotonic nanoseconds; matches pn_clock_fn (user unused). */
uint64_t pn_threads_now_ns(void *user);

#ifdef __cplusplus
}
#endif
#endif
