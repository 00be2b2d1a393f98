/* The tracker's settings, start and per-frame pipeline: see track_frame.h. */
#include "track_frame.h"

#include <modelc/bytes.h>
#include <modelc/imgedge.h>
#include <modelc/sdepth.h>

#define PI 3.14159265358979323846
#define BOX_MAX 268435455.0   /* the filter's translations stay within +-(2^28 - 1) um */

void mc_track_settings_default(mc_track_settings *s)
{
    s->particles = 100, s->fresh = -1, s->layers = 3, s->threshold = 30, s->radius = 2, s->fine_radius = 1, s->tolerance = 1;
    s->sharpness = 32, s->recall = 4, s->min_visible = 20;
    s->detect = 16, s->detect_reach = 64, s->detect_stride = 3, s->detect_below = 0.9;
    s->step_t_mm = 5, s->step_r_deg = 2, s->fresh_r_deg = 15, s->search_mm = 60, s->near_m = 0.02, s->far_m = 20;
    s->seed = 1, s->dof = 6;
}

int32_t mc_track_round(double x)
{
    /* the whole part by truncation, then the fraction a - i, which is exact: halves go up in magnitude */
    const double a = x < 0 ? -x : x;
    int32_t i = (int32_t)a;
    if (a - (double)i >= 0.5) i++;
    return x < 0 ? -i : i;
}

int mc_track_camera_fixed(mc_camera *cam, double px, double py, double u0, double v0, unsigned long k, uint16_t w,
                          uint16_t h, double near_m, double far_m)
{
    /* pixel i of the shrunk frame covers pixels k i .. k i + k - 1, so u' + 1/2 = (u + 1/2) / k */
    const double K = (double)k;
    const double kpx = px / K, kpy = py / K, ku0 = (u0 + 0.5) / K - 0.5, kv0 = (v0 + 0.5) / K - 0.5;
    return mc_camera_init(cam, mc_track_round(kpx * 65536), mc_track_round(kpy * 65536), mc_track_round(ku0 * 65536),
                          mc_track_round(kv0 * 65536), w, h, mc_track_round(near_m * 1e6), mc_track_round(far_m * 1e6));
}

void mc_track_filter_params(const mc_track_settings *s, const int32_t t[3], mc_filter_params *prm)
{
    prm->particles = (uint32_t)s->particles;
    prm->fresh = (uint32_t)(s->fresh < 0 ? s->particles / 3 : s->fresh);
    prm->step_t = mc_track_round(s->step_t_mm * 1000);
    prm->step_r = mc_track_round(s->step_r_deg * PI / 180 / 2 * (1 << 30));   /* half-angle */
    prm->fresh_r = mc_track_round(s->fresh_r_deg * PI / 180 / 2 * (1 << 30));
    for (int k = 0; k < 3; k++) {
        const double lo = t[k] - s->search_mm * 1000, hi = t[k] + s->search_mm * 1000;
        prm->lo[k] = (int32_t)(lo > -BOX_MAX ? lo : -BOX_MAX), prm->hi[k] = (int32_t)(hi < BOX_MAX ? hi : BOX_MAX);
    }
    prm->min_visible = (uint32_t)s->min_visible, prm->sharpness = (uint8_t)s->sharpness, prm->recall = (uint8_t)s->recall;
    prm->detect = s->detect < (long)prm->fresh ? (uint32_t)s->detect : prm->fresh;
    prm->detect_reach = (uint16_t)s->detect_reach, prm->detect_stride = (uint8_t)s->detect_stride;
    prm->detect_below = (uint32_t)mc_track_round(s->detect_below * 65536);
    prm->dof = (uint8_t)s->dof;
    prm->layers = (uint8_t)s->layers;
}

int mc_track_start(mc_track_state *t, const mc_app *app, const mc_camera *cam, const mc_track_settings *s,
                   const int32_t q[4], const int32_t t_um[3])
{
    t->app = app;
    t->w = cam->width, t->h = cam->height;
    t->threshold = (uint16_t)s->threshold, t->radius = (uint8_t)s->radius;
    t->fine_radius = s->layers > 1 && s->fine_radius < s->radius ? (int)s->fine_radius : -1;
    if (mc_sdepth_init(&t->sd, t->w, t->h, app->edges_sdepth, app->depth, app->color, 0xFFFF, 0) != MC_OK)
        return MC_TRACK_START_SDEPTH;
    const uint32_t words = MC_SDEPTH_MATCHED_WORDS(t->w, t->h);
    for (uint32_t i = 0; i < words; i++) app->edges_matched[i] = 0;
    mc_sdepth_keep_matched(&t->sd, app->edges_matched);
    t->view.model = app->model->edges, t->view.cam = cam, t->view.sd = &t->sd, t->view.masks = app->edges_masks;
    t->view.cache = app->edges_cache, t->view.tolerance = (uint8_t)s->tolerance;
    t->view.fine = t->fine_radius >= 0 ? app->edges_frame : 0;   /* the frame's buffer, once its edges are found */
    mc_filter_params prm;
    mc_track_filter_params(s, t_um, &prm);
    if (mc_filter_init(&t->f, &prm, app->particles, app->particles + app->max_particles, s->seed, q, t_um) != MC_OK)
        return MC_TRACK_START_FILTER;
    return MC_TRACK_START_OK;
}

/* a K x K box average of src (w wide) into dst ((w / K) x (h / K)), rounded */
static void shrink(const uint8_t *src, unsigned w, unsigned K, uint8_t *dst, unsigned dw, unsigned dh)
{
    if (K == 2) {   /* the usual one (640x480 frames to 320x240) without the division */
        for (unsigned y = 0; y < dh; y++) {
            const uint8_t *a = src + (uint32_t)(2 * y) * w, *b = a + w;
            uint8_t *d = dst + (uint32_t)y * dw;
            for (unsigned x = 0; x < dw; x++) d[x] = (uint8_t)((a[2 * x] + a[2 * x + 1] + b[2 * x] + b[2 * x + 1] + 2u) >> 2);
        }
        return;
    }
    const unsigned n = K * K;
    for (unsigned y = 0; y < dh; y++)
        for (unsigned x = 0; x < dw; x++) {
            unsigned s = 0;
            for (unsigned j = 0; j < K; j++)
                for (unsigned i = 0; i < K; i++) s += src[(uint32_t)(y * K + j) * w + x * K + i];
            dst[(uint32_t)y * dw + x] = (uint8_t)((s + n / 2) / n);
        }
}

uint32_t mc_track_edges(mc_track_state *t, const uint8_t *src, unsigned src_w, unsigned k, uint8_t *codes, uint8_t *grey)
{
    const mc_app *app = t->app;
    const uint32_t n = (uint32_t)t->w * t->h;
    if (k > 1) {
        shrink(src, src_w, k, app->edges_frame, t->w, t->h);
    } else if (src != app->edges_frame) {
        for (uint32_t y = 0; y < t->h; y++) mc_bytes_copy(app->edges_frame + y * t->w, src + y * src_w, t->w);
    }
    if (grey)
        for (uint32_t i = 0; i < n; i++) grey[i] = app->edges_frame[i];
    const uint32_t edges =
        mc_imgedge(app->edges_frame, t->w, t->w, t->h, t->threshold, app->edges_masks, app->edges_scratch);
    if (codes)
        for (uint32_t i = 0; i < n; i++) codes[i] = app->edges_masks[i];
    if (t->fine_radius >= 0) {   /* the grey frame is done with: its buffer takes the fine masks */
        mc_imgedge_masks(app->edges_masks, t->w, t->h, (unsigned)t->fine_radius, (uint8_t *)app->edges_scratch);
        mc_bytes_copy(app->edges_frame, app->edges_masks, n);
        mc_imgedge_spread(app->edges_masks, t->w, t->h, t->radius - (unsigned)t->fine_radius, (uint8_t *)app->edges_scratch);
    } else {
        mc_imgedge_masks(app->edges_masks, t->w, t->h, t->radius, (uint8_t *)app->edges_scratch);
    }
    return edges;
}
