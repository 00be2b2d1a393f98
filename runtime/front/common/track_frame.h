/* The tracker's settings, its start and its per-frame pipeline: what the host tracker
 * (../track/tracker.c, NAME-track) and the firmware tracker (../fw/track_main.c) both run, so that
 * the same frames, camera and start pose give the same poses on both, bit for bit.
 *
 * Promise:
 *   - mc_track_settings_default: the tracker's defaults (NAME-track --help lists them);
 *   - mc_track_camera_fixed: the camera of a frame shrunk k times (a k x k box average) from the
 *     camera's own frames: pixel i of the shrunk frame covers pixels k i .. k i + k - 1, so the
 *     intrinsics become px / k, py / k, (u0 + 1/2) / k - 1/2 and (v0 + 1/2) / k - 1/2, each times
 *     65536 rounded to nearest (halves away from zero, as lround), in double precision; near and
 *     far in micrometres, rounded the same way; then mc_camera_init;
 *   - mc_track_filter_params: the filter's parameters from the settings and the start translation
 *     t (um): steps in um and Q30 half-angles, rounded as above, the box of fresh translations t +-
 *     search mm clamped to +-(2^28 - 1) um, fresh = particles / 3 when settings.fresh < 0;
 *   - mc_track_start: the sparse depth buffer over the app binding's buffers (app.h), its matched
 *     bits kept and cleared, the scoring view, and the filter at pose (q, t) with the seed;
 *   - mc_track_edges: the frame into app->edges_frame (a k x k box average of src, rounded to
 *     nearest, or for k = 1 a copy), its edges (mc_imgedge at the threshold), optionally those codes
 *     copied to codes, then spread into masks (mc_imgedge_masks at the radius) and, with more than
 *     one layer and a fine radius below the radius, into fine masks in the frame's buffer (the
 *     later layers' sharper likelihood, particles.h); then the caller runs
 *     mc_filter_step(&t->f, &t->view, ...) (the two stages apart, so that either side times them);
 *   - MC_TRACK_POSE_LINE / MC_TRACK_POSE_ARGS: one line per frame of the estimate's integer fields,
 *     "pose K q0 q1 q2 q3 t0 t1 t2 visible matched confidence", printed the same on every machine.
 * The arithmetic in doubles is IEEE-754 additions, multiplications and divisions only (no library
 * function), correctly rounded on every machine, so the integers are the same everywhere. No heap;
 * freestanding (the frame copy may become a memcpy call, which every front end's C library has).
 */
#ifndef MODELC_FRONT_TRACK_FRAME_H
#define MODELC_FRONT_TRACK_FRAME_H

#include <stdint.h>
#include <modelc/app.h>
#include <modelc/camera.h>
#include <modelc/particles.h>

typedef struct mc_track_settings {
    long particles, fresh;          /* fresh < 0: particles / 3 */
    long layers, threshold, radius, fine_radius, tolerance, sharpness, recall, min_visible;
    long detect, detect_reach, detect_stride;
    double step_t_mm, step_r_deg, fresh_r_deg, search_mm, near_m, far_m, detect_below;
    unsigned long seed;
    int dof;                        /* 6, or 3 with an orientation a frame */
} mc_track_settings;

/* The defaults: 100 particles, fresh -1 (a third), 3 layers (300 scores a frame, as the paper's 300
 * particles, but the later two with the sharper masks: on ViSP's cube sequence this follows ViSP's
 * tracker more closely than one layer of 300), threshold 30, radius 2 (fine radius 1, for the later
 * layers), tolerance 1,
 * sharpness 32, recall 4, min_visible 20, detect 16 (of the fresh ones, placed by the image search within
 * 64 pixels on a grid of 3 while the confidence is below 0.9: detect.h), steps 5 mm and 2 degrees, fresh turn 15 degrees, search 60 mm,
 * near 0.02 m, far 20 m, seed 1, 6 DOF. */
void mc_track_settings_default(mc_track_settings *s);

/* Rounded to nearest, halves away from zero (lround's rounding), for |x| < 2^31. */
int32_t mc_track_round(double x);

/* Returns mc_camera_init's result. */
int mc_track_camera_fixed(mc_camera *cam, double px, double py, double u0, double v0, unsigned long k, uint16_t w,
                          uint16_t h, double near_m, double far_m);

void mc_track_filter_params(const mc_track_settings *s, const int32_t t[3], mc_filter_params *prm);

typedef struct mc_track_state {
    const mc_app *app;
    uint16_t w, h;                  /* the frame as tracked: the camera's width and height */
    uint16_t threshold;
    uint8_t radius;
    int fine_radius;                /* the later layers' masks' radius, or -1: one set of masks */
    mc_sdepth sd;
    mc_track_view view;             /* points at sd and at the caller's camera */
    mc_filter f;
} mc_track_state;

enum { MC_TRACK_START_OK = 0, MC_TRACK_START_SDEPTH = 1, MC_TRACK_START_FILTER = 2 };

/* cam (mc_track_camera_fixed's, cam->width x cam->height within the binding's screen) must outlive
 * t. Returns MC_TRACK_START_OK, MC_TRACK_START_SDEPTH (the depth buffer could not be set up) or
 * MC_TRACK_START_FILTER (mc_filter_init refused the parameters). */
int mc_track_start(mc_track_state *t, const mc_app *app, const mc_camera *cam, const mc_track_settings *s,
                   const int32_t q[4], const int32_t t_um[3]);

/* src: the frame before shrinking, src_w pixels a row, at least k t->w x k t->h; codes: NULL, or
 * t->w x t->h bytes for the edge codes before spreading; grey: NULL, or t->w x t->h bytes for the
 * shrunk frame (with layers > 1 and a fine radius below the radius, the frame's own buffer goes on
 * to hold the fine masks, t->view.fine). Returns mc_imgedge's edge pixel count. */
uint32_t mc_track_edges(mc_track_state *t, const uint8_t *src, unsigned src_w, unsigned k, uint8_t *codes, uint8_t *grey);

/* printf(MC_TRACK_POSE_LINE, MC_TRACK_POSE_ARGS(k, &t->f)): casts to long so that int32_t (long on
 * arm-none-eabi, int on x86-64) prints the same everywhere. */
#define MC_TRACK_POSE_LINE "pose %ld %ld %ld %ld %ld %ld %ld %ld %lu %lu %lu\n"
#define MC_TRACK_POSE_ARGS(k, f)                                                                           \
    (long)(k), (long)(f)->estimate.q[0], (long)(f)->estimate.q[1], (long)(f)->estimate.q[2],                  \
        (long)(f)->estimate.q[3], (long)(f)->estimate.t[0], (long)(f)->estimate.t[1], (long)(f)->estimate.t[2], \
        (unsigned long)(f)->estimate.visible, (unsigned long)(f)->estimate.matched, (unsigned long)(f)->confidence

#endif
