/* Interaction timing: the coarse frame drawn while the view moves (depth D-1), the
 * fine frame drawn when it stops (depth D), and the abort latency of the fine frame, for one bake
 * (mc_app_model) at 320x240, next to the source paper's 100 ms frame period and 300 ms limit.
 *
 *   interaction [--frames N] [--trials N] [--markdown] [--size WxH]
 *
 * Frames: N views of one full turn of yaw (zoom 1, orthographic, the default splat), each timed as
 * the viewer draws it: mc_clear + mc_octree_render + mc_finish (the default fill); wall clock
 * (CLOCK_MONOTONIC) and CPU time of the thread (CLOCK_THREAD_CPUTIME_ID, which leaves out time the
 * machine spent on other processes). Median, 95th percentile and maximum.
 *
 * Abort latency: a fine frame starts; a key "arrives" at a random moment, uniform over the median
 * fine frame time; from then on the abort callback returns 1 (it compares the clock with the key's
 * time, as the viewer's callback polls the terminal). The latency is the time from the key to
 * mc_octree_render returning. The callback is polled on entering each node at depth MC_ABORT_LEVEL (4, the
 * paper's). Trials in which the frame ended before the key are not counted (no abort was needed).
 * Measured twice: on the wall clock, and on the thread's CPU clock (key time and latency in CPU time,
 * so that preemption by other processes on a shared machine does not count).
 */
#define _POSIX_C_SOURCE 200809L
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <modelc/app.h>
#include <modelc/modelc.h>
#include "timing.h"   /* runtime/front/host: clocks, medians */


typedef struct summary { double median, p95, max; } summary;
static summary summarize(double *v, int n)
{
    mc_host_sort(v, (size_t)n);
    summary s = {v[n / 2], v[(int)(0.95 * (n - 1))], v[n - 1]};
    return s;
}

typedef struct key { double at; uint32_t polls; clockid_t clock; } key;
static int key_pressed(void *user)
{
    key *k = user;
    k->polls++;
    return mc_host_clock_ms(k->clock) >= k->at;
}

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static double rnd_unit(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

int main(int argc, char **argv)
{
    int frames = 200, trials = 2000, markdown = 0;
    unsigned w = 320, h = 240;
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "--frames") && i + 1 < argc) frames = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--trials") && i + 1 < argc) trials = atoi(argv[++i]);
        else if (!strcmp(argv[i], "--markdown")) markdown = 1;
        else if (!strcmp(argv[i], "--size") && i + 1 < argc) {
            if (sscanf(argv[++i], "%ux%u", &w, &h) != 2) return 2;
        } else {
            fprintf(stderr, "usage: %s [--frames N] [--trials N] [--markdown] [--size WxH]\n", argv[0]);
            return 2;
        }
    }
    if (frames < 1 || frames > 100000 || trials < 1 || trials > 1000000) return 2;
    if (w > mc_app_model.max_width || h > mc_app_model.max_height || !w || !h) {
        fprintf(stderr, "size over the bake's %ux%u\n", mc_app_model.max_width, mc_app_model.max_height);
        return 2;
    }
    const mc_octree *scene = mc_app_model.model->octree;
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)w, (uint16_t)h};
    const unsigned fine = scene->depth, coarse = scene->depth > 1 ? scene->depth - 1u : 1u;
    double *wall = malloc(sizeof(double) * (size_t)(frames > trials ? frames : trials));
    double *cpu = malloc(sizeof(double) * (size_t)frames);
    if (!wall || !cpu) return 1;

    summary sw[2], sc[2];
    double points[2];
    unsigned depths[2] = {coarse, fine};
    for (int d = 0; d < 2; d++) {
        mc_view v = mc_view_default();
        uint64_t pts = 0;
        for (int i = -frames / 10; i < frames; i++) {   /* the first tenth warms up, untimed */
            v.yaw = (int32_t)((int64_t)MC_ANGLE_FULL * (i < 0 ? -i : i) / frames);
            mc_stats st;
            double w0 = mc_host_now_ms(), c0 = mc_host_clock_ms(CLOCK_THREAD_CPUTIME_ID);
            mc_clear(&t);
            mc_octree_render(scene, &v, depths[d], NULL, &t, NULL, NULL, &st);
            mc_finish(&t, MC_FILL_DEFAULT);
            double w1 = mc_host_now_ms(), c1 = mc_host_clock_ms(CLOCK_THREAD_CPUTIME_ID);
            if (i < 0) continue;
            wall[i] = w1 - w0;
            cpu[i] = c1 - c0;
            pts += st.points;
        }
        sw[d] = summarize(wall, frames);
        sc[d] = summarize(cpu, frames);
        points[d] = (double)pts / frames;
    }

    /* abort latency of the fine frame */
    uint32_t full_polls = 0;
    {
        key k = {1e300, 0, CLOCK_MONOTONIC};
        mc_view v = mc_view_default();
        mc_clear(&t);
        mc_octree_render(scene, &v, fine, NULL, &t, key_pressed, &k, NULL);
        full_polls = k.polls;
    }
    /* twice: on the wall clock (what a user sees, preemption by other processes included), and on
     * the thread's CPU clock (the key at a CPU-time moment, the latency in CPU time: the renderer's
     * own delay, which preemption on this shared machine does not inflate) */
    int n = 0, finished = 0, nc = 0, finished_c = 0;
    uint64_t polls_aborted = 0;
    summary lat = {0, 0, 0}, lat_cpu = {0, 0, 0};
    for (int pass = 0; pass < 2; pass++) {
        const clockid_t clk = pass ? CLOCK_THREAD_CPUTIME_ID : CLOCK_MONOTONIC;
        int m = 0, fin = 0;
        for (int i = 0; i < trials; i++) {
            mc_view v = mc_view_default();
            v.yaw = (int32_t)(rnd_unit() * MC_ANGLE_FULL);
            mc_clear(&t);
            key k = {0, 0, clk};
            mc_stats st;
            double t0 = mc_host_clock_ms(clk);
            k.at = t0 + rnd_unit() * (pass ? sc[1].median : sw[1].median);
            mc_octree_render(scene, &v, fine, NULL, &t, key_pressed, &k, &st);
            double t1 = mc_host_clock_ms(clk);
            if (!st.aborted) { fin++; continue; }
            wall[m++] = (t1 - k.at) * 1e3;   /* microseconds */
            if (!pass) polls_aborted += st.polls;
        }
        summary s = m ? summarize(wall, m) : (summary){0, 0, 0};
        if (pass) lat_cpu = s, nc = m, finished_c = fin;
        else lat = s, n = m, finished = fin;
    }

    if (markdown) {
        printf("\n## Interaction timing (coarse and fine frames, abort latency)\n\n");
        printf("Written by `tests/bench/interaction.sh` (`make bench`): `%s --frames %d --trials %d` "
               "(tests/bench/interaction.c) on %s at %ux%u, linked with the benchmarked runtime. Frames: a full turn "
               "of yaw at zoom 1, each timed as the viewer draws it (mc_clear + mc_octree_render + mc_finish with the default "
               "fill and splat); wall clock and thread CPU time (CPU time leaves out the time other processes took "
               "on this shared machine).\n\n",
               argv[0], frames, trials, mc_app_model.model->name, w, h);
        printf("| frame | depth | points | wall ms median | wall ms p95 | wall ms max | CPU ms median | CPU ms p95 | paper |\n");
        printf("|---|---:|---:|---:|---:|---:|---:|---:|---|\n");
        printf("| coarse (view moving) | %u | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f | one frame per 100 ms period: %.0fx headroom (median) |\n",
               coarse, points[0], sw[0].median, sw[0].p95, sw[0].max, sc[0].median, sc[0].p95, 100.0 / sw[0].median);
        printf("| fine (view still) | %u | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f | shown within 300 ms of the key release: %.0fx headroom (median) |\n\n",
               fine, points[1], sw[1].median, sw[1].p95, sw[1].max, sc[1].median, sc[1].p95, 300.0 / sw[1].median);
        printf("Abort latency of the fine frame (a key arrives at a uniformly random moment of the frame; the callback "
               "is polled at tree depth %d, %u times in a whole frontal fine frame, one poll every %.1f us on average): "
               "%d of %d trials aborted (%d frames ended before the key), latency from the key to mc_octree_render returning: "
               "**median %.1f us, 95th percentile %.1f us, max %.1f us** on the wall clock (which includes the time "
               "other processes held the CPU); on the thread's CPU clock (key and latency in CPU time, %d of %d "
               "aborted): **median %.1f us, 95th percentile %.1f us, max %.1f us**. The paper promises \"within a "
               "millisecond\" and budgets 300 ms from a key to the new image.\n",
               MC_ABORT_LEVEL, full_polls, sw[1].median * 1e3 / (full_polls ? full_polls : 1), n, trials, finished,
               lat.median, lat.p95, lat.max, nc, nc + finished_c, lat_cpu.median, lat_cpu.p95, lat_cpu.max);
    } else {
        printf("coarse depth %u: %.0f points, wall ms median %.3f p95 %.3f max %.3f, cpu ms median %.3f p95 %.3f\n",
               coarse, points[0], sw[0].median, sw[0].p95, sw[0].max, sc[0].median, sc[0].p95);
        printf("fine depth %u: %.0f points, wall ms median %.3f p95 %.3f max %.3f, cpu ms median %.3f p95 %.3f\n", fine,
               points[1], sw[1].median, sw[1].p95, sw[1].max, sc[1].median, sc[1].p95);
        printf("abort at depth %d: %u polls per frontal fine frame; %d of %d trials aborted (%d finished first), "
               "latency us median %.1f p95 %.1f max %.1f (mean polls before giving up %.0f); CPU clock: %d aborted, "
               "latency us median %.1f p95 %.1f max %.1f\n",
               MC_ABORT_LEVEL, full_polls, n, trials, finished, lat.median, lat.p95, lat.max,
               n ? (double)polls_aborted / n : 0.0, nc, lat_cpu.median, lat_cpu.p95, lat_cpu.max);
    }
    free(wall);
    free(cpu);
    return 0;
}
