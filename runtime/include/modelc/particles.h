/* The tracker's particle filter over camera poses (Isard and Blake's Condensation, as Klein and
 * Murray and Kissling et al. run it): each frame, particles are drawn from the last frame's weights,
 * moved by a random motion, joined by a few placed at random (to find the object again after it was
 * lost), and weighed by the score of their pose (track.h).
 *
 * Promise (mc_filter_step), with N particles of which F are fresh:
 *   1. resampling: N - F particles drawn from the previous ones by systematic resampling, exactly in
 *      integers: particle i is drawn floor or ceil of (N - F) w_i / W times (W the sum of the
 *      weights), one with weight 0 never; when every weight is 0, the first N - F are kept as they are;
 *   2. motion: each drawn particle's translation moves by a random step per axis (the sum of four
 *      uniform integers in [-step_t, step_t], halved: mean 0, standard deviation step_t / sqrt(3));
 *      in 6-DOF mode its orientation turns by a random small rotation (the quaternion times
 *      (1, e1, e2, e3), each e a step of step_r in Q30, made unit length again); in 3-DOF mode
 *      every particle takes the frame's given orientation (the paper's IMU);
 *   3. re-detection: F fresh particles with translations uniform in the box [lo, hi] and, in 6-DOF
 *      mode, orientations from four steps of 2^28 made unit length (spread over every rotation) or,
 *      with fresh_r, the last estimate's turned as in the motion by steps of fresh_r (a random
 *      search over all rotations rarely lands near the object's; one around the last estimate
 *      finds it again after a jump of a few tens of degrees); in 3-DOF mode the given orientation.
 *      With layers > 1 and recall > 0, while the last confidence is below detect_below, the
 *      first `detect` of them take, instead of a translation from the box, the last estimate's
 *      moved by the image shift that fits their orientation best (detect.h: mc_detect_shift within
 *      detect_reach pixels on a grid of detect_stride, then mc_detect_move): a random translation
 *      and orientation land in the true pose's basin about once in a million draws, an orientation
 *      with the translation the image gives often enough to find the object within a few frames.
 *      Not while the estimate is confident: there a proposal fitted to the image's edges at a
 *      wrong orientation pulls the weighted mean off a pose that holds (the real cube at 320x240
 *      shows it; the tracker's --detect-below 1.01 searches in every frame). Not without the
 *      recall term either: an orientation whose shifted lines fit a part of the object's (one
 *      face's outline) matches all of them, as the object's own pose does, and only the count of
 *      matched pixels tells the two apart;
 *   4. weighing: each particle's pose scored (mc_track_score_pose); r = matched / visible in Q16;
 *      weight 2^(sharpness (r - 1)) in Q16, its exponent truncated to sixteenths (65536 at r = 1,
 *      halving every 1/sharpness of r below, at most 2^(1/16) times the exact value), or 0 where
 *      fewer than min_visible line pixels are visible;
 *   4a. recall, in the layers after the first (4b) when recall > 0 (mc_filter_recall): each weight
 *      then times 2^(-recall (1 - m / M)), m the particle's matched pixels and M the most of any
 *      particle with a weight, the exponent truncated to sixteenths as in 4: a pose that explains
 *      fewer of the image's edge pixels than the best one loses weight even when all its own lines
 *      match (r = 1), as a cube seen nearly face on does when it hides a side face the image shows.
 *      Not in the first layer, whose fresh particles lie anywhere in the box: there a pose nearer
 *      the camera shows more lines, and would match more edge pixels by chance;
 *   4b. with layers L > 1, L - 1 more rounds on the same frame: all N particles drawn again from the
 *      weights just found (systematic resampling) and moved by the steps halved each round (step_t
 *      and step_r shifted right by the round's number), no fresh ones, and weighed again (4, then 4a)
 *      against the view's fine masks when it has them (an annealed search: N L scores, a finer look
 *      around the likely poses with a sharper likelihood: edges within a smaller radius);
 *   5. the estimate: the weighted mean of the translations and of the orientations (each turned to
 *      the hemisphere of the heaviest particle's, then made unit length); its own score against the
 *      view's masks (the coarse ones) gives the confidence, r of the estimate in Q16 (0 when it
 *      shows fewer than min_visible pixels).
 * Random numbers: a PCG32 stream (rng.h) seeded at init, so the same frames give the same poses on
 * every machine. Memory: the caller's, two arrays of N particles; no heap, no floating point.
 * Work: N L + 1 scores a frame, plus N L for the motion and the resampling, plus `detect` searches
 * (a score and a mask read per feature and shift each). Freestanding.
 */
#ifndef MODELC_PARTICLES_H
#define MODELC_PARTICLES_H

#include <stdint.h>
#include "rng.h"
#include "track.h"

typedef struct mc_particle {
    int32_t q[4];               /* orientation: unit quaternion (w, x, y, z), Q30 */
    int32_t t[3];               /* translation, um */
    uint32_t weight;            /* Q16, 0 .. 65536 */
    uint32_t visible, matched;  /* its score */
} mc_particle;

typedef struct mc_filter_params {
    uint32_t particles;         /* N, >= 1 */
    uint32_t fresh;             /* F < N placed at random each frame */
    int32_t step_t;             /* translation step per frame, um (see the promise), >= 0 */
    int32_t step_r;             /* orientation step per frame, Q30 (2^30 / 100: about 1 degree), >= 0 */
    int32_t fresh_r;            /* fresh particles' turn from the estimate, as step_r; 0: any orientation */
    int32_t lo[3], hi[3];       /* the box fresh translations are drawn in, um, lo <= hi, within +-(2^28 - 1) */
    uint32_t min_visible;       /* fewer visible line pixels weigh 0 */
    uint8_t sharpness;          /* 1 .. 64: how fast the weight falls as r drops */
    uint8_t recall;             /* 0 .. 64: how fast it falls, in the layers after the first, as the
                                 * matched count drops below the best particle's (step 4a); 0: not at all */
    uint32_t detect;            /* of the F fresh ones, placed by an image search (step 3), <= F */
    uint16_t detect_reach;      /* the search's reach, pixels (detect.h), <= 1024 */
    uint8_t detect_stride;      /* its coarse grid, pixels, 1 .. 16 */
    uint32_t detect_below;      /* the search runs only while the confidence is below this (Q16) */
    uint8_t dof;                /* 6, or 3 (orientation given each frame) */
    uint8_t layers;             /* 0 or 1: one weighing a frame; 2 .. 4: that many (see the promise) */
} mc_filter_params;

typedef struct mc_filter {
    mc_filter_params prm;
    mc_particle *p, *spare;     /* the caller's, N each */
    mc_rng rng;
    mc_particle estimate;       /* after each step: the pose, and its own score */
    uint32_t confidence;        /* the estimate's r, Q16 */
} mc_filter;

/* Starts with every particle at pose (q, t), equal weights. Returns MC_OK, or MC_ERR_ARG for a null
 * array, N = 0 or above 65535, F >= N, detect > F, with detect a stride of 0 or above 16 or a reach
 * above 1024, a step (or fresh_r) below 0 or above 2^28, lo > hi, a box or
 * t beyond +-(2^28 - 1), a sharpness outside 1 .. 64, a recall above 64, dof not 3 or 6, layers above 4,
 * or q = 0.
 * Translations stay within +-(2^28 - 1) um as they move. */
int mc_filter_init(mc_filter *f, const mc_filter_params *prm, mc_particle *p, mc_particle *spare, uint64_t seed,
                   const int32_t q[4], const int32_t t[3]);

/* One frame (see the promise): view holds the frame's edge masks; orientation (Q30, 3-DOF mode only,
 * else ignored) the frame's given orientation. Returns MC_OK, or what scoring returned. */
int mc_filter_step(mc_filter *f, const mc_track_view *view, const int32_t orientation[4]);

/* Step 1 on its own: m draws (m <= n) from the n particles of src (n <= 65535) into dst by
 * systematic resampling, one number from r. */
void mc_filter_resample(mc_rng *r, const mc_particle *src, uint32_t n, mc_particle *dst, uint32_t m);

/* The weight of a score under f's parameters (step 4), Q16. */
uint32_t mc_filter_weight(const mc_filter *f, uint32_t visible, uint32_t matched);

/* Step 4a on its own: the weights of the n particles of p (each as step 4 gave it from its score)
 * scaled by their recall under f's parameters; nothing when f's recall is 0. */
void mc_filter_recall(const mc_filter *f, mc_particle *p, uint32_t n);

#endif
