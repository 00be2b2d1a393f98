/* Host timing helpers shared by the viewer's --bench and the benchmark drivers (tests/bench,
 * tests/finish, tests/accuracy): a clock in milliseconds and the median of a sample. Header-only,
 * so a driver needs only -Iruntime/front/host. POSIX clocks (compile with _POSIX_C_SOURCE >= 199309L).
 */
#ifndef MODELC_HOST_TIMING_H
#define MODELC_HOST_TIMING_H

#include <stddef.h>
#include <stdlib.h>
#include <time.h>

/* Milliseconds on clock id: CLOCK_MONOTONIC for wall-clock time, CLOCK_PROCESS_CPUTIME_ID or
 * CLOCK_THREAD_CPUTIME_ID for CPU time (which leaves out time spent preempted on a busy machine). */
static inline double mc_host_clock_ms(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static inline double mc_host_now_ms(void) { return mc_host_clock_ms(CLOCK_MONOTONIC); }

static inline int mc_host_cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Sorts v[0..n) in place; n > 0. */
static inline void mc_host_sort(double *v, size_t n) { qsort(v, n, sizeof v[0], mc_host_cmp_double); }

/* The median of v[0..n), n > 0 (the mean of the two middle values for even n); sorts v. */
static inline double mc_host_median(double *v, size_t n)
{
    mc_host_sort(v, n);
    return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

#endif
