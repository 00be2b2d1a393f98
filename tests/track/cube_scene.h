/* A synthetic tracking scene for tests and benchmarks (never linked into a tracker): ViSP's 84 mm
 * cube (the mbt/cube sequence's cube.cao, centred on its own origin so that a pose's translation is
 * the cube's centre), its 12 edges to match and 12 triangles to hide them, marked convex as the
 * generator marks it (the tracker's shortcut, track.h), before ViSP's cube camera
 * (mbt/cube.xml, 640x480) scaled to the frame asked for; a frame's edge masks are the cube's own
 * visible lines at the true pose, drawn by the tracker's score (mc_track_score_pose) and spread by
 * a pixel (mc_imgedge_masks): the image a perfect edge detector would give, with no clutter. The
 * truth turns about a tilted axis by 0.01 rad and drifts about 1.5 mm a frame.
 * Header only (static functions), C99 with libm. */
#ifndef MODELC_TESTS_CUBE_SCENE_H
#define MODELC_TESTS_CUBE_SCENE_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/imgedge.h>
#include <modelc/particles.h>

typedef struct cube_scene {
    uint8_t bpos[96], bline[48], bface[72], blf[48];
    mc_chunk cpos[2], cline[2], cface[2], clf[2];
    mc_edges e;
    mc_camera cam;
    mc_sdepth sd;
    unsigned w, h;
    uint32_t *bits, *matched;
    uint16_t *depth;
    uint8_t *color, *masks, *scratch;
    mc_xvertex cache[8];
    mc_track_view view;
} cube_scene;

static void cube_put16(uint8_t *b, uint32_t v) { b[0] = (uint8_t)v, b[1] = (uint8_t)(v >> 8); }

/* 0 on success */
static int cube_scene_new(cube_scene *s, unsigned w, unsigned h)
{
    static const int32_t corner[8][3] = {{0, 0, 0},         {-84000, 0, 0},     {-84000, 84000, 0},     {0, 84000, 0},
                                         {0, 0, 84000},     {-84000, 0, 84000}, {-84000, 84000, 84000}, {0, 84000, 84000}};
    static const uint32_t quad[6][4] = {{0, 4, 5, 1}, {1, 5, 6, 2}, {6, 7, 3, 2}, {3, 7, 4, 0}, {0, 1, 2, 3}, {7, 6, 5, 4}};
    static const uint32_t edge[12][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}, {4, 5}, {5, 6},
                                         {6, 7}, {7, 4}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    memset(s, 0, sizeof *s);
    for (int v = 0; v < 8; v++)
        for (int k = 0; k < 3; k++) {
            const int32_t c = corner[v][k] + (k == 0 ? 42000 : -42000);
            for (int b = 0; b < 4; b++) s->bpos[v * 12 + 4 * k + b] = (uint8_t)((uint32_t)c >> (8 * b));
        }
    for (int i = 0; i < 12; i++) cube_put16(s->bline + 4 * i, edge[i][0]), cube_put16(s->bline + 4 * i + 2, edge[i][1]);
    for (int q = 0; q < 6; q++) {
        const uint32_t *c = quad[q];
        cube_put16(s->bface + 12 * q, c[0]), cube_put16(s->bface + 12 * q + 2, c[1]), cube_put16(s->bface + 12 * q + 4, c[2]);
        cube_put16(s->bface + 12 * q + 6, c[0]), cube_put16(s->bface + 12 * q + 8, c[2]), cube_put16(s->bface + 12 * q + 10, c[3]);
    }
    s->cpos[0].data = s->bpos, s->cpos[0].size = 96;
    s->cline[0].data = s->bline, s->cline[0].size = 48;
    s->cface[0].data = s->bface, s->cface[0].size = 72;
    s->e.vertices = 8, s->e.lines = 12, s->e.faces = 12, s->e.index_bytes = 2, s->e.record_shift = 4, s->e.closed = 1;
    s->e.positions = s->cpos, s->e.line_list = s->cline, s->e.face_list = s->cface;
    /* convex: each edge's two faces (the triangles of quads q and r are 2q, 2q + 1), for the
     * tracker's shortcut (track.h) */
    for (int i = 0; i < 12; i++) {
        int n = 0;
        for (int f = 0; f < 12 && n < 2; f++) {
            const uint32_t *c = quad[f / 2];
            const uint32_t t[3] = {c[0], f % 2 ? c[2] : c[1], f % 2 ? c[3] : c[2]};
            for (int k = 0; k < 3; k++) {
                const uint32_t a = t[k], b = t[(k + 1) % 3];
                if ((a == edge[i][0] && b == edge[i][1]) || (a == edge[i][1] && b == edge[i][0])) cube_put16(s->blf + 4 * i + 2 * n++, (uint32_t)f);
            }
        }
        if (n != 2) return 1;
    }
    s->clf[0].data = s->blf, s->clf[0].size = 48;
    s->e.convex = 1, s->e.line_faces = s->clf;
    /* mbt/cube.xml: px 547.74, py 542.07, u0 338.70, v0 234.51 at 640x480; the frame w x h takes
     * the scale w / 640 and is centred on the same principal point */
    const double k = w / 640.0;
    if (mc_camera_init(&s->cam, (int32_t)(547.7367575 * k * 65536), (int32_t)(542.0744058 * k * 65536),
                       (int32_t)((338.7036994 - 320) * k * 65536 + w * 32768.0), (int32_t)((234.5083345 - 240) * k * 65536 + h * 32768.0),
                       (uint16_t)w, (uint16_t)h, 10000, 5000000) != MC_OK)
        return 1;
    s->w = w, s->h = h;
    s->bits = malloc(4u * MC_SDEPTH_WORDS(w, h)), s->matched = malloc(4u * MC_SDEPTH_MATCHED_WORDS(w, h));
    s->depth = malloc(2u * w * h), s->color = malloc(w * h), s->masks = malloc(w * h);
    s->scratch = malloc(MC_IMGEDGE_MASK_SCRATCH(w, 1));
    if (!s->bits || !s->matched || !s->depth || !s->color || !s->masks || !s->scratch) return 1;
    if (mc_sdepth_init(&s->sd, (uint16_t)w, (uint16_t)h, s->bits, s->depth, s->color, 0xFFFF, 0) != MC_OK) return 1;
    mc_sdepth_keep_matched(&s->sd, s->matched);
    s->view.model = &s->e, s->view.cam = &s->cam, s->view.sd = &s->sd, s->view.masks = s->masks;
    s->view.cache = s->cache, s->view.tolerance = 1;
    return 0;
}

static void cube_scene_free(cube_scene *s)
{
    free(s->bits), free(s->matched), free(s->depth), free(s->color), free(s->masks), free(s->scratch);
}

/* the frame of the true pose (q, t) into s->masks; 0 on success */
static int cube_scene_frame(cube_scene *s, const int32_t q[4], const int32_t t[3])
{
    mc_pose pose;
    mc_track_score sc;
    memset(s->masks, 0, (size_t)s->w * s->h);
    if (mc_pose_set(&pose, q, t) != MC_OK || mc_track_score_pose(&s->view, &pose, &sc) != MC_OK) return 1;
    for (uint32_t i = 0; i < s->w * s->h; i++)
        if (mc_sdepth_in_use(&s->sd, i % s->w, i / s->w)) s->masks[i] = s->color[i];
    mc_imgedge_masks(s->masks, (uint16_t)s->w, (uint16_t)s->h, 1, s->scratch);
    return 0;
}

/* the truth at frame k */
static void cube_scene_truth(int k, int32_t q[4], int32_t t[3])
{
    const double a = 0.35 + 0.01 * k, ax[3] = {0.48, 0.8, 0.36};
    q[0] = (int32_t)lround(cos(a / 2) * (1 << 30));
    for (int j = 0; j < 3; j++) q[j + 1] = (int32_t)lround(sin(a / 2) * ax[j] * (1 << 30));
    t[0] = -10000 + 2000 * k / 2, t[1] = 5000 - 1000 * k / 2, t[2] = 320000 + 1000 * k;
}

/* the angle between two unit Q30 quaternions, degrees, and the distance between two points, um */
static double cube_scene_angle(const int32_t a[4], const int32_t b[4])
{
    double d = 0;
    for (int k = 0; k < 4; k++) d += (double)a[k] * b[k] / (1.0 * (1 << 30) * (1 << 30));
    d = fabs(d);
    return 2 * acos(d > 1 ? 1 : d) * 180 / 3.14159265358979323846;
}

static double cube_scene_distance(const int32_t a[3], const int32_t b[3])
{
    double d = 0;
    for (int k = 0; k < 3; k++) d += ((double)a[k] - b[k]) * ((double)a[k] - b[k]);
    return sqrt(d);
}

/* the paper's filter settings: 300 particles, 100 of them fresh, in a box around the cube's path */
static mc_filter_params cube_scene_params(void)
{
    mc_filter_params p;
    memset(&p, 0, sizeof p);
    p.particles = 300, p.fresh = 100;
    p.step_t = 3000, p.step_r = (1 << 30) / 100;
    for (int k = 0; k < 3; k++) p.lo[k] = -100000, p.hi[k] = 100000;
    p.lo[2] = 200000, p.hi[2] = 500000;
    p.min_visible = 20, p.sharpness = 16, p.dof = 6;
    return p;
}

#endif
