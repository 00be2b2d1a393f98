/* The tracker's particle filter on the synthetic cube sequence (tests/track/cube_scene.h), for
 * tests/bench/track.sh: per frame, the frame's edge masks are made from the true pose (not timed),
 * then mc_filter_step runs (timed; callgrind: --toggle-collect=mc_filter_step). Prints the median
 * time of a step, the pose errors against the truth and the frames within 5 mm and 3 degrees and
 * within 5 cm and 5 degrees; with --poses, each frame's estimate first ("pose K q0 q1 q2 q3 t0 t1 t2":
 * Q30, um), so that two builds can be compared pose for pose.
 *   track_frames [--particles N] [--fresh F] [--size WxH] [--frames K] [--dof 3|6] [--seed S] [--poses]
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "timing.h"
#include "../track/cube_scene.h"

int main(int argc, char **argv)
{
    unsigned n = 300, fresh = 100, w = 320, h = 180, frames = 60, dof = 6;
    unsigned long seed = 1;
    int poses = 0;
    for (int i = 1; i < argc; i += 2) {
        if (!strcmp(argv[i], "--poses")) { poses = 1; i--; continue; }
        if (i + 1 >= argc) {
            fprintf(stderr, "track_frames: %s: missing value\n", argv[i]);
            return 2;
        }
        if (!strcmp(argv[i], "--particles")) n = (unsigned)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--fresh")) fresh = (unsigned)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--size") && sscanf(argv[i + 1], "%ux%u", &w, &h) == 2) continue;
        else if (!strcmp(argv[i], "--frames")) frames = (unsigned)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--dof")) dof = (unsigned)atoi(argv[i + 1]);
        else if (!strcmp(argv[i], "--seed")) seed = strtoul(argv[i + 1], 0, 10);
        else {
            fprintf(stderr, "track_frames: unknown option %s\n", argv[i]);
            return 2;
        }
    }
    cube_scene s;
    if (cube_scene_new(&s, w, h)) {
        fprintf(stderr, "track_frames: cannot set up a %ux%u scene\n", w, h);
        return 1;
    }
    mc_filter_params prm = cube_scene_params();
    prm.particles = n, prm.fresh = fresh, prm.dof = (uint8_t)dof;
    mc_particle *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
    double *ms = malloc(frames * sizeof *ms), *et = malloc(frames * sizeof *et), *er = malloc(frames * sizeof *er);
    int32_t q[4], t[3];
    cube_scene_truth(0, q, t);
    t[0] += 9000, t[1] -= 9000, t[2] += 8000;   /* starting 15 mm off */
    mc_filter f;
    if (!a || !b || !ms || !et || !er || mc_filter_init(&f, &prm, a, b, seed, q, t) != MC_OK) {
        fprintf(stderr, "track_frames: bad settings\n");
        return 1;
    }
    unsigned fine = 0, coarse = 0;
    for (unsigned k = 0; k < frames; k++) {
        cube_scene_truth((int)k, q, t);
        if (cube_scene_frame(&s, q, t)) return 1;
        const double t0 = mc_host_now_ms();
        if (mc_filter_step(&f, &s.view, q) != MC_OK) return 1;
        ms[k] = mc_host_now_ms() - t0;
        et[k] = cube_scene_distance(f.estimate.t, t) / 1000, er[k] = cube_scene_angle(f.estimate.q, q);
        if (poses)
            printf("pose %u %ld %ld %ld %ld %ld %ld %ld\n", k, (long)f.estimate.q[0], (long)f.estimate.q[1], (long)f.estimate.q[2],
                   (long)f.estimate.q[3], (long)f.estimate.t[0], (long)f.estimate.t[1], (long)f.estimate.t[2]);
        fine += et[k] < 5 && er[k] < 3;
        coarse += et[k] < 50 && er[k] < 5;
    }
    printf("particles %u fresh %u size %ux%u dof %u frames %u\n", n, fresh, w, h, dof, frames);
    printf("ms per frame (median) %.4f\n", mc_host_median(ms, frames));
    printf("translation error mm (median) %.2f\n", mc_host_median(et, frames));
    printf("rotation error deg (median) %.2f\n", mc_host_median(er, frames));
    printf("frames within 5 mm and 3 deg %u\n", fine);
    printf("frames within 5 cm and 5 deg %u\n", coarse);
    free(a), free(b), free(ms), free(et), free(er);
    cube_scene_free(&s);
    return 0;
}
