/* Finding a tracked object again in the image: for a trial orientation, where in the frame the
 * model's edges fit the image's edges best (a chamfer-style template search, as Hinterstoisser et
 * al.'s LINE-2D matches spread orientation maps), so that a re-detection particle lands on the object
 * instead of anywhere in a box. In six degrees of freedom a random translation and orientation hits
 * the basin of the true pose about once in a million draws; a trial orientation with the best shift
 * for it needs only the orientation to be near.
 *
 * Promise (mc_detect_shift), for a pose: the pose is scored (mc_track_score_pose through view, so the
 * view's buffer then holds its visible line pixels, each with its orientation bin); up to
 * MC_DETECT_FEATURES of those pixels are taken as features (pixel, bin): with n pixels, every
 * ceil(n / MC_DETECT_FEATURES)-th in row-major order, starting with the first;
 * then for every shift (dx, dy), both multiples of stride within +-reach pixels, the features whose
 * shifted pixel lies on the frame and whose mask there (view->masks: image edges within the masks'
 * radius) has a bin within view->tolerance of the feature's are counted; the shift with the most
 * (the first in order of dy, then dx, among equals) is refined the same way over the shifts within
 * +-(stride - 1) of it. *dx, *dy get the best shift and the return value its count (0, with a zero
 * shift, when the pose shows no feature).
 *
 * mc_detect_move turns a shift in pixels into the translation that moves the model by it at the
 * depth of its origin (t's z): t + (dx z / px, dy z / py, 0), the camera's focal lengths in Q16,
 * kept within camera.h's +-(2^28 - 1) um per axis (|dx|, |dy| <= 2^16, t within that range); out may
 * be t itself.
 *
 * Work: one score, then (2 reach / stride + 1)^2 + (2 stride - 1)^2 shifts times the features, a
 * mask read each. No heap, no floating point, bounded stack (the features on it: 12 bytes each). Deterministic.
 * Freestanding.
 */
#ifndef MODELC_DETECT_H
#define MODELC_DETECT_H

#include <stdint.h>
#include "track.h"

#define MC_DETECT_FEATURES 64

uint32_t mc_detect_shift(const mc_track_view *view, const mc_pose *pose, int32_t reach, int32_t stride, int32_t *dx,
                         int32_t *dy);

void mc_detect_move(const mc_camera *cam, const int32_t t[3], int32_t dx, int32_t dy, int32_t out[3]);

#endif
