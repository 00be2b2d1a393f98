/* Hidden lines by quantitative invisibility: see modelc/mesh_qi.h.
 *
 * Long because it is one algorithm whose parts share one set of integer bounds (below) and one work
 * buffer layout: the screen grids, the batched ray tests, the exact crossings and their ordering, the
 * face-by-face fallback and the pixel walk all depend on the same invariants, and split across files
 * they would each have to restate them.
 *
 * Bounds every product below relies on: projected x, y lie in the band, |x|, |y| <= 2^21 (1/16
 * pixel), so a difference of two is below 2^22 in magnitude, twice the area of a triangle of three
 * such points at most 2^44, a cross product of two differences at most 2^45; depths are below 2^16.
 */
#include "modelc/mesh_qi.h"
#include "line_walk.h"   /* the walk of a line, as mc_line's */

typedef struct qi_line {
    int32_t ax, ay, bx, by;   /* projected corners, 1/16 pixel */
    uint32_t half;            /* MC_HALF_EDGE(f, k) */
    uint32_t g;               /* the face across, or MC_NO_HALF_EDGE (none) */
    uint32_t qi[4];           /* QI_L(0+), QI_R(0+), QI_L(1-), QI_R(1-) */
    uint16_t az, bz;
    uint32_t kind;
} qi_line;

typedef struct qi_contour {
    int32_t x0, y0, x1, y1;   /* W0, W1: its corners as its first face holds them */
    uint32_t stamp;           /* the last line tested against it, plus one */
    uint16_t z0, z1;
    uint8_t pos, neg;         /* faces that can hide on each side: cross(W1 - W0, P - W0) > 0, < 0 */
    uint8_t pad[2];
} qi_contour;

/* the record sizes the header's byte counts promise */
typedef char qi_line_is_its_record[sizeof(qi_line) == MC_QI_LINE_RECORD ? 1 : -1];
typedef char qi_contour_is_its_record[sizeof(qi_contour) == MC_QI_CONTOUR_RECORD ? 1 : -1];

enum { CLS_NONE = 0, CLS_FRONT = 1, CLS_BACK = 2 };

typedef struct qi_ctx {
    const mc_pmesh_lod *lod;
    mc_xform x;
    const mc_xvertex *cache;   /* null: project on each use */
    const uint8_t *facing;     /* mc_mesh_facing's bits */
    const uint8_t *hides;      /* faces that can hide: no flagged corner, some projected area */
} qi_ctx;

/* ---- integers ------------------------------------------------------------------------------------ */

/* a * b < c * d for a, b, c, d < 2^64: the 128-bit products compared from 32-bit halves (no
 * 64 x 64 multiply wider than 64 bits exists in C99) */
static void mul128(uint64_t a, uint64_t b, uint64_t *hi, uint64_t *lo)
{
    const uint64_t a0 = (uint32_t)a, a1 = a >> 32, b0 = (uint32_t)b, b1 = b >> 32;
    const uint64_t p00 = a0 * b0, p01 = a0 * b1, p10 = a1 * b0, p11 = a1 * b1;
    const uint64_t mid = (p00 >> 32) + (uint32_t)p01 + (uint32_t)p10;
    *lo = (mid << 32) | (uint32_t)p00;
    *hi = p11 + (p01 >> 32) + (p10 >> 32) + (mid >> 32);
}

static int cmp_mul(uint64_t a, uint64_t b, uint64_t c, uint64_t d)
{
    uint64_t h1, l1, h2, l2;
    mul128(a, b, &h1, &l1);
    mul128(c, d, &h2, &l2);
    if (h1 != h2) return h1 < h2 ? -1 : 1;
    return l1 < l2 ? -1 : l1 > l2;
}

/* The sign of a/b - c/d, b and d > 0, |a|, |c| < 2^63. */
static int cmp_frac(int64_t a, int64_t b, int64_t c, int64_t d)
{
    const int sa = (a > 0) - (a < 0), sc = (c > 0) - (c < 0);
    if (sa != sc) return sa < sc ? -1 : 1;
    if (sa == 0) return 0;
    const int r = cmp_mul(mc_mag64(a), (uint64_t)d, mc_mag64(c), (uint64_t)b);
    return sa > 0 ? r : -r;
}

static int64_t area2(const mc_raster_vertex v[3])
{
    return (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y);
}

static uint32_t align8(uint32_t n) { return (n + 7u) & ~7u; }

/* ---- faces ----------------------------------------------------------------------------------------- */

/* Face f's corner indices at the level (mc_pmesh_lod_face, inlined: every pass reads every face). */
MC_ALWAYS_INLINE void face_idx(const mc_pmesh_lod *lod, uint32_t f, uint32_t idx[3])
{
    const mc_pmesh *pm = lod->pm;
    if (pm->index_bytes == 2) {
        const uint8_t *r = mc_chunk_record(pm->corners, pm->record_shift, 6u, f);
        const uint16_t *anc = (const uint16_t *)lod->anc;
        idx[0] = anc[mc_le16(r)], idx[1] = anc[mc_le16(r + 2)], idx[2] = anc[mc_le16(r + 4)];
    } else {
        const uint8_t *r = mc_chunk_record(pm->corners, pm->record_shift, 12u, f);
        const uint32_t *anc = (const uint32_t *)lod->anc;
        idx[0] = anc[mc_le32(r)], idx[1] = anc[mc_le32(r + 4)], idx[2] = anc[mc_le32(r + 8)];
    }
}

/* The projections of corners idx; returns their MC_XFORM_* flags, or-ed (as mc_mesh_face). */
static uint32_t project(const qi_ctx *c, const uint32_t idx[3], mc_raster_vertex v[3])
{
    uint32_t out = 0;
    for (int k = 0; k < 3; k++) {
        mc_xvertex xv;
        const mc_xvertex *p = &xv;
        if (c->cache) {
            p = &c->cache[idx[k]];
        } else {
            int32_t q[3];
            mc_pmesh_position(c->lod->pm, idx[k], q);
            mc_xform_vertex(&c->x, q, &xv);
        }
        out |= p->flags;
        v[k].x = p->x, v[k].y = p->y, v[k].z = p->z;
    }
    return out;
}

/* Face f's corner indices and projections; returns its corners' flags, or-ed. */
static uint32_t corners(const qi_ctx *c, uint32_t f, uint32_t idx[3], mc_raster_vertex v[3])
{
    face_idx(c->lod, f, idx);
    return project(c, idx, v);
}

/* The facing of a face with a flagged corner, corners idx: its plane's (mc_mesh_face_front), as
 * mc_mesh_facing gives it. */
static int flagged_front(const qi_ctx *c, const uint32_t idx[3])
{
    int32_t p[3][3];
    for (int k = 0; k < 3; k++) mc_pmesh_position(c->lod->pm, idx[k], p[k]);
    return mc_mesh_face_front(&c->x, (const int32_t(*)[3])p);
}

static unsigned bit(const uint8_t *b, uint32_t i) { return (b[i >> 3] >> (i & 7u)) & 1u; }

/* A face that hides is front or back by its facing bit; a face with a flagged corner has a facing
 * bit too (its plane's, as mc_mesh_lines gives it) but hides nothing. */
static unsigned face_class(const qi_ctx *c, uint32_t f)
{
    return !bit(c->hides, f) ? CLS_NONE : bit(c->facing, f) ? CLS_FRONT : CLS_BACK;
}

/* The quantities of face v (area2 a != 0) along the line P + t d, depth zp + t dz (mesh_qi.h's covering
 * test, in the face's orientation so that inside is positive): edge k's function e[k] + t s[k] and
 * its rate p[k] towards the line's left normal (-dy, dx); and |a| (F's depth - line's depth) =
 * al + t be. |e| <= 2^44, |s|, |p| <= 2^45, |al| < 2^62, |be| < 2^63. */
typedef struct qi_face_line {
    int64_t e[3], s[3], p[3], al, be;
} qi_face_line;

static void face_line(const mc_raster_vertex v[3], int64_t a, int32_t px, int32_t py, uint32_t pz, int32_t dx,
                      int32_t dy, int32_t dz, qi_face_line *q)
{
    const int64_t sg = a > 0 ? 1 : -1;
    for (int k = 0; k < 3; k++) {
        const mc_raster_vertex *u = &v[k], *w = &v[k == 2 ? 0 : k + 1];
        const int64_t ex = (int64_t)w->x - u->x, ey = (int64_t)w->y - u->y;
        q->e[k] = sg * (ex * ((int64_t)py - u->y) - ey * ((int64_t)px - u->x));
        q->s[k] = sg * (ex * dy - ey * dx);
        q->p[k] = sg * (ex * dx + ey * dy);
    }
    /* barycentric: |a| z_F(P) = sum_k e_k(P) z_{k+2}; the k = 1 term is z_0's, folded into |a| z_0 */
    const int64_t z0 = v[0].z, z1 = (int64_t)v[1].z - z0, z2 = (int64_t)v[2].z - z0, aa = (int64_t)mc_mag64(a);
    q->al = q->e[0] * z2 + q->e[2] * z1 + aa * (z0 - (int64_t)pz);
    q->be = q->s[0] * z2 + q->s[2] * z1 - aa * dz;
}

/* The ray test: whether face v (area2 a != 0) covers the line P + t d, depth zp + t dz, at t -> 0+
 * on the left (*l) and on the right (*r), lexicographically: face_line's values at 0, then their
 * rates along the line, then (edge functions only: the line along the edge) the rates to the side.
 * The same quantities as face_line, each computed only when the ones before leave it open. */
static void ray(const mc_raster_vertex v[3], int64_t a, int32_t px, int32_t py, uint32_t pz, int32_t dx, int32_t dy,
                int32_t dz, int *l, int *r)
{
    const int64_t sg = a > 0 ? 1 : -1;
    int64_t e[3], s[3];
    int inl = 1, inr = 1;
    *l = *r = 0;
    for (int k = 0; k < 3; k++) {
        const mc_raster_vertex *u = &v[k], *w = &v[k == 2 ? 0 : k + 1];
        const int64_t ex = (int64_t)w->x - u->x, ey = (int64_t)w->y - u->y;
        e[k] = sg * (ex * ((int64_t)py - u->y) - ey * ((int64_t)px - u->x));
        if (e[k] < 0) return;
        s[k] = sg * (ex * dy - ey * dx);
        if (e[k] > 0 || s[k] > 0) continue;
        if (s[k] < 0) return;
        const int64_t p = sg * (ex * dx + ey * dy);
        inl &= p > 0;
        inr &= p < 0;
    }
    if (!inl && !inr) return;
    const int64_t z0 = v[0].z, z1 = (int64_t)v[1].z - z0, z2 = (int64_t)v[2].z - z0, aa = a > 0 ? a : -a;
    const int64_t al = e[0] * z2 + e[2] * z1 + aa * (z0 - (int64_t)pz);
    const int front = al < 0 || (al == 0 && s[0] * z2 + s[2] * z1 - aa * dz < 0);
    *l = inl && front;
    *r = inr && front;
}

/* ---- the Bresenham walk, as mc_line (line.c) ----------------------------------------------------- */

/* (div27 and step_reaching: line_walk.h's) */

/* (the walk: line_walk.h's walk_init, which also records d, first and from_b for the passes below) */

/* Draws the walk's steps whose bit is set (colour and depth, no test); returns how many. */
static uint32_t walk_draw(walk *w, const mc_target *t, const uint8_t *bits, uint8_t color)
{
    uint8_t *const cbuf = t->color;
    uint16_t *const dbuf = t->depth;
    uint32_t drawn = 0;
    for (uint32_t n = 0;;) {
        if (bit(bits, n)) {
            cbuf[w->idx] = color;
            dbuf[w->idx] = (uint16_t)w->z;
            drawn++;
        }
        if (++n == w->count) break;
        w->idx += w->ustep;
        w->r += w->m2;
        if (w->r >= w->d2) {
            w->r -= w->d2;
            w->idx += w->vstep;
        }
        w->z += w->zstep;
        w->zr += w->zrstep;
        if (w->zr >= w->d2) {
            w->zr -= w->d2;
            w->z += w->zunit;
        }
    }
    return drawn;
}

/* Step first + j's t from a, as a fraction of D (D > 0). */
static int64_t step_num(const walk *w, uint32_t j)
{
    const uint32_t i = w->first + j;
    return w->from_b ? (int64_t)(w->d - i) : (int64_t)i;
}

/* ---- the grid ---------------------------------------------------------------------------------------- */

typedef struct qi_end {
    int32_t x, y;   /* the end point */
    uint32_t id;    /* 2 line + (0: a, 1: b) */
    uint32_t f, g;  /* the line's own faces (tested before the line is read) */
} qi_end;

typedef struct qi_grid {
    uint32_t nx, ny, shift;    /* contour cells of 2^shift units of 1/16 pixel */
    uint32_t qnx, qny, qshift; /* line-end cells */
    uint32_t *chead, *centry;  /* contours by cell: cell c holds centry[chead[c] .. chead[c+1]) */
    uint32_t *qhead;           /* line ends by cell */
    struct qi_end *qentry;
} qi_grid;

static uint32_t cell(int32_t v, uint32_t shift, uint32_t n)
{
    if (v < 0) return 0;
    const uint32_t c = (uint32_t)v >> shift;
    return c < n ? c : n - 1u;
}

static uint32_t contour_cells(const qi_contour *c, const qi_grid *g)
{
    const uint32_t x0 = cell(c->x0 < c->x1 ? c->x0 : c->x1, g->shift, g->nx);
    const uint32_t x1 = cell(c->x0 < c->x1 ? c->x1 : c->x0, g->shift, g->nx);
    const uint32_t y0 = cell(c->y0 < c->y1 ? c->y0 : c->y1, g->shift, g->ny);
    const uint32_t y1 = cell(c->y0 < c->y1 ? c->y1 : c->y0, g->shift, g->ny);
    return (x1 - x0 + 1u) * (y1 - y0 + 1u);
}

/* ---- one line ----------------------------------------------------------------------------------------- */

typedef struct qi_frame {
    qi_ctx c;
    const mc_target *t;
    unsigned flags;
    qi_line *lines_top;       /* line j is lines_top[-1 - j] */
    qi_contour *contours;
    uint32_t nlines, ncontours;
    qi_grid g;
    mc_qi_t *ev_t;            /* events: t, and the changes of QI_L, QI_R */
    int8_t *ev_d;
    uint32_t ev_cap;
    uint8_t *bits;            /* per step on the target: drawn */
    int32_t *cnt;             /* face by face: 4 difference arrays of side + 1 */
    uint32_t side;
    mc_qi_stats *st;
} qi_frame;

/* The contours crossing line j in front, as events; returns 1, or 0 when the line must be computed
 * face by face (a tie at a crossing, more events than room, ends that disagree). */
static int collect(qi_frame *fr, const qi_line *ln, uint32_t j, uint32_t *nev)
{
    const qi_grid *g = &fr->g;
    const int64_t ax = ln->ax, ay = ln->ay, dx = (int64_t)ln->bx - ln->ax, dy = (int64_t)ln->by - ln->ay;
    const int64_t az = ln->az, dz = (int64_t)ln->bz - ln->az;
    const int32_t bx0 = ln->ax < ln->bx ? ln->ax : ln->bx, bx1 = ln->ax < ln->bx ? ln->bx : ln->ax;
    const int32_t by0 = ln->ay < ln->by ? ln->ay : ln->by, by1 = ln->ay < ln->by ? ln->by : ln->ay;
    const uint32_t cx0 = cell(bx0, g->shift, g->nx), cx1 = cell(bx1, g->shift, g->nx);
    const uint32_t cy0 = cell(by0, g->shift, g->ny), cy1 = cell(by1, g->shift, g->ny);
    const int64_t side = (int64_t)1 << g->shift;
    int64_t suml = 0, sumr = 0;
    uint32_t n = 0;
    for (uint32_t cy = cy0; cy <= cy1; cy++)
        for (uint32_t cx = cx0; cx <= cx1; cx++) {
            const uint32_t ci = cy * g->nx + cx;
            if (g->chead[ci] == g->chead[ci + 1]) continue;
            if (cx1 > cx0 || cy1 > cy0) {   /* does the segment pass the cell (within its bounding box)? */
                int64_t rx0 = cx ? (int64_t)cx * side : bx0, rx1 = cx + 1 < g->nx ? (int64_t)(cx + 1) * side : bx1;
                int64_t ry0 = cy ? (int64_t)cy * side : by0, ry1 = cy + 1 < g->ny ? (int64_t)(cy + 1) * side : by1;
                if (rx0 < bx0) rx0 = bx0;
                if (rx1 > bx1) rx1 = bx1;
                if (ry0 < by0) ry0 = by0;
                if (ry1 > by1) ry1 = by1;
                const int64_t o00 = dx * (ry0 - ay) - dy * (rx0 - ax), o01 = dx * (ry1 - ay) - dy * (rx0 - ax);
                const int64_t o10 = dx * (ry0 - ay) - dy * (rx1 - ax), o11 = dx * (ry1 - ay) - dy * (rx1 - ax);
                if ((o00 > 0 && o01 > 0 && o10 > 0 && o11 > 0) || (o00 < 0 && o01 < 0 && o10 < 0 && o11 < 0)) continue;
            }
            for (uint32_t e = g->chead[ci]; e < g->chead[ci + 1]; e++) {
                qi_contour *c = &fr->contours[g->centry[e]];
                if (c->stamp == j + 1u) continue;
                c->stamp = j + 1u;
                if ((c->x0 < bx0 && c->x1 < bx0) || (c->x0 > bx1 && c->x1 > bx1) || (c->y0 < by0 && c->y1 < by0) ||
                    (c->y0 > by1 && c->y1 > by1))
                    continue;
                fr->st->pair_tests++;
                /* sides of the contour's corners: o > 0 left of the line; the left-shifted line
                 * counts a corner on the line as right, the right-shifted one as left */
                const int64_t o1 = dx * (c->y0 - ay) - dy * (c->x0 - ax), o2 = dx * (c->y1 - ay) - dy * (c->x1 - ax);
                const int cl = (o1 > 0) != (o2 > 0), cr = (o1 >= 0) != (o2 >= 0);
                if (!cl && !cr) continue;
                /* t = cross(W0 - A, u) / cross(d, u), u = W1 - W0, cross(d, u) = o2 - o1; the numerator
                 * is also A's side of the contour (positive: A on its positive side); s = o1 / (o1 - o2) */
                const int64_t ux = (int64_t)c->x1 - c->x0, uy = (int64_t)c->y1 - c->y0;
                const int64_t q = ux * (ay - c->y0) - uy * (ax - c->x0);
                int64_t num = q, den = o2 - o1, sn = -o1;
                if (den < 0) num = -num, den = -den, sn = o1;
                if (num <= 0 || num >= den) continue;   /* 0 < t < 1 only: the ends are the ray tests' */
                /* den |z| below 2^61 each side: the depths at the crossing, times den */
                const int64_t ze = az * den + num * dz, zc = (int64_t)c->z0 * den + sn * ((int64_t)c->z1 - c->z0);
                if (ze == zc) return 0;
                if (zc > ze) continue;
                fr->st->crossings++;
                const int delta = q > 0 ? (int)c->neg - (int)c->pos : (int)c->pos - (int)c->neg;
                if (n >= fr->ev_cap) return 0;
                fr->ev_t[n].num = num, fr->ev_t[n].den = den;
                fr->ev_d[2 * n] = (int8_t)(cl ? delta : 0);
                fr->ev_d[2 * n + 1] = (int8_t)(cr ? delta : 0);
                suml += cl ? delta : 0;
                sumr += cr ? delta : 0;
                n++;
            }
        }
    *nev = n;
    return (int64_t)ln->qi[0] + suml == (int64_t)ln->qi[2] && (int64_t)ln->qi[1] + sumr == (int64_t)ln->qi[3];
}

static void ev_swap(qi_frame *fr, uint32_t a, uint32_t b)
{
    /* field by field: a structure assignment may become a memcpy call, which freestanding code lacks */
    const int64_t n = fr->ev_t[a].num, d = fr->ev_t[a].den;
    const int8_t l = fr->ev_d[2 * a], r = fr->ev_d[2 * a + 1];
    fr->ev_t[a].num = fr->ev_t[b].num, fr->ev_t[a].den = fr->ev_t[b].den;
    fr->ev_d[2 * a] = fr->ev_d[2 * b], fr->ev_d[2 * a + 1] = fr->ev_d[2 * b + 1];
    fr->ev_t[b].num = n, fr->ev_t[b].den = d, fr->ev_d[2 * b] = l, fr->ev_d[2 * b + 1] = r;
}

static int ev_less(const qi_frame *fr, uint32_t a, uint32_t b)
{
    return cmp_frac(fr->ev_t[a].num, fr->ev_t[a].den, fr->ev_t[b].num, fr->ev_t[b].den) < 0;
}

/* Heap sort of the n events by t: bounded work and no recursion. */
static void ev_sort(qi_frame *fr, uint32_t n)
{
    for (uint32_t k = n; k-- > 0;)   /* heapify, then take the largest out n - 1 times */
        for (uint32_t i = k;;) {
            uint32_t c = 2u * i + 1u;
            if (c >= n) break;
            if (c + 1u < n && ev_less(fr, c, c + 1u)) c++;
            if (!ev_less(fr, i, c)) break;
            ev_swap(fr, i, c);
            i = c;
        }
    for (uint32_t end = n; end > 1u;) {
        ev_swap(fr, 0, --end);
        for (uint32_t i = 0;;) {
            uint32_t c = 2u * i + 1u;
            if (c >= end) break;
            if (c + 1u < end && ev_less(fr, c, c + 1u)) c++;
            if (!ev_less(fr, i, c)) break;
            ev_swap(fr, i, c);
            i = c;
        }
    }
}

/* The sorted events swept into the visibility changes, written over ev_t's start; returns how many. */
static uint32_t sweep(qi_frame *fr, const qi_line *ln, uint32_t n, int *v0)
{
    int64_t l = ln->qi[0], r = ln->qi[1];
    int vis = l == 0 || r == 0;
    *v0 = vis;
    uint32_t m = 0;
    for (uint32_t i = 0; i < n;) {
        const int64_t tn = fr->ev_t[i].num, td = fr->ev_t[i].den;
        uint32_t k = i;
        for (; k < n && cmp_frac(fr->ev_t[k].num, fr->ev_t[k].den, tn, td) == 0; k++)
            l += fr->ev_d[2 * k], r += fr->ev_d[2 * k + 1];
        const int now = l == 0 || r == 0;
        if (now != vis) fr->ev_t[m].num = tn, fr->ev_t[m].den = td, m++, vis = now;
        i = k;
    }
    return m;
}

/* Bits of the steps on the target from the changes (t sorted from a; visible at a change). */
static void bits_from_changes(qi_frame *fr, const walk *w, const mc_qi_t *ch, uint32_t m, int v0, int v1)
{
    const int64_t d = w->d;
    uint32_t k = 0;   /* changes below the step's t */
    if (w->from_b) k = m;
    for (uint32_t j = 0; j < w->count; j++) {
        const int64_t num = step_num(w, j);
        int vis;
        if (num == 0) vis = v0;
        else if (num == d) vis = v1;
        else {
            if (!w->from_b)
                while (k < m && cmp_frac(ch[k].num, ch[k].den, num, d) < 0) k++;
            else
                while (k > 0 && cmp_frac(ch[k - 1].num, ch[k - 1].den, num, d) >= 0) k--;
            vis = (k < m && cmp_frac(ch[k].num, ch[k].den, num, d) == 0) || (v0 ^ (int)(k & 1u));
        }
        if (vis) fr->bits[j >> 3] |= (uint8_t)(1u << (j & 7u));
    }
}

/* The steps j (0 .. count) before which step t crosses x: the first j where t_j >= x (ge) or > x,
 * for t increasing in j; where t_j <= x (ge) or < x for t decreasing. */
static uint32_t step_bound(const walk *w, int64_t xn, int64_t xd, int ge)
{
    uint32_t lo = 0, hi = w->count;
    while (lo < hi) {
        const uint32_t mid = lo + (hi - lo) / 2u;
        const int c = cmp_frac(step_num(w, mid), (int64_t)w->d, xn, xd);
        const int past = w->from_b ? (ge ? c <= 0 : c < 0) : (ge ? c >= 0 : c > 0);
        if (past) hi = mid;
        else lo = mid + 1u;
    }
    return lo;
}

static void add_range(int32_t *a, uint32_t j0, uint32_t j1)
{
    if (j0 >= j1) return;
    a[j0]++;
    a[j1]--;
}

/* Line ln computed face by face from the definition: every face's open interval of covering on
 * each side, counted per step just after (plus) and just before (minus) its t. */
static void face_by_face(qi_frame *fr, const qi_line *ln, const walk *w)
{
    const uint32_t n1 = w->count + 1u;
    int32_t *lp = fr->cnt, *lm = lp + n1, *rp = lm + n1, *rm = rp + n1;
    for (uint32_t i = 0; i < 4u * n1; i++) fr->cnt[i] = 0;
    const int32_t dx = ln->bx - ln->ax, dy = ln->by - ln->ay, dz = (int32_t)ln->bz - (int32_t)ln->az;
    const int32_t bx0 = ln->ax < ln->bx ? ln->ax : ln->bx, bx1 = ln->ax < ln->bx ? ln->bx : ln->ax;
    const int32_t by0 = ln->ay < ln->by ? ln->ay : ln->by, by1 = ln->ay < ln->by ? ln->by : ln->ay;
    const uint32_t f = MC_HALF_FACE(ln->half), faces = fr->c.lod->faces;
    for (uint32_t h = 0; h < faces; h++) {
        if (h == f || h == ln->g || face_class(&fr->c, h) == CLS_NONE) continue;
        uint32_t idx[3];
        mc_raster_vertex v[3];
        corners(&fr->c, h, idx, v);
        if ((v[0].x < bx0 && v[1].x < bx0 && v[2].x < bx0) || (v[0].x > bx1 && v[1].x > bx1 && v[2].x > bx1) ||
            (v[0].y < by0 && v[1].y < by0 && v[2].y < by0) || (v[0].y > by1 && v[1].y > by1 && v[2].y > by1))
            continue;
        qi_face_line q;
        face_line(v, area2(v), ln->ax, ln->ay, ln->az, dx, dy, dz, &q);
        int64_t lon = 0, lod = 1, hin = 1, hid = 1;   /* (lo, hi) within (0, 1) */
        int okl = 1, okr = 1;
        for (int k = 0; k < 4 && (okl || okr); k++) {
            const int64_t e = k < 3 ? q.e[k] : -q.al, s = k < 3 ? q.s[k] : -q.be;   /* e + t s > 0 */
            if (s > 0) {
                if (cmp_frac(-e, s, lon, lod) > 0) lon = -e, lod = s;
            } else if (s < 0) {
                if (cmp_frac(e, -s, hin, hid) < 0) hin = e, hid = -s;
            } else if (e < 0 || (e == 0 && k == 3)) {
                okl = okr = 0;
            } else if (e == 0) {
                okl &= q.p[k] > 0;
                okr &= q.p[k] < 0;
            }
        }
        if ((!okl && !okr) || cmp_frac(lon, lod, hin, hid) >= 0) continue;
        fr->st->ray_tests++;
        const uint32_t p0 = step_bound(w, lon, lod, 1), p1 = step_bound(w, hin, hid, 1);
        const uint32_t m0 = step_bound(w, lon, lod, 0), m1 = step_bound(w, hin, hid, 0);
        /* t increasing: plus [t >= lo, t >= hi), minus [t > lo, t > hi); decreasing: the same bounds swapped */
        if (okl) {
            if (!w->from_b) add_range(lp, p0, p1), add_range(lm, m0, m1);
            else add_range(lp, m1, m0), add_range(lm, p1, p0);
        }
        if (okr) {
            if (!w->from_b) add_range(rp, p0, p1), add_range(rm, m0, m1);
            else add_range(rp, m1, m0), add_range(rm, p1, p0);
        }
    }
    int32_t cl = 0, cm = 0, cr = 0, cn = 0;
    for (uint32_t j = 0; j < w->count; j++) {
        cl += lp[j], cm += lm[j], cr += rp[j], cn += rm[j];
        const int64_t num = step_num(w, j);
        const int vis = (num > 0 && (cm == 0 || cn == 0)) || (num < (int64_t)w->d && (cl == 0 || cr == 0));
        if (vis) fr->bits[j >> 3] |= (uint8_t)(1u << (j & 7u));
    }
}

static void draw_line(qi_frame *fr, const qi_line *ln, uint32_t j, const mc_qi_hook *hook)
{
    mc_line_vertex la, lb;
    la.x = mc_raster_floor16(ln->ax), la.y = mc_raster_floor16(ln->ay), la.z = ln->az;
    lb.x = mc_raster_floor16(ln->bx), lb.y = mc_raster_floor16(ln->by), lb.z = ln->bz;
    walk w;
    if (!walk_init(fr->t->width, fr->t->height, la, lb, &w)) return;
    for (uint32_t i = 0; i < (w.count + 7u) / 8u; i++) fr->bits[i] = 0;
    const int v0 = ln->qi[0] == 0 || ln->qi[1] == 0, v1 = ln->qi[2] == 0 || ln->qi[3] == 0;
    uint32_t m = 0;
    int exact = 0, start = v0;
    if (fr->flags & MC_LINES_NO_HIDING) {
        for (uint32_t i = 0; i < (w.count + 7u) / 8u; i++) fr->bits[i] = 0xFFu;
    } else if (w.d == 0) {   /* one pixel: both ends */
        if (v0 || v1) fr->bits[0] = 1u;
    } else {
        uint32_t n = 0;
        if (!(fr->flags & MC_QI_FACE_BY_FACE) && collect(fr, ln, j, &n)) {
            ev_sort(fr, n);
            m = sweep(fr, ln, n, &start);
            bits_from_changes(fr, &w, fr->ev_t, m, v0, v1);
            fr->st->changes += m;
        } else {
            exact = 1;
            fr->st->exact_lines++;
            face_by_face(fr, ln, &w);
        }
    }
    const unsigned kind = ln->kind;
    const unsigned color = kind == MC_EDGE_SILHOUETTE ? MC_LINES_SILHOUETTE_COLOR
                           : kind == MC_EDGE_CREASE   ? MC_LINES_CREASE_COLOR
                                                      : MC_LINES_BORDER_COLOR;
    const uint32_t wd = w.d, wfirst = w.first, wcount = w.count;
    const int wfrom_b = w.from_b;
    const uint32_t drawn = walk_draw(&w, fr->t, fr->bits, (uint8_t)color);
    fr->st->pixels += w.count;
    fr->st->visible += drawn;
    fr->st->hidden += w.count - drawn;
    if (hook && hook->line) {
        mc_qi_line info;
        info.half = ln->half, info.kind = kind;
        info.a.x = ln->ax, info.a.y = ln->ay, info.a.z = ln->az;
        info.b.x = ln->bx, info.b.y = ln->by, info.b.z = ln->bz;
        for (int i = 0; i < 4; i++) info.qi[i] = ln->qi[i];
        info.exact = exact, info.visible_at_start = start;
        info.changes = exact ? 0 : m, info.change = fr->ev_t;
        info.d = wd, info.from_b = wfrom_b, info.first = wfirst, info.count = wcount;
        info.visible = fr->bits;
        hook->line(hook->user, &info);
    }
}

/* ---- the frame ----------------------------------------------------------------------------------------- */

/* Chooses the grids' cells and fills them; 0 when even one cell each does not fit in [mem, end).
 * Contour cells start at 8 pixels, line-end cells at 2, each no more than about twice its items
 * (more cells than items only cost memory and empty cells), then coarser until they fit. */
static int build_grid(qi_frame *fr, uint8_t *mem, uint8_t *end)
{
    qi_grid *g = &fr->g;
    const uint32_t w = fr->t->width, h = fr->t->height, C = fr->ncontours, L = fr->nlines;
    const uint32_t room = (uint32_t)(end - mem), evmin = MC_QI_MIN_EVENTS * MC_QI_EVENT_RECORD + 8u;
    uint32_t s = 3, sq = 1;
    for (;;) {
        g->shift = s + MC_XFORM_SUBPIXEL_BITS, g->qshift = sq + MC_XFORM_SUBPIXEL_BITS;
        g->nx = (w + (1u << s) - 1u) >> s, g->ny = (h + (1u << s) - 1u) >> s;
        g->qnx = (w + (1u << sq) - 1u) >> sq, g->qny = (h + (1u << sq) - 1u) >> sq;
        const uint32_t cells = g->nx * g->ny, qcells = g->qnx * g->qny;
        const int one = cells == 1u, qone = qcells == 1u;
        if (!one && cells > 2u * C + 16u) { s++; continue; }
        if (!qone && qcells > 16u * L + 16u) { sq++; continue; }
        uint64_t entries = 0;
        for (uint32_t i = 0; i < C; i++) entries += contour_cells(&fr->contours[i], g);
        const uint64_t need = 4u * ((uint64_t)cells + qcells + 2u) + 4u * entries + 40u * (uint64_t)L + 4u;
        if (need + evmin <= room) break;
        if (one && qone) return 0;
        if (!one && (qone || cells >= qcells)) s++;
        else sq++;
    }
    fr->st->grid_shift = s;
    const uint32_t cells = g->nx * g->ny, qcells = g->qnx * g->qny;
    g->chead = (uint32_t *)(void *)mem;
    g->qhead = g->chead + cells + 1u;
    g->centry = g->qhead + qcells + 1u;
    for (uint32_t i = 0; i <= cells; i++) g->chead[i] = 0;
    for (uint32_t i = 0; i <= qcells; i++) g->qhead[i] = 0;
    /* counting sort: counts, running ends, then each item placed at --end */
    uint32_t total = 0;
    for (uint32_t i = 0; i < C; i++) {
        const qi_contour *c = &fr->contours[i];
        const uint32_t x0 = cell(c->x0 < c->x1 ? c->x0 : c->x1, g->shift, g->nx), x1 = cell(c->x0 < c->x1 ? c->x1 : c->x0, g->shift, g->nx);
        const uint32_t y0 = cell(c->y0 < c->y1 ? c->y0 : c->y1, g->shift, g->ny), y1 = cell(c->y0 < c->y1 ? c->y1 : c->y0, g->shift, g->ny);
        for (uint32_t y = y0; y <= y1; y++)
            for (uint32_t x = x0; x <= x1; x++) g->chead[y * g->nx + x]++;
    }
    for (uint32_t i = 0; i < cells; i++) total += g->chead[i], g->chead[i] = total;
    g->chead[cells] = total;
    g->qentry = (qi_end *)(void *)(g->centry + total);
    for (uint32_t i = 0; i < C; i++) {
        const qi_contour *c = &fr->contours[i];
        const uint32_t x0 = cell(c->x0 < c->x1 ? c->x0 : c->x1, g->shift, g->nx), x1 = cell(c->x0 < c->x1 ? c->x1 : c->x0, g->shift, g->nx);
        const uint32_t y0 = cell(c->y0 < c->y1 ? c->y0 : c->y1, g->shift, g->ny), y1 = cell(c->y0 < c->y1 ? c->y1 : c->y0, g->shift, g->ny);
        for (uint32_t y = y0; y <= y1; y++)
            for (uint32_t x = x0; x <= x1; x++) g->centry[--g->chead[y * g->nx + x]] = i;
    }
    for (uint32_t j = 0; j < L; j++) {
        const qi_line *ln = fr->lines_top - 1 - j;
        g->qhead[cell(ln->ay, g->qshift, g->qny) * g->qnx + cell(ln->ax, g->qshift, g->qnx)]++;
        g->qhead[cell(ln->by, g->qshift, g->qny) * g->qnx + cell(ln->bx, g->qshift, g->qnx)]++;
    }
    total = 0;
    for (uint32_t i = 0; i < qcells; i++) total += g->qhead[i], g->qhead[i] = total;
    g->qhead[qcells] = total;
    for (uint32_t j = 0; j < L; j++) {
        const qi_line *ln = fr->lines_top - 1 - j;
        qi_end *e = &g->qentry[--g->qhead[cell(ln->ay, g->qshift, g->qny) * g->qnx + cell(ln->ax, g->qshift, g->qnx)]];
        e->x = ln->ax, e->y = ln->ay, e->id = 2u * j, e->f = MC_HALF_FACE(ln->half), e->g = ln->g;
        e = &g->qentry[--g->qhead[cell(ln->by, g->qshift, g->qny) * g->qnx + cell(ln->bx, g->qshift, g->qnx)]];
        e->x = ln->bx, e->y = ln->by, e->id = 2u * j + 1u, e->f = MC_HALF_FACE(ln->half), e->g = ln->g;
    }
    /* the events: what is left */
    uint8_t *ev = (uint8_t *)(g->qentry + 2u * L);
    ev += (8u - ((uintptr_t)ev & 7u)) & 7u;
    fr->ev_cap = (uint32_t)(end - ev) / MC_QI_EVENT_RECORD;
    fr->ev_t = (mc_qi_t *)(void *)ev;
    fr->ev_d = (int8_t *)(ev + 16u * fr->ev_cap);
    return 1;
}

/* The ray tests: every face against the line ends in the cells under its bounding box. */
static void ray_tests(qi_frame *fr)
{
    const qi_grid *g = &fr->g;
    const uint32_t faces = fr->c.lod->faces;
    for (uint32_t f = 0; f < faces; f++) {
        if (face_class(&fr->c, f) == CLS_NONE) continue;
        uint32_t idx[3];
        mc_raster_vertex v[3];
        corners(&fr->c, f, idx, v);
        int32_t x0 = v[0].x, x1 = v[0].x, y0 = v[0].y, y1 = v[0].y;
        for (int k = 1; k < 3; k++) {
            if (v[k].x < x0) x0 = v[k].x;
            if (v[k].x > x1) x1 = v[k].x;
            if (v[k].y < y0) y0 = v[k].y;
            if (v[k].y > y1) y1 = v[k].y;
        }
        const uint32_t cx0 = cell(x0, g->qshift, g->qnx), cx1 = cell(x1, g->qshift, g->qnx);
        const uint32_t cy0 = cell(y0, g->qshift, g->qny), cy1 = cell(y1, g->qshift, g->qny);
        int64_t a = 0;
        for (uint32_t cy = cy0; cy <= cy1; cy++)
            for (uint32_t cx = cx0; cx <= cx1; cx++) {
                const uint32_t ci = cy * g->qnx + cx;
                for (uint32_t e = g->qhead[ci]; e < g->qhead[ci + 1]; e++) {
                    const qi_end *q = &g->qentry[e];
                    if (q->x < x0 || q->x > x1 || q->y < y0 || q->y > y1 || f == q->f || f == q->g) continue;
                    qi_line *ln = fr->lines_top - 1 - (q->id >> 1);
                    if (!a) a = area2(v);
                    fr->st->ray_tests++;
                    int l, r;
                    const int32_t dx = ln->bx - ln->ax, dy = ln->by - ln->ay, dz = (int32_t)ln->bz - (int32_t)ln->az;
                    if (!(q->id & 1u)) {
                        ray(v, a, ln->ax, ln->ay, ln->az, dx, dy, dz, &l, &r);
                        ln->qi[0] += (uint32_t)l, ln->qi[1] += (uint32_t)r;
                    } else {   /* from b backwards: its left is the line's right */
                        ray(v, a, ln->bx, ln->by, ln->bz, -dx, -dy, -dz, &r, &l);
                        ln->qi[2] += (uint32_t)l, ln->qi[3] += (uint32_t)r;
                    }
                }
            }
    }
}

int mc_mesh_qi(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t,
               const mc_qi_buffers *buf, const mc_qi_hook *hook, mc_qi_stats *stats)
{
    /* the caller's stats, or a local: filled field by field (an aggregate initialiser or a
     * structure assignment may become a memset or memcpy call, which freestanding code lacks) */
    mc_qi_stats local;
    mc_qi_stats *const st = stats ? stats : &local;
    st->edges = st->silhouettes = st->creases = st->borders = st->skipped = st->skipped_faces = st->lines = 0;
    st->clipped = st->clipped_away = 0;
    st->contours = st->pixels = st->visible = st->hidden = st->changes = st->crossings = st->pair_tests = 0;
    st->ray_tests = st->exact_lines = st->grid_shift = st->work_needed = 0;
    if (!lod || !lod->pm || !view || !t || !t->color || !t->depth || !buf || !buf->facing || !buf->work) return MC_ERR_ARG;
    if (t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    if (!t->width || !t->height) return MC_OK;
    qi_frame fr;
    fr.t = t, fr.flags = flags, fr.st = st;
    fr.c.lod = lod;
    mc_xform_init(&fr.c.x, view, t->width, t->height);
    fr.c.cache = buf->cache;
    fr.c.facing = buf->facing;
    const uint32_t faces = lod->faces, side = t->width > t->height ? t->width : t->height;
    fr.side = side;

    /* the work buffer: per-face and per-step arrays, then contours upwards and lines downwards */
    uint8_t *base = (uint8_t *)buf->work;
    uint32_t bytes = buf->work_bytes;
    const uint32_t skew = (uint32_t)((8u - ((uintptr_t)base & 7u)) & 7u);
    bytes = bytes > skew ? (bytes - skew) & ~7u : 0u;
    base += skew;
    const uint32_t fixed = align8((faces + 7u) / 8u) + align8((side + 8u) / 8u) + align8(16u * (side + 1u));
    st->work_needed = MC_QI_WORK_BYTES(faces, 0, 0, side);
    if (buf->work_bytes < st->work_needed || fixed + 8u > bytes) return MC_ERR_SIZE;
    uint8_t *hides = base;
    fr.bits = base + align8((faces + 7u) / 8u);
    fr.cnt = (int32_t *)(void *)(fr.bits + align8((side + 8u) / 8u));
    uint8_t *lo = (uint8_t *)fr.cnt + align8(16u * (side + 1u)), *hi = base + bytes;
    fr.contours = (qi_contour *)(void *)lo;
    fr.lines_top = (qi_line *)(void *)hi;
    fr.c.hides = hides;

    /* 1. facing bits (mc_mesh_facing's: a face with a flagged corner by its plane) and hiding bits */
    if (buf->cache) mc_mesh_project(lod, &fr.c.x, buf->cache);
    uint8_t *facing = buf->facing;
    for (uint32_t i = 0; i < MC_MESH_FACING_BYTES(faces); i++) facing[i] = 0, hides[i] = 0;
    for (uint32_t f = 0; f < faces; f++) {
        uint32_t idx[3];
        mc_raster_vertex v[3];
        const uint8_t b = (uint8_t)(1u << (f & 7u));
        if (corners(&fr.c, f, idx, v)) {
            st->skipped_faces++;
            if (flagged_front(&fr.c, idx)) facing[f >> 3] |= b;
            continue;
        }
        const int64_t a = area2(v);
        if (a < 0) facing[f >> 3] |= b;
        if (a != 0) hides[f >> 3] |= b;
    }

    /* 2. the edges: kinds, contours, lines */
    const int hiding = !(flags & MC_LINES_NO_HIDING);
    uint32_t C = 0, L = 0;
    int room = 1;
    for (uint32_t f = 0; f < faces; f++) {
        uint32_t idx[3];
        mc_raster_vertex v[3];
        uint32_t fflags = 0;
        int projected = 0;
        face_idx(lod, f, idx);
        const unsigned cf = face_class(&fr.c, f);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;   /* the earlier face's */
            const unsigned kind = mc_mesh_edge_kind(lod, facing, h, o);
            st->edges++;
            st->silhouettes += kind == MC_EDGE_SILHOUETTE;
            st->creases += kind == MC_EDGE_CREASE;
            st->borders += kind == MC_EDGE_BORDER;
            const uint32_t g = o == MC_NO_HALF_EDGE ? MC_NO_HALF_EDGE : MC_HALF_FACE(o);
            /* a contour: the faces that can hide are not one on each side. f's third corner lies on
             * the positive side of its edge a -> b (cross(b - a, P - a) > 0) when f is back-facing;
             * g runs the edge b -> a (pmesh.h: the level's neighbour holds the same two corners the
             * other way round), so its third corner does when g is front-facing */
            const unsigned cg = g == MC_NO_HALF_EDGE ? CLS_NONE : face_class(&fr.c, g);
            const unsigned pos = (cf == CLS_BACK) + (cg == CLS_FRONT), neg = (cf == CLS_FRONT) + (cg == CLS_BACK);
            const int contour = hiding && pos != neg, drawn = (kind & flags) != 0;
            if (!contour && !drawn) continue;
            if (!projected) fflags = project(&fr.c, idx, v), projected = 1;
            if (contour) {
                uint32_t gi[3];
                mc_raster_vertex gv[3];
                const mc_raster_vertex *a = &v[k], *b = &v[(k + 1) % 3];
                if (fflags) {   /* f hides nothing: g does, and holds the same corners unflagged */
                    const uint32_t jg = MC_HALF_EDGE_INDEX(o);
                    corners(&fr.c, g, gi, gv);
                    a = &gv[(jg + 1u) % 3u], b = &gv[jg];
                }
                if (room && (uint8_t *)(fr.contours + C + 1) <= (uint8_t *)(fr.lines_top - L)) {
                    qi_contour *c = &fr.contours[C];
                    c->x0 = a->x, c->y0 = a->y, c->x1 = b->x, c->y1 = b->y;
                    c->z0 = (uint16_t)a->z, c->z1 = (uint16_t)b->z;
                    c->pos = (uint8_t)pos, c->neg = (uint8_t)neg, c->stamp = 0, c->pad[0] = c->pad[1] = 0;
                } else {
                    room = 0;
                }
                C++;
            }
            if (!drawn) continue;
            mc_raster_vertex ends[2];   /* field by field: a structure assignment may become a memcpy call */
            for (uint32_t i = 0; i < 2; i++) {
                const mc_raster_vertex *c = &v[(k + i) % 3];
                ends[i].x = c->x, ends[i].y = c->y, ends[i].z = c->z;
            }
            if (fflags) {   /* as mc_mesh_lines: a flagged end clips the line */
                const int clipped = mc_mesh_edge_ends(lod, &fr.c.x, h, ends);
                if (clipped == 2) { st->clipped_away++; continue; }
                st->clipped += (uint32_t)clipped;
            }
            const mc_raster_vertex *a = &ends[0], *b = &ends[1];
            mc_line_vertex la, lb;
            la.x = mc_raster_floor16(a->x), la.y = mc_raster_floor16(a->y), la.z = a->z;
            lb.x = mc_raster_floor16(b->x), lb.y = mc_raster_floor16(b->y), lb.z = b->z;
            walk w;
            if (!walk_init(t->width, t->height, la, lb, &w)) continue;   /* no pixel on the target */
            if (room && (uint8_t *)(fr.contours + C) <= (uint8_t *)(fr.lines_top - L - 1)) {
                qi_line *ln = fr.lines_top - 1 - L;
                ln->ax = a->x, ln->ay = a->y, ln->bx = b->x, ln->by = b->y;
                ln->az = (uint16_t)a->z, ln->bz = (uint16_t)b->z;
                ln->half = h, ln->g = g, ln->kind = kind;
                ln->qi[0] = ln->qi[1] = ln->qi[2] = ln->qi[3] = 0;
            } else {
                room = 0;
            }
            L++;
        }
    }
    st->lines = L, st->contours = C;
    st->work_needed = MC_QI_WORK_BYTES(faces, L, C, side);
    fr.nlines = L, fr.ncontours = C;
    if (!room || buf->work_bytes < st->work_needed) return MC_ERR_SIZE;

    /* 3. the grid; 4. the ray tests */
    uint8_t *mid = (uint8_t *)(fr.contours + C);
    mid += (8u - ((uintptr_t)mid & 7u)) & 7u;
    if (hiding) {
        if (!build_grid(&fr, mid, (uint8_t *)(fr.lines_top - L))) return MC_ERR_SIZE;
        ray_tests(&fr);
    }

    /* 5. each line, in mc_mesh_lines' order */
    for (uint32_t j = 0; j < L; j++) draw_line(&fr, fr.lines_top - 1 - j, j, hook);
    return MC_OK;
}
