/* Renders of a baked model against the double-precision reference (runtime/ref), point by point.
 *
 * Linked with one model's generated files and a runtime compiled with MC_PLOT_HOOK pointing at
 * record_point below, so every point the real renderer puts on screen is recorded with its Q F
 * screen position and the address of its palette index, which names the leaf. The reference walks
 * the same leaves in double precision. For each view it checks:
 *
 *  1. every point's fixed-point position is within BOUND pixels of the exact one. The bound comes
 *     from the format: a leaf's position is the root's plus one displacement vector per level, each
 *     rounded once to Q F, so |error| <= (d + 1) / 2 units of 2^-F per axis, plus the Q30 rotation
 *     matrix rounding (entries within 2^-29, times the extent, at most the scale S) plus, in
 *     perspective, the Q24 magnification rounding times the offset from the axis:
 *       BOUND = (d + 1) * 2^-(F+1) + S * 2^-28 (+ S * 2^-23 in perspective);
 *  2. at least 99.9 % of the points drawn (by either renderer) land on the same pixel. A point can
 *     only change pixel if its exact position lies within BOUND of a pixel edge: a share of about
 *     4 * BOUND of the points (two edges, two axes), 0.06 % at d = 8, F = 15 and S = 240, so 99.9 %
 *     leaves margin while a real error of a tenth of a pixel would fail it;
 *  3. the z-buffered images agree on at least 99.5 % of the pixels (colour and coverage): points
 *     that move one pixel and depth ties may change a few pixels, not more.
 * In perspective (drawn depth >= 3) the renderer draws most leaves through linear frames
 * (config.h MC_LINEAR_ERROR): the bound becomes twice the above plus their stated error and
 * rounding; criterion 2 allows 2 * MC_LINEAR_ERROR / 256 of the points to move, and criterion 3
 * two pixels more per moved point.
 *
 * Built with -DMC_FLOAT=1 it checks the float build of the renderer (config.h) the same way, against
 * the bound of its own format. A float vector is rounded a few times relative to its size (the
 * Q30 rotation entry and the scale converted, two products: under 4 * 2^-24 of S for all levels
 * together), and each of the d additions rounds to half the float spacing at the sum, at most
 * M * 2^-24 for coordinates below M = max(w, h) + S:
 *       BOUND = (d + 4) * M * 2^-24 + S * 2^-28, doubled in perspective (the magnification, under 2
 *       at the tested eye distance, scales the error, and the division rounds once more).
 * At 320x240 and d = 8 that is 4.0e-4 px, against Q15's 1.5e-4: floats near 320 are spaced
 * 2^-15 apart, Q15 2^-15 everywhere, and each float sum rounds.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/app.h>
#include <modelc/modelc.h>
#include "ref.h"

#define MAX_POINTS (1u << 22)

typedef struct rec { const uint8_t *color; double x, y; } rec;
static rec fixed_pts[MAX_POINTS], ref_pts[MAX_POINTS];
static size_t n_fixed, n_ref;

#if MC_FLOAT
void record_point(float fx, float fy, const uint8_t *color)
{
    if (n_fixed < MAX_POINTS) fixed_pts[n_fixed++] = (rec){color, fx, fy};
}
#else
void record_point(int32_t fx, int32_t fy, const uint8_t *color)
{
    if (n_fixed < MAX_POINTS)
        fixed_pts[n_fixed++] = (rec){color, fx / (double)(1 << MC_FRAC_BITS), fy / (double)(1 << MC_FRAC_BITS)};
}
#endif

static void record_ref(const mc_ref_point *p, void *user)
{
    (void)user;
    if (p->on_screen && n_ref < MAX_POINTS) ref_pts[n_ref++] = (rec){p->color, p->sx, p->sy};
}

static int by_color_ptr(const void *a, const void *b)
{
    const uint8_t *x = ((const rec *)a)->color, *y = ((const rec *)b)->color;
    return x < y ? -1 : x > y;
}

typedef struct view_case {
    const char *name;
    double yaw, pitch, roll, zoom;
    int perspective, coarser, w, h;
} view_case;

static const view_case cases[] = {
    {"front", 0, 0, 0, 1, 0, 0, 320, 240},
    {"yaw30", 30, 0, 0, 1, 0, 0, 320, 240},
    {"yaw45-pitch20", 45, 20, 0, 1, 0, 0, 320, 240},
    {"yaw120-pitch-35-roll15", 120, -35, 15, 1, 0, 0, 320, 240},
    {"zoom2-yaw30", 30, 0, 0, 2, 0, 0, 320, 240},
    {"zoom0.5-roll90", 0, 0, 90, 0.5, 0, 0, 320, 240},
    {"zoom3-pitch60", 10, 60, 0, 3, 0, 0, 640, 480},
    {"coarse-yaw200", 200, 10, 0, 1, 0, 1, 320, 240},
    {"perspective-yaw30", 30, 10, 0, 1, 1, 0, 320, 240},
    {"perspective-zoom2-yaw-60", -60, 0, 5, 2, 1, 0, 640, 480},
};

static uint8_t ref_color[640 * 480];
static uint16_t ref_depth[640 * 480];
static double ref_z[640 * 480];

static int32_t angle(double deg) { return (int32_t)lround(deg * MC_ANGLE_FULL / 360.0); }

static int run_case(const view_case *vc)
{
    const mc_octree *scene = mc_app_model.model->octree;
    mc_view v = mc_view_default();
    v.yaw = angle(vc->yaw), v.pitch = angle(vc->pitch), v.roll = angle(vc->roll);
    v.zoom = (int32_t)lround(vc->zoom * MC_ZOOM_ONE);
    v.projection = vc->perspective ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    /* one pixel per leaf and every leaf, as the reference image draws */
    const mc_octree_options opt = {MC_SPLAT_PIXEL, 0, MC_CULL_OFF};
    const char *name = mc_app_model.model->name;
    unsigned depth = scene->depth - (unsigned)vc->coarser;
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)vc->w, (uint16_t)vc->h};
    mc_target rt = {ref_color, ref_depth, (uint16_t)vc->w, (uint16_t)vc->h};

    n_fixed = n_ref = 0;
    mc_clear(&t);
    mc_stats st;
    if (mc_octree_render(scene, &v, depth, &opt, &t, NULL, NULL, &st) != MC_OK) {
        printf("not ok - %s %s: mc_octree_render failed\n", name, vc->name);
        return 1;
    }
    mc_ref_points(scene, &v, depth, t.width, t.height, record_ref, NULL);
    mc_ref_render(scene, &v, depth, &rt, ref_z);

    qsort(fixed_pts, n_fixed, sizeof(rec), by_color_ptr);
    qsort(ref_pts, n_ref, sizeof(rec), by_color_ptr);
    size_t i = 0, j = 0, same = 0, total = 0;
    double max_err = 0;
    while (i < n_fixed || j < n_ref) {
        total++;
        if (j == n_ref || (i < n_fixed && fixed_pts[i].color < ref_pts[j].color)) { i++; continue; }
        if (i == n_fixed || ref_pts[j].color < fixed_pts[i].color) { j++; continue; }
        double ex = fabs(fixed_pts[i].x - ref_pts[j].x), ey = fabs(fixed_pts[i].y - ref_pts[j].y);
        if (ex > max_err) max_err = ex;
        if (ey > max_err) max_err = ey;
        same += floor(fixed_pts[i].x) == floor(ref_pts[j].x) && floor(fixed_pts[i].y) == floor(ref_pts[j].y);
        i++, j++;
    }
    mc_view cv = mc_view_clamp(&v, t.width, t.height);
    double s = cv.zoom / 65536.0 * (t.width < t.height ? t.width : t.height);
#if MC_FLOAT
    double m = (t.width > t.height ? t.width : t.height) + s;
    double bound = ((depth + 4) * m * ldexp(1, -24) + s * ldexp(1, -28)) * (vc->perspective ? 2 : 1);
#else
    double bound = (depth + 1) * ldexp(1, -(MC_FRAC_BITS + 1)) + s * ldexp(1, -28) + (vc->perspective ? s * ldexp(1, -23) : 0);
#endif
    /* perspective, linear frames (config.h MC_LINEAR_ERROR): their stated error plus their vectors'
     * rounding, the exact path's errors counted twice (see tests/stress/stress.c) */
    const double lin = vc->perspective && depth >= 3 && MC_LINEAR_ERROR
                           ? MC_LINEAR_ERROR / 256.0 + 26 * ldexp(1, -(MC_FRAC_BITS + 1)) + s * ldexp(1, -22) : 0;
    /* the frames' axis steps are rounded before they are magnified (stress.c): the magnification at
     * the tested eye (2 cube sides) is under 2 */
    if (lin > 0) bound = 2 * bound + lin + 48 * ldexp(1, -(MC_FRAC_BITS + 1));
    size_t npix = (size_t)t.width * t.height, pix_same = 0;
    for (size_t p = 0; p < npix; p++) {
        int a = t.depth[p] != MC_DEPTH_EMPTY, b = rt.depth[p] != MC_DEPTH_EMPTY;
        pix_same += a == b && (!a || t.color[p] == rt.color[p]);
    }
    double share = total ? (double)same / total : 0, pix_share = (double)pix_same / npix;
    /* a point off by e on an axis, its exact position spread evenly within its pixel, changes pixel
     * with probability e on that axis: with linear frames at most 2 * MC_LINEAR_ERROR / 256 of the
     * points move (about a tenth of that in practice: the bound is for the worst point of a node);
     * each moved point changes at most two pixels */
    double min_share = lin > 0 ? 1 - 2 * (MC_LINEAR_ERROR / 256.0) : 0.999;
    double min_pix = 0.995 - (lin > 0 ? 2.0 * (total - same) / npix : 0);
    int ok = total > 1000 && share >= min_share && max_err <= bound && pix_share >= min_pix;
    printf("%s - %s %s: %zu points, %.4f%% on the same pixel, max error %.2e px (bound %.2e), "
           "%.3f%% of pixels equal\n",
           ok ? "ok" : "not ok", name, vc->name, total, 100 * share, max_err, bound, 100 * pix_share);
    return !ok;
}

int main(void)
{
    int failed = 0;
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) failed += run_case(&cases[c]);
    return failed != 0;
}
