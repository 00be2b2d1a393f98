/* Template search for re-detection: see modelc/detect.h. */
#include "modelc/detect.h"
#include "modelc/imgedge.h"

typedef struct feature {
    uint32_t at;    /* y width + x */
    uint16_t x, y;
    uint8_t want;   /* the mask bits the feature's bin accepts */
} feature;

/* The features of the buffer's entries: every step-th of them in row-major order (the first, the
 * step + 1-th, ...). The entries' colours are 1 + bin (track.h). */
static uint32_t take_features(const mc_track_view *view, feature *f)
{
    const mc_sdepth *sd = view->sd;
    const uint32_t n = mc_sdepth_count(sd);
    if (!n || !sd->color) return 0;
    const uint32_t step = (n + MC_DETECT_FEATURES - 1u) / MC_DETECT_FEATURES;
    uint32_t seen = 0, k = 0;
    for (uint32_t y = sd->row_lo; y <= sd->row_hi && y < sd->height; y++) {
        const uint32_t *u = sd->used + y * sd->blocks;
        for (uint32_t b = 0; b < sd->blocks; b++)
            for (uint32_t bits = u[b]; bits;) {
                const uint32_t lead = mc_clz32(bits), x = b * 32u + lead;   /* the leftmost pixel left */
                bits &= ~(0x80000000u >> lead);
                if (seen++ % step || k == MC_DETECT_FEATURES) continue;
                const unsigned bin = (unsigned)(sd->color[y * sd->width + x] - 1u) & (MC_IMGEDGE_DIRS - 1u);
                f[k].at = y * sd->width + x, f[k].x = (uint16_t)x, f[k].y = (uint16_t)y;
                f[k].want = mc_imgedge_bin_mask(bin, view->tolerance);
                k++;
            }
    }
    return k;
}

/* The features matched with the model shifted by (dx, dy); box: the features' bounding box (x0, y0,
 * x1, y1), so that a shift that keeps all of them on the frame reads the masks without a test. */
static uint32_t count_at(const mc_track_view *view, const feature *f, uint32_t n, const int32_t box[4], int32_t dx,
                         int32_t dy)
{
    const int32_t w = view->cam->width, h = view->cam->height;
    uint32_t c = 0;
    if (box[0] + dx >= 0 && box[1] + dy >= 0 && box[2] + dx < w && box[3] + dy < h) {
        /* every at + d is then on the frame (the sum, not a pointer moved before the array) */
        const int32_t d = dy * w + dx;
        for (uint32_t i = 0; i < n; i++) c += (view->masks[(int32_t)f[i].at + d] & f[i].want) != 0;
        return c;
    }
    for (uint32_t i = 0; i < n; i++) {
        const int32_t x = f[i].x + dx, y = f[i].y + dy;
        if ((uint32_t)x >= (uint32_t)w || (uint32_t)y >= (uint32_t)h) continue;
        c += (view->masks[y * w + x] & f[i].want) != 0;
    }
    return c;
}

/* The best shift of the grid (cx + i step, cy + j step), |i|, |j| <= r, into *bx, *by; its count. */
static uint32_t best_of(const mc_track_view *view, const feature *f, uint32_t n, const int32_t box[4], int32_t cx,
                        int32_t cy, int32_t r, int32_t step, int32_t *bx, int32_t *by)
{
    uint32_t best = 0;
    *bx = cx, *by = cy;
    for (int32_t j = -r; j <= r; j++)
        for (int32_t i = -r; i <= r; i++) {
            const uint32_t c = count_at(view, f, n, box, cx + i * step, cy + j * step);
            if (c > best) best = c, *bx = cx + i * step, *by = cy + j * step;
        }
    return best;
}

uint32_t mc_detect_shift(const mc_track_view *view, const mc_pose *pose, int32_t reach, int32_t stride, int32_t *dx,
                         int32_t *dy)
{
    feature f[MC_DETECT_FEATURES];
    mc_track_score s;
    *dx = *dy = 0;
    if (stride < 1 || reach < 0 || mc_track_score_pose(view, pose, &s) != MC_OK) return 0;
    const uint32_t n = take_features(view, f);
    if (!n) return 0;
    int32_t box[4] = {f[0].x, f[0].y, f[0].x, f[0].y}, x, y;
    for (uint32_t i = 1; i < n; i++) {
        if (f[i].x < box[0]) box[0] = f[i].x;
        if (f[i].y < box[1]) box[1] = f[i].y;
        if (f[i].x > box[2]) box[2] = f[i].x;
        if (f[i].y > box[3]) box[3] = f[i].y;
    }
    best_of(view, f, n, box, 0, 0, reach / stride, stride, &x, &y);
    return best_of(view, f, n, box, x, y, stride - 1, 1, dx, dy);
}

/* camera.h's range of a coordinate, um */
#define T_MAX (((int64_t)1 << 28) - 1)

static int32_t clamp_um(int64_t v) { return (int32_t)(v > T_MAX ? T_MAX : v < -T_MAX ? -T_MAX : v); }

void mc_detect_move(const mc_camera *cam, const int32_t t[3], int32_t dx, int32_t dy, int32_t out[3])
{
    /* |d| <= 2^16 pixels, |z| < 2^28 um: the products below 2^61 */
    out[0] = clamp_um((int64_t)t[0] + (int64_t)dx * t[2] * 65536 / cam->px);
    out[1] = clamp_um((int64_t)t[1] + (int64_t)dy * t[2] * 65536 / cam->py);
    out[2] = t[2];
}
