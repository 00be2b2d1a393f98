/* Double-precision reference renderer of the original model: see mesh_ref.h. */
#include "mesh_ref.h"
#include "ref.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void mc_mesh_ref_free(mc_mesh_ref *m)
{
    free(m->pos); free(m->normal); free(m->rgb); free(m->tris);
    memset(m, 0, sizeof *m);
}

int mc_mesh_ref_load(const char *path, mc_mesh_ref *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    FILE *f = fopen(path, "rb");
    if (!f) { snprintf(err, errlen, "%s: cannot open", path); return -1; }
    char magic[8];
    uint32_t hdr[4];
    double g[5];
    if (fread(magic, 1, 8, f) != 8 || memcmp(magic, "MCREF01\n", 8) != 0 || fread(hdr, 4, 4, f) != 4 ||
        fread(g, 8, 5, f) != 5 || hdr[0] > 1 || hdr[2] == 0 || hdr[2] > 100000000u || hdr[3] > 200000000u) {
        snprintf(err, errlen, "%s: not a modelc reference dump (MCREF01)", path);
        fclose(f);
        return -1;
    }
    m->is_points = hdr[0] == 1;
    m->shade = hdr[1] != 0;
    m->nverts = hdr[2];
    m->ntris = hdr[3];
    m->side = g[0];
    m->origin[0] = g[1], m->origin[1] = g[2], m->origin[2] = g[3];
    m->radius = g[4];
    size_t n = m->nverts;
    m->pos = malloc(3 * n * sizeof(double));
    m->normal = malloc(3 * n * sizeof(double));
    m->rgb = malloc(3 * n * sizeof(double));
    m->tris = malloc((3 * (size_t)m->ntris + 1) * sizeof(uint32_t));
    double *rec = malloc(9 * n * sizeof(double));
    int ok = m->pos && m->normal && m->rgb && m->tris && rec && fread(rec, 72, n, f) == n &&
             fread(m->tris, 12, m->ntris, f) == m->ntris;
    if (ok) {
        for (size_t i = 0; i < n; i++)
            for (int a = 0; a < 3; a++) {
                m->pos[3 * i + a] = rec[9 * i + a];
                m->normal[3 * i + a] = rec[9 * i + 3 + a];
                m->rgb[3 * i + a] = rec[9 * i + 6 + a];
            }
        for (size_t i = 0; i < 3 * (size_t)m->ntris; i++)
            if (m->tris[i] >= m->nverts) ok = 0;
    }
    free(rec);
    fclose(f);
    if (!ok) {
        snprintf(err, errlen, "%s: truncated or bad vertex index", path);
        mc_mesh_ref_free(m);
        return -1;
    }
    return 0;
}

/* the view, as runtime/ref/ref.c builds it */
typedef struct xform {
    double r[3][3], scale, cx, cy, eye;
    int perspective;
} xform;

static void make_xform(const mc_view *view, unsigned width, unsigned height, xform *x)
{
    mc_view v = mc_view_clamp(view, width, height);
    mc_ref_rotation(&v, x->r);
    x->scale = v.zoom / 65536.0 * (width < height ? width : height);
    x->cx = width / 2.0 + v.tx;
    x->cy = height / 2.0 + v.ty;
    x->eye = v.eye / 65536.0;
    x->perspective = v.projection == MC_PERSPECTIVE;
}

/* screen position, depth (1 - z) and perspective weight (1 / distance, 1 orthographic) of p;
 * returns 0 when p is at or behind the near plane */
typedef struct svert { double x, y, z, w; } svert;
static int project(const xform *x, const double *p, svert *s)
{
    double q[3];
    for (int i = 0; i < 3; i++) q[i] = x->r[i][0] * p[0] + x->r[i][1] * p[1] + x->r[i][2] * p[2];
    double mag = 1.0;
    s->w = 1.0;
    if (x->perspective) {
        double dist = x->eye - q[2];
        if (dist < 1.0 / 64) return 0;
        mag = x->eye / dist;
        s->w = 1.0 / dist;
    }
    s->x = x->cx + x->scale * q[0] * mag;
    s->y = x->cy - x->scale * q[1] * mag;
    s->z = 1.0 - q[2];
    return 1;
}

static uint8_t to_byte(double v)
{
    if (!(v > 0)) return 0;
    if (v > 255) return 255;
    return (uint8_t)lround(v);
}

static int nearest(const uint8_t *palette, unsigned n, const uint8_t c[3])
{
    int best = 0;
    long best_d = -1;
    for (unsigned p = 0; p < n; p++) {
        long d = 0;
        for (int a = 0; a < 3; a++) d += (long)(c[a] - palette[3 * p + a]) * (c[a] - palette[3 * p + a]);
        if (best_d < 0 || d < best_d) best_d = d, best = (int)p;
    }
    return best;
}

/* Edge function of the directed edge a -> b at p, computed in one canonical vertex order so that the
 * two triangles sharing an edge get exactly opposite values; *incl says whether a pixel centre exactly
 * on the edge belongs to this side (an antisymmetric rule: exactly one of the two triangles takes it). */
static double edge(const svert *a, const svert *b, double px, double py, int *incl)
{
    int flip = a->x > b->x || (a->x == b->x && a->y > b->y);
    const svert *u = flip ? b : a, *v = flip ? a : b;
    double e = (v->x - u->x) * (py - u->y) - (v->y - u->y) * (px - u->x);
    double dy = v->y - u->y, dx = v->x - u->x;
    int take = dy > 0 || (dy == 0 && dx > 0);
    *incl = flip ? !take : take;
    return flip ? -e : e;
}

typedef struct frame {
    unsigned w, h;
    double *z;
    uint8_t *rgb, *cov, *idx;
    const uint8_t *palette;
    unsigned palette_size;
    int gray_index[256];
} frame;

static void put(frame *fr, size_t i, double z, const double rgb[3])
{
    if (!(z < fr->z[i])) return;
    fr->z[i] = z;
    uint8_t c[3] = {to_byte(rgb[0]), to_byte(rgb[1]), to_byte(rgb[2])};
    if (fr->palette) {
        int k;
        if (c[0] == c[1] && c[1] == c[2]) {
            if (fr->gray_index[c[0]] < 0) fr->gray_index[c[0]] = nearest(fr->palette, fr->palette_size, c);
            k = fr->gray_index[c[0]];
        } else {
            k = nearest(fr->palette, fr->palette_size, c);
        }
        for (int a = 0; a < 3; a++) c[a] = fr->palette[3 * k + a];
        if (fr->idx) fr->idx[i] = (uint8_t)k;
    }
    memcpy(fr->rgb + 3 * i, c, 3);
    fr->cov[i] = 1;
}

static double light(const double n[3])
{
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) return 0.6;
    return 0.15 + 0.85 * fabs(n[2] / len);
}

static void triangle(frame *fr, const mc_mesh_ref *m, const uint32_t *t, const svert *s0)
{
    const svert *s[3] = {&s0[0], &s0[1], &s0[2]};
    uint32_t vi[3] = {t[0], t[1], t[2]};
    int dummy;
    double area = edge(s[0], s[1], s[2]->x, s[2]->y, &dummy);
    if (area == 0 || !isfinite(area)) return;
    if (area < 0) {   /* two-sided: make every triangle counter-clockwise in the edge function's sense */
        const svert *ts = s[1]; s[1] = s[2]; s[2] = ts;
        uint32_t tv = vi[1]; vi[1] = vi[2]; vi[2] = tv;
        area = -area;
    }
    double xmin = fmin(s[0]->x, fmin(s[1]->x, s[2]->x)), xmax = fmax(s[0]->x, fmax(s[1]->x, s[2]->x));
    double ymin = fmin(s[0]->y, fmin(s[1]->y, s[2]->y)), ymax = fmax(s[0]->y, fmax(s[1]->y, s[2]->y));
    long x0 = (long)ceil(xmin - 0.5), x1 = (long)floor(xmax - 0.5);
    long y0 = (long)ceil(ymin - 0.5), y1 = (long)floor(ymax - 0.5);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > (long)fr->w - 1) x1 = (long)fr->w - 1;
    if (y1 > (long)fr->h - 1) y1 = (long)fr->h - 1;
    for (long y = y0; y <= y1; y++) {
        double py = y + 0.5;
        for (long x = x0; x <= x1; x++) {
            double px = x + 0.5;
            int i0, i1, i2;
            double e0 = edge(s[1], s[2], px, py, &i0);   /* weight of vertex 0 */
            double e1 = edge(s[2], s[0], px, py, &i1);
            double e2 = edge(s[0], s[1], px, py, &i2);
            if (e0 < 0 || e1 < 0 || e2 < 0) continue;
            if ((e0 == 0 && !i0) || (e1 == 0 && !i1) || (e2 == 0 && !i2)) continue;
            double l[3] = {e0 / area, e1 / area, e2 / area};
            if (s[0]->w != 1 || s[1]->w != 1 || s[2]->w != 1) {   /* perspective-correct weights */
                double a = l[0] * s[0]->w, b = l[1] * s[1]->w, c = l[2] * s[2]->w, sum = a + b + c;
                l[0] = a / sum, l[1] = b / sum, l[2] = c / sum;
            }
            double z = l[0] * s[0]->z + l[1] * s[1]->z + l[2] * s[2]->z;
            double rgb[3] = {0, 0, 0};
            if (m->shade) {
                double n[3] = {0, 0, 0};
                for (int k = 0; k < 3; k++)
                    for (int a = 0; a < 3; a++) n[a] += l[k] * m->normal[3 * vi[k] + a];
                rgb[0] = rgb[1] = rgb[2] = 255.0 * light(n);
            } else {
                for (int k = 0; k < 3; k++)
                    for (int a = 0; a < 3; a++) rgb[a] += l[k] * m->rgb[3 * vi[k] + a];
            }
            put(fr, (size_t)y * fr->w + (size_t)x, z, rgb);
        }
    }
}

static void disc(frame *fr, const svert *s, double r, const double rgb[3])
{
    long x0 = (long)ceil(s->x - r - 0.5), x1 = (long)floor(s->x + r - 0.5);
    long y0 = (long)ceil(s->y - r - 0.5), y1 = (long)floor(s->y + r - 0.5);
    if (x0 < 0) x0 = 0;
    if (y0 < 0) y0 = 0;
    if (x1 > (long)fr->w - 1) x1 = (long)fr->w - 1;
    if (y1 > (long)fr->h - 1) y1 = (long)fr->h - 1;
    for (long y = y0; y <= y1; y++)
        for (long x = x0; x <= x1; x++) {
            double dx = x + 0.5 - s->x, dy = y + 0.5 - s->y;
            if (dx * dx + dy * dy <= r * r) put(fr, (size_t)y * fr->w + (size_t)x, s->z, rgb);
        }
}

long mc_mesh_ref_render(const mc_mesh_ref *m, const mc_view *view, unsigned width, unsigned height,
                        const uint8_t *palette, unsigned palette_size, uint8_t *out_rgb,
                        uint8_t *out_covered, uint8_t *out_index)
{
    size_t n = (size_t)width * height;
    frame fr = {width, height, malloc(n * sizeof(double)), out_rgb, out_covered, out_index,
                palette && palette_size ? palette : NULL, palette_size, {0}};
    svert *sv = malloc((size_t)m->nverts * sizeof(svert));
    uint8_t *ok = malloc(m->nverts);
    if (!fr.z || !sv || !ok) { free(fr.z); free(sv); free(ok); return -1; }
    for (int i = 0; i < 256; i++) fr.gray_index[i] = -1;
    for (size_t i = 0; i < n; i++) fr.z[i] = HUGE_VAL;
    memset(out_rgb, 0, 3 * n);
    memset(out_covered, 0, n);
    if (out_index) memset(out_index, 0, n);
    xform x;
    make_xform(view, width, height, &x);
    for (uint32_t i = 0; i < m->nverts; i++) ok[i] = (uint8_t)project(&x, m->pos + 3 * i, &sv[i]);
    if (m->is_points) {
        for (uint32_t i = 0; i < m->nverts; i++) {
            if (!ok[i]) continue;
            double r = m->radius * x.scale * (x.perspective ? x.eye * sv[i].w : 1.0);
            disc(&fr, &sv[i], r < 0.5 ? 0.5 : r, m->rgb + 3 * i);
        }
    } else {
        for (uint32_t t = 0; t < m->ntris; t++) {
            const uint32_t *v = m->tris + 3 * t;
            if (!ok[v[0]] || !ok[v[1]] || !ok[v[2]]) continue;
            svert s[3] = {sv[v[0]], sv[v[1]], sv[v[2]]};
            triangle(&fr, m, v, s);
        }
    }
    long covered = 0;
    for (size_t i = 0; i < n; i++) covered += out_covered[i];
    free(fr.z); free(sv); free(ok);
    return covered;
}
