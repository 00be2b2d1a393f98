/* Double-precision reference: see ref.h. */
#include "ref.h"

#include <math.h>
#include <stddef.h>

typedef struct walk {
    const mc_chunk *chunk[MC_MAX_DEPTH + 1];
    uint32_t at[MC_MAX_DEPTH + 1];
    const mc_chunk *color_chunk;
    uint32_t color_at;
    double r[3][3], scale, cx, cy, eye;
    unsigned d, w, h;
    int perspective;
    mc_ref_fn fn;
    void *user;
} walk;

static const uint8_t *next_byte(const mc_chunk **chunk, uint32_t *at)
{
    while (*at == (*chunk)->size) { (*chunk)++; *at = 0; }
    return (*chunk)->data + (*at)++;
}

static void leaf(walk *w, uint32_t ix, uint32_t iy, uint32_t iz)
{
    const double inv = 1.0 / (double)(1u << w->d);   /* a power of two: the products are exact */
    double p[3] = {(ix + 0.5) * inv - 0.5, (iy + 0.5) * inv - 0.5, (iz + 0.5) * inv - 0.5};
    double q[3];
    for (int i = 0; i < 3; i++) q[i] = w->r[i][0] * p[0] + w->r[i][1] * p[1] + w->r[i][2] * p[2];
    mc_ref_point pt;
    pt.color = next_byte(&w->color_chunk, &w->color_at);
    pt.depth = 1.0 - q[2];
    double mag = 1.0;
    pt.on_screen = 1;
    if (w->perspective) {
        double dist = w->eye - q[2];
        if (dist < 1.0 / 64) pt.on_screen = 0;
        else mag = w->eye / dist;
    }
    pt.sx = w->cx + w->scale * q[0] * mag;
    pt.sy = w->cy - w->scale * q[1] * mag;
    if (!(pt.sx >= 0 && pt.sy >= 0 && pt.sx < w->w && pt.sy < w->h)) pt.on_screen = 0;
    w->fn(&pt, w->user);
}

static void node(walk *w, unsigned l, uint32_t ix, uint32_t iy, uint32_t iz)
{
    unsigned m = *next_byte(&w->chunk[l], &w->at[l]);
    for (unsigned k = 0; k < 8; k++) {
        if (!(m & (1u << k))) continue;
        uint32_t cx = 2 * ix + (k & 1), cy = 2 * iy + ((k >> 1) & 1), cz = 2 * iz + ((k >> 2) & 1);
        if (l + 1 == w->d) leaf(w, cx, cy, cz);
        else node(w, l + 1, cx, cy, cz);
    }
}

void mc_ref_rotation(const mc_view *v, double r[3][3])
{
    const double turn = 2 * 3.14159265358979323846 / MC_ANGLE_FULL;
    double sy = sin(v->yaw * turn), cy = cos(v->yaw * turn), sp = sin(v->pitch * turn), cp = cos(v->pitch * turn);
    double sr = sin(v->roll * turn), cr = cos(v->roll * turn);
    double ry[3][3] = {{cy, 0, sy}, {0, 1, 0}, {-sy, 0, cy}};
    double rx[3][3] = {{1, 0, 0}, {0, cp, -sp}, {0, sp, cp}};
    double rz[3][3] = {{cr, -sr, 0}, {sr, cr, 0}, {0, 0, 1}};
    double t[3][3];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) t[i][j] = rx[i][0] * ry[0][j] + rx[i][1] * ry[1][j] + rx[i][2] * ry[2][j];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) r[i][j] = rz[i][0] * t[0][j] + rz[i][1] * t[1][j] + rz[i][2] * t[2][j];
}

void mc_ref_points(const mc_octree *scene, const mc_view *view, unsigned depth, unsigned width,
                   unsigned height, mc_ref_fn fn, void *user)
{
    walk w;
    mc_view v = mc_view_clamp(view, width, height);
    mc_ref_rotation(&v, w.r);
    w.scale = v.zoom / 65536.0 * (width < height ? width : height);
    w.cx = width / 2.0 + v.tx;
    w.cy = height / 2.0 + v.ty;
    w.eye = v.eye / 65536.0;
    w.perspective = v.projection == MC_PERSPECTIVE;
    w.d = depth;
    w.w = width;
    w.h = height;
    w.fn = fn;
    w.user = user;
    for (unsigned l = 0; l < depth; l++) { w.chunk[l] = scene->levels[l].masks; w.at[l] = 0; }
    w.color_chunk = scene->levels[depth].colors;
    w.color_at = 0;
    node(&w, 0, 0, 0, 0);
}

typedef struct image { const mc_target *t; double *zbuf; } image;

static void plot(const mc_ref_point *p, void *user)
{
    image *im = user;
    if (!p->on_screen) return;
    size_t i = (size_t)floor(p->sy) * im->t->width + (size_t)floor(p->sx);
    if (p->depth < im->zbuf[i]) {
        im->zbuf[i] = p->depth;
        im->t->depth[i] = 0;   /* coverage only: the double depth decides */
        im->t->color[i] = *p->color;
    }
}

void mc_ref_render(const mc_octree *scene, const mc_view *view, unsigned depth, const mc_target *t,
                   double *zbuf)
{
    size_t n = (size_t)t->width * t->height;
    for (size_t i = 0; i < n; i++) { zbuf[i] = HUGE_VAL; t->depth[i] = MC_DEPTH_EMPTY; t->color[i] = 0; }
    image im = {t, zbuf};
    mc_ref_points(scene, view, depth, t->width, t->height, plot, &im);
}
