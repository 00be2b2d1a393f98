/* Checks the quantitative-invisibility line drawing (runtime/src/mesh_qi.c, modelc/mesh_qi.h) on a
 * baked progressive mesh. Built by tests/gen/qi.sh like pmesh_check.c: -DPM=mc_pmesh_NAME
 * -include NAME.h, the bake's files, the runtime and runtime/ref/xform_ref.c.
 * Long because its reference (exact fractions, line.h's steps, the brute-force ray test) and its
 * modes share the runtime set-up and the line records, which split files would each repeat.
 *
 *   qi_check check N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE     (zoom, eye Q16; xform.h)
 *       level N through that view on a W x H target; one line "ok: ..." or "not ok: ...":
 *       - the edges and their kinds counted as mc_mesh_lines counts them (its clipped and clipped
 *         away lines too, none skipped), and with
 *         MC_LINES_NO_HIDING the target byte for byte mc_mesh_lines' with MC_LINES_NO_HIDING;
 *       - each line's steps, pixels and depths as line.h's promise gives them (recomputed here), its
 *         drawn steps those whose t lies in its visible set as its change list gives it (exact, in
 *         128-bit integers), and the target exactly the union of the lines' drawn steps in order;
 *       - the same target without the vertex cache, from the definition face by face
 *         (MC_QI_FACE_BY_FACE), and with the least work buffer the frame says it needs (one byte
 *         less: MC_ERR_SIZE, nothing drawn); guard zones untouched;
 *       - the reference: at every step on the target and on both sides of every visibility change
 *         (0.3 pixel away, where no other change is that near), a brute-force test in doubles of the exact projections
 *         (runtime/ref/xform_ref.c; a line with a flagged end between its exactly clipped ends,
 *         mc_ref_clip_segment) against every face of the level other than the line's own and the
 *         faces the runtime flags (they hide nothing, mesh_qi.h):
 *         hidden for sure when each of P and 8 points around it 0.15 pixel away lies inside a face
 *         nearer than the line by more than 2 depth units plus 0.3 pixel of both depth slopes,
 *         visible for sure when every face is 0.15 pixel away from P or farther than that; the
 *         module must agree wherever the reference is sure (elsewhere the sample is within the
 *         tolerance of a visibility change or of a tie: counted, not judged);
 *       - the z-buffer method (mc_mesh_render in paper, culled when the part is closed, then
 *         mc_mesh_lines): the line pixels where the two drawings differ, reported only.
 *   qi_check image N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE OUT
 *       OUT.qi.ppm and OUT.zbuf.ppm: the two drawings' line pixels on white
 *   qi_check boxes W H
 *       a two-box scene (the bake of tests/gen/qi.sh's boxes.off) seen frontally, orthographic: the
 *       back box's lines are hidden exactly at the steps whose point lies strictly inside the front
 *       box's projected rectangle (exact, in integers), the front box's are whole.
 *   qi_check bench N W H FRAMES
 *       ms per frame (median wall clock and CPU) over FRAMES views of one turn (yaw i / FRAMES of a
 *       turn, pitch 0, zoom 1, orthographic) of: the z-buffer drawing (mc_clear, mc_mesh_render in
 *       paper, culled when closed, mc_mesh_lines), and mc_clear + mc_mesh_qi, with and without caches
 *   qi_check frames zbuf|qi|zbuf-nocache|qi-nocache N W H FRAMES
 *       the same frames untimed, for valgrind --tool=callgrind --toggle-collect=... (mc_mesh_render and
 *       mc_mesh_lines, or mc_mesh_qi)
 */
#ifndef _POSIX_C_SOURCE
#define _POSIX_C_SOURCE 200809L
#endif
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "modelc/mesh_lines.h"
#include "modelc/mesh_qi.h"
#include "modelc/mesh_render.h"
#include "modelc/pmesh.h"
#include "../../runtime/ref/xform_ref.h"

extern const mc_pmesh PM;

/* mc_mesh_render gained a vertex cache argument; either form links */
#ifdef MC_MESH_CACHE_BYTES
#define RENDER(lod, v, fl, t, cache, st) mc_mesh_render(lod, v, fl, t, cache, st)
#else
#define RENDER(lod, v, fl, t, cache, st) ((void)(cache), mc_mesh_render(lod, v, fl, t, st))
#endif

static mc_pmesh_lod lod;
static uint32_t W, H;
static mc_view view;

/* ---- exact fractions ------------------------------------------------------------------------------- */

typedef __int128 i128;
static int cmpq(int64_t a, int64_t b, int64_t c, int64_t d)   /* sign of a/b - c/d, b, d > 0 */
{
    const i128 x = (i128)a * d, y = (i128)c * b;
    return x < y ? -1 : x > y;
}

/* ---- lines the hook reports --------------------------------------------------------------------------- */

typedef struct rec {
    mc_qi_line info;   /* change and visible point into the copies below */
    mc_qi_t *change;
    uint8_t *bits;
} rec;

typedef struct recs {
    rec *r;
    size_t n, cap;
} recs;

static void hook_fn(void *user, const mc_qi_line *l)
{
    recs *rs = user;
    if (rs->n == rs->cap) {
        rs->cap = rs->cap ? 2 * rs->cap : 256;
        rs->r = realloc(rs->r, rs->cap * sizeof(rec));
        if (!rs->r) exit(2);
    }
    rec *r = &rs->r[rs->n++];
    r->info = *l;
    r->change = malloc(sizeof(mc_qi_t) * (l->changes + 1));
    r->bits = malloc((l->count + 7) / 8 + 1);
    if (!r->change || !r->bits) exit(2);
    memcpy(r->change, l->change, sizeof(mc_qi_t) * l->changes);
    memcpy(r->bits, l->visible, (l->count + 7) / 8);
    r->info.change = r->change, r->info.visible = r->bits;
}

static void recs_free(recs *rs)
{
    for (size_t i = 0; i < rs->n; i++) free(rs->r[i].change), free(rs->r[i].bits);
    free(rs->r);
    rs->r = NULL, rs->n = rs->cap = 0;
}

static int bitv(const uint8_t *b, uint32_t j) { return (b[j >> 3] >> (j & 7)) & 1; }

/* ---- running the module ---------------------------------------------------------------------------------- */

static uint8_t *facing, *lines_mem;   /* facing bits (mc_mesh_facing, mc_mesh_qi); mc_mesh_lines' memory */
static mc_xvertex *vcache;

/* a target inside guard zones */
typedef struct gtarget {
    mc_target t;
    uint8_t *cmem;
    uint16_t *dmem;
} gtarget;
#define GUARD 4096

static void gt_init(gtarget *g)
{
    const size_t px = (size_t)W * H;
    g->cmem = malloc(px + 2 * GUARD);
    g->dmem = malloc(2 * (px + 2 * GUARD));
    if (!g->cmem || !g->dmem) exit(2);
    memset(g->cmem, 0xA5, px + 2 * GUARD);
    for (size_t i = 0; i < px + 2 * GUARD; i++) g->dmem[i] = 0x5A5A;
    g->t.color = g->cmem + GUARD, g->t.depth = g->dmem + GUARD, g->t.width = (uint16_t)W, g->t.height = (uint16_t)H;
    mc_clear(&g->t);
}

static size_t gt_guard(const gtarget *g)
{
    const size_t px = (size_t)W * H;
    size_t bad = 0;
    for (size_t i = 0; i < GUARD; i++)
        bad += (g->cmem[i] != 0xA5) + (g->cmem[GUARD + px + i] != 0xA5) + (g->dmem[i] != 0x5A5A) +
               (g->dmem[GUARD + px + i] != 0x5A5A);
    return bad;
}

static int gt_same(const gtarget *a, const gtarget *b)
{
    const size_t px = (size_t)W * H;
    return !memcmp(a->t.color, b->t.color, px) && !memcmp(a->t.depth, b->t.depth, 2 * px);
}

static void gt_free(gtarget *g) { free(g->cmem), free(g->dmem); }

static int run_qi(gtarget *g, unsigned flags, int cache, uint32_t work_bytes, recs *rs, mc_qi_stats *st)
{
    uint8_t *work = malloc(work_bytes + 16);
    if (!work) exit(2);
    memset(work, 0x77, work_bytes + 16);
    mc_qi_buffers b = {facing, cache ? vcache : NULL, work + 1, work_bytes};   /* misaligned on purpose */
    mc_qi_hook hk = {hook_fn, rs};
    const int rc = mc_mesh_qi(&lod, &view, flags, &g->t, &b, rs ? &hk : NULL, st);
    int guard = 0;
    for (int i = 0; i < 15; i++) guard |= work[1 + work_bytes + i] != 0x77;
    guard |= work[0] != 0x77;
    free(work);
    return guard ? -100 : rc;
}

/* ---- line.h's promise, recomputed ----------------------------------------------------------------------- */

typedef struct bres {
    int32_t sx, sy, ex, ey;   /* start, end pixels (as walked) */
    uint32_t zs, ze;          /* their depths, clamped */
    int xmajor, from_b;
    uint32_t d, m;
} bres;

static int32_t fl16(int32_t v) { return (int32_t)floor(v / 16.0); }

static void bres_init(bres *b, const mc_raster_vertex *a, const mc_raster_vertex *c)
{
    int32_t ax = fl16(a->x), ay = fl16(a->y), cx = fl16(c->x), cy = fl16(c->y);
    uint32_t za = a->z < MC_LINE_DEPTH_MAX ? a->z : MC_LINE_DEPTH_MAX, zc = c->z < MC_LINE_DEPTH_MAX ? c->z : MC_LINE_DEPTH_MAX;
    const int32_t dx = cx - ax, dy = cy - ay;
    b->xmajor = abs(dx) >= abs(dy);
    b->from_b = b->xmajor ? dx < 0 : dy < 0;
    if (b->from_b) b->sx = cx, b->sy = cy, b->ex = ax, b->ey = ay, b->zs = zc, b->ze = za;
    else b->sx = ax, b->sy = ay, b->ex = cx, b->ey = cy, b->zs = za, b->ze = zc;
    b->d = (uint32_t)(b->xmajor ? abs(dx) : abs(dy));
    b->m = (uint32_t)(b->xmajor ? abs(dy) : abs(dx));
    if (!dx && !dy && zc < za) b->zs = zc;
}

static int64_t ceil_div(int64_t n, int64_t m) { return n >= 0 ? (n + m - 1) / m : -((-n) / m); }   /* m > 0 */

/* step i's pixel and depth: offsets the integers nearest to i M / D and i |dz| / D, halves towards the start */
static void bres_step(const bres *b, uint32_t i, int32_t *x, int32_t *y, uint32_t *z)
{
    if (b->d == 0) { *x = b->sx, *y = b->sy, *z = b->zs; return; }
    const int64_t D2 = 2 * (int64_t)b->d;
    const int64_t k = ceil_div(2 * (int64_t)i * b->m - b->d, D2);
    const int32_t dmin = b->xmajor ? (b->ey >= b->sy ? 1 : -1) : (b->ex >= b->sx ? 1 : -1);
    if (b->xmajor) *x = b->sx + (int32_t)i, *y = b->sy + dmin * (int32_t)k;
    else *y = b->sy + (int32_t)i, *x = b->sx + dmin * (int32_t)k;
    const int64_t dz = (int64_t)b->ze - b->zs, adz = dz < 0 ? -dz : dz;
    const int64_t kz = ceil_div(2 * (int64_t)i * adz - b->d, D2);
    *z = (uint32_t)((int64_t)b->zs + (dz < 0 ? -kz : kz));
}

static unsigned kind_color(unsigned kind)
{
    return kind == MC_EDGE_SILHOUETTE ? MC_LINES_SILHOUETTE_COLOR : kind == MC_EDGE_CREASE ? MC_LINES_CREASE_COLOR : MC_LINES_BORDER_COLOR;
}

/* the module's visibility at t = num / den from a line's change list (not exact lines) */
static int vis_at(const mc_qi_line *l, int64_t num, int64_t den)
{
    if (num == 0) return l->qi[0] == 0 || l->qi[1] == 0;
    if (num == den) return l->qi[2] == 0 || l->qi[3] == 0;
    uint32_t k = 0;
    while (k < l->changes && cmpq(l->change[k].num, l->change[k].den, num, den) < 0) k++;
    if (k < l->changes && cmpq(l->change[k].num, l->change[k].den, num, den) == 0) return 1;
    return l->visible_at_start ^ (int)(k & 1);
}

/* ---- the reference: exact projections, faces binned on a grid of 4-pixel cells --------------------- */

#define TAU 0.15
#define CHANGE_PX 0.3
typedef struct rface {
    double x[3], y[3], z[3];
    double nx[3], ny[3], c[3];   /* inside: nx x + ny y + c > 0, unit normals, distance in pixels */
    double gx, gy, z0x, z0y, z0; /* depth plane z0 + gx (x - z0x) + gy (y - z0y) */
    int ok;                      /* unflagged (by the runtime) with area */
} rface;

static rface *rf;
static uint32_t *cell_head, *cell_list, gnx, gny;
#define RCELL 4.0

static int rcell(double v, uint32_t n)
{
    double c = floor(v / RCELL);
    if (c < 0) c = 0;
    if (c > n - 1) c = n - 1;
    return (int)c;
}

static void ref_build(void)
{
    const uint32_t F = lod.faces;
    rf = calloc(F + 1, sizeof(rface));
    mc_xform x;
    mc_xform_init(&x, &view, W, H);
    for (uint32_t f = 0; f < F; f++) {
        uint32_t c[3];
        int32_t p[3][3];
        mc_raster_vertex v[3];
        rface *r = &rf[f];
        if (mc_mesh_face(&lod, &x, f, p, v)) continue;   /* the runtime flags it: it hides nothing */
        mc_pmesh_lod_face(&lod, f, c);
        for (int k = 0; k < 3; k++) {
            mc_ref_vertex e = mc_ref_project(&view, W, H, p[k]);
            r->x[k] = e.x, r->y[k] = e.y, r->z[k] = e.z;
        }
        const double a = (r->x[1] - r->x[0]) * (r->y[2] - r->y[0]) - (r->x[2] - r->x[0]) * (r->y[1] - r->y[0]);
        if (fabs(a) < 1e-12) continue;
        const double sg = a > 0 ? 1 : -1;
        for (int k = 0; k < 3; k++) {
            const int k1 = (k + 1) % 3;
            const double ex = r->x[k1] - r->x[k], ey = r->y[k1] - r->y[k], len = hypot(ex, ey);
            /* cross(e, P - V) = ex (y - vy) - ey (x - vx) */
            r->nx[k] = -sg * ey / len, r->ny[k] = sg * ex / len;
            r->c[k] = -(r->nx[k] * r->x[k] + r->ny[k] * r->y[k]);
        }
        const double z1 = r->z[1] - r->z[0], z2 = r->z[2] - r->z[0];
        const double x1 = r->x[1] - r->x[0], y1 = r->y[1] - r->y[0], x2 = r->x[2] - r->x[0], y2 = r->y[2] - r->y[0];
        r->gx = (z1 * y2 - z2 * y1) / a, r->gy = (x1 * z2 - x2 * z1) / a;
        r->z0x = r->x[0], r->z0y = r->y[0], r->z0 = r->z[0];
        r->ok = 1;
    }
    gnx = (uint32_t)ceil(W / RCELL), gny = (uint32_t)ceil(H / RCELL);
    cell_head = calloc((size_t)gnx * gny + 1, sizeof(uint32_t));
    size_t total = 0;
    for (int pass = 0; pass < 2; pass++) {
        for (uint32_t f = 0; f < F; f++) {
            const rface *r = &rf[f];
            if (!r->ok) continue;
            double x0 = fmin(r->x[0], fmin(r->x[1], r->x[2])) - 2 * TAU, x1 = fmax(r->x[0], fmax(r->x[1], r->x[2])) + 2 * TAU;
            double y0 = fmin(r->y[0], fmin(r->y[1], r->y[2])) - 2 * TAU, y1 = fmax(r->y[0], fmax(r->y[1], r->y[2])) + 2 * TAU;
            for (int cy = rcell(y0, gny); cy <= rcell(y1, gny); cy++)
                for (int cx = rcell(x0, gnx); cx <= rcell(x1, gnx); cx++) {
                    if (pass == 0) cell_head[cy * gnx + cx + 1]++;
                    else cell_list[cell_head[cy * gnx + cx]++] = f;
                }
        }
        if (pass == 0) {
            for (uint32_t i = 0; i < gnx * gny; i++) cell_head[i + 1] += cell_head[i];
            total = cell_head[gnx * gny];
            cell_list = malloc(sizeof(uint32_t) * (total + 1));
        }
    }
    for (uint32_t i = gnx * gny; i > 0; i--) cell_head[i] = cell_head[i - 1];   /* back to starts */
    cell_head[0] = 0;
}

static void ref_free(void) { free(rf), free(cell_head), free(cell_list); }

static double rdepth(const rface *r, double x, double y) { return r->z0 + r->gx * (x - r->z0x) + r->gy * (y - r->z0y); }

/* 1: hidden for sure, 0: visible for sure, -1: within the tolerance. ge: |dz/dpixel| along the line */
static int ref_class(double px, double py, double ze, double ge, uint32_t own1, uint32_t own2)
{
    const uint32_t ci = (uint32_t)rcell(py, gny) * gnx + (uint32_t)rcell(px, gnx);
    int visible = 1;
    int covered[9] = {0};
    for (uint32_t e = cell_head[ci]; e < cell_head[ci + 1]; e++) {
        const uint32_t f = cell_list[e];
        if (f == own1 || f == own2) continue;
        const rface *r = &rf[f];
        const double tz = 2 + 2 * TAU * (hypot(r->gx, r->gy) + ge);
        double dmin = 1e300;
        for (int k = 0; k < 3; k++) dmin = fmin(dmin, r->nx[k] * px + r->ny[k] * py + r->c[k]);
        if (!(dmin < -TAU || rdepth(r, px, py) > ze + tz)) visible = 0;
        for (int q = 0; q < 9; q++) {
            if (covered[q]) continue;
            const double qx = px + (q ? TAU * cos(q * 0.78539816339744831) : 0), qy = py + (q ? TAU * sin(q * 0.78539816339744831) : 0);
            int in = 1;
            for (int k = 0; k < 3 && in; k++) in = r->nx[k] * qx + r->ny[k] * qy + r->c[k] > 0;
            if (in && rdepth(r, qx, qy) < ze - tz) covered[q] = 1;
        }
    }
    int hidden = 1;
    for (int q = 0; q < 9; q++) hidden &= covered[q];
    return hidden ? 1 : visible ? 0 : -1;
}

/* ---- check ------------------------------------------------------------------------------------------------ */

static char first[400];
static unsigned long problems;
#define PROBLEM(...) do { if (!problems++) snprintf(first, sizeof first, __VA_ARGS__); } while (0)

static int check(void)
{
    const uint32_t F = lod.faces;
    mc_qi_stats st, st2;
    mc_lines_stats ls;
    recs rs = {0};
    const uint32_t big = 64u << 20;

    /* kinds and NO_HIDING against mc_mesh_lines */
    gtarget a, b;
    gt_init(&a), gt_init(&b);
    int rc = run_qi(&a, MC_LINES_ALL | MC_LINES_NO_HIDING, 1, big, NULL, &st);
    mc_mesh_lines(&lod, &view, MC_LINES_ALL | MC_LINES_NO_HIDING, &b.t, lines_mem, NULL, &ls);
    if (rc != MC_OK) PROBLEM("mc_mesh_qi returned %d (no hiding)", rc);
    if (st.edges != ls.edges || st.silhouettes != ls.silhouettes || st.creases != ls.creases || st.borders != ls.borders ||
        st.skipped != 0 || ls.skipped != 0 || st.clipped != ls.clipped || st.clipped_away != ls.clipped_away)
        PROBLEM("counts: edges %u %u %u %u skipped %u clipped %u away %u, mc_mesh_lines %u %u %u %u skipped %u clipped %u "
                "away %u", st.edges, st.silhouettes, st.creases, st.borders, st.skipped, st.clipped, st.clipped_away,
                ls.edges, ls.silhouettes, ls.creases, ls.borders, ls.skipped, ls.clipped, ls.clipped_away);
    if (!gt_same(&a, &b)) PROBLEM("with MC_LINES_NO_HIDING the target is not mc_mesh_lines'");
    if (st.pixels != ls.pixels) PROBLEM("no hiding: %u pixels, mc_mesh_lines %u", st.pixels, ls.pixels);
    gt_free(&a), gt_free(&b);

    /* the drawing, with the hook */
    gtarget q;
    gt_init(&q);
    rc = run_qi(&q, MC_LINES_ALL, 1, big, &rs, &st);
    if (rc != MC_OK) PROBLEM("mc_mesh_qi returned %d", rc);
    const size_t px = (size_t)W * H;
    /* the union of the lines' drawn steps, recomputed from line.h, and each line's bits from its changes */
    uint8_t *ec = malloc(px);
    uint16_t *ed = malloc(2 * px);
    for (size_t i = 0; i < px; i++) ec[i] = 0, ed[i] = MC_DEPTH_EMPTY;
    unsigned long steps = 0, vis_steps = 0, bad_bits = 0, bad_run = 0;
    for (size_t i = 0; i < rs.n; i++) {
        const mc_qi_line *l = &rs.r[i].info;
        bres br;
        bres_init(&br, &l->a, &l->b);
        if (br.d != l->d || br.from_b != l->from_b) { bad_run++; continue; }
        uint32_t on0 = UINT32_MAX, on1 = 0;
        for (uint32_t s = 0; s <= br.d; s++) {
            int32_t x, y;
            uint32_t z;
            bres_step(&br, s, &x, &y, &z);
            if (x < 0 || y < 0 || x >= (int32_t)W || y >= (int32_t)H) continue;
            if (on0 == UINT32_MAX) on0 = s;
            on1 = s;
        }
        if (on0 != l->first || on1 - on0 + 1 != l->count) { bad_run++; continue; }
        for (uint32_t j = 0; j < l->count; j++) {
            const uint32_t s = l->first + j;
            int32_t x, y;
            uint32_t z;
            bres_step(&br, s, &x, &y, &z);
            const int v = bitv(l->visible, j);
            steps++, vis_steps += v;
            if (!l->exact) {
                int want;
                if (l->d == 0) want = vis_at(l, 0, 1) || vis_at(l, 1, 1);
                else want = vis_at(l, l->from_b ? (int64_t)(l->d - s) : (int64_t)s, l->d);
                bad_bits += want != v;
            }
            if (v) ec[(size_t)y * W + x] = (uint8_t)kind_color(l->kind), ed[(size_t)y * W + x] = (uint16_t)z;
        }
    }
    if (bad_run) PROBLEM("%lu lines' steps on the target are not line.h's", bad_run);
    if (bad_bits) PROBLEM("%lu steps drawn against their lines' change lists", bad_bits);
    unsigned long img = 0;
    for (size_t i = 0; i < px; i++) img += ec[i] != (q.t.depth[i] == MC_DEPTH_EMPTY ? 0 : q.t.color[i]) || ed[i] != q.t.depth[i];
    if (img) PROBLEM("%lu pixels differ from the union of the lines' drawn steps", img);
    if (st.visible != vis_steps || st.pixels != steps) PROBLEM("stats %u of %u visible, the lines say %lu of %lu", st.visible, st.pixels, vis_steps, steps);
    if (gt_guard(&q)) PROBLEM("guard zones touched");

    /* without the cache; face by face; the least work buffer */
    gtarget n;
    gt_init(&n);
    rc = run_qi(&n, MC_LINES_ALL, 0, big, NULL, &st2);
    if (rc != MC_OK || !gt_same(&n, &q)) PROBLEM("without the vertex cache the target differs (rc %d)", rc);
    gt_free(&n);
    gt_init(&n);
    rc = run_qi(&n, MC_LINES_ALL | MC_QI_FACE_BY_FACE, 1, big, NULL, &st2);
    unsigned long fbf = 0;
    for (size_t i = 0; i < px; i++) fbf += n.t.color[i] != q.t.color[i] || n.t.depth[i] != q.t.depth[i];
    if (rc != MC_OK || fbf) PROBLEM("face by face (the definition) %lu pixels differ from Appel's (rc %d)", fbf, rc);
    gt_free(&n);
    gt_init(&n);
    rc = run_qi(&n, MC_LINES_ALL, 1, st.work_needed - 1, NULL, &st2);
    unsigned long drawn_small = 0;
    for (size_t i = 0; i < px; i++) drawn_small += n.t.depth[i] != MC_DEPTH_EMPTY;
    if (rc != MC_ERR_SIZE || drawn_small || st2.work_needed != st.work_needed)
        PROBLEM("work %u - 1 bytes: rc %d, %lu pixels drawn, needed %u", st.work_needed, rc, drawn_small, st2.work_needed);
    gt_free(&n);
    gt_init(&n);
    rc = run_qi(&n, MC_LINES_ALL, 1, st.work_needed, NULL, &st2);
    if (rc != MC_OK || !gt_same(&n, &q)) PROBLEM("work of exactly %u bytes: rc %d, same target %d", st.work_needed, rc, gt_same(&n, &q));
    const uint32_t least_shift = st2.grid_shift;
    gt_free(&n);

    /* the reference */
    ref_build();
    unsigned long sure_h = 0, sure_v = 0, amb = 0, dis = 0, csure = 0, camb = 0, cdis = 0, cnear = 0;
    char dfirst[300] = "";
    for (size_t i = 0; i < rs.n; i++) {
        const mc_qi_line *l = &rs.r[i].info;
        const uint32_t f = MC_HALF_FACE(l->half), k = MC_HALF_EDGE_INDEX(l->half);
        const uint32_t o = mc_pmesh_lod_opposite(&lod, l->half), g = o == MC_NO_HALF_EDGE ? UINT32_MAX : MC_HALF_FACE(o);
        uint32_t c[3];
        int32_t pa[3], pb[3];
        mc_pmesh_lod_face(&lod, f, c);
        mc_pmesh_position(&PM, c[k], pa);
        mc_pmesh_position(&PM, c[(k + 1) % 3], pb);
        /* the exact ends: the corners' projections, or the edge's clipped ends where one is flagged */
        mc_ref_vertex e[2];
        if (!mc_ref_clip_segment(&view, W, H, pa, pb, e)) { amb += l->count; continue; }
        const mc_ref_vertex ea = e[0], eb = e[1];
        const double len = hypot(eb.x - ea.x, eb.y - ea.y), ge = len > 0 ? fabs(eb.z - ea.z) / len : 0;
        for (uint32_t j = 0; j < l->count; j++) {
            const uint32_t s = l->first + j;
            const int v = bitv(l->visible, j);
            int want;
            if (l->d == 0) {   /* stands for both ends: visible if either is */
                const int w0 = ref_class(ea.x, ea.y, ea.z, ge, f, g), w1 = ref_class(eb.x, eb.y, eb.z, ge, f, g);
                want = w0 == 0 || w1 == 0 ? 0 : w0 == 1 && w1 == 1 ? 1 : -1;
            } else {
                const double t = l->from_b ? (double)(l->d - s) / l->d : (double)s / l->d;
                want = ref_class(ea.x + t * (eb.x - ea.x), ea.y + t * (eb.y - ea.y), ea.z + t * (eb.z - ea.z), ge, f, g);
            }
            if (want < 0) { amb++; continue; }
            sure_h += want == 1, sure_v += want == 0;
            if (want == v) {   /* hidden (1) against drawn (1), or visible (0) against not drawn (0) */
                if (!dis++)
                    snprintf(dfirst, sizeof dfirst, "line %zu (half-edge %u) step %u of %u: drawn %d, the reference says %s",
                             i, l->half, s, l->d, v, want ? "hidden" : "visible");
            }
        }
        /* both sides of each change, CHANGE_PX away (beyond the reference's tolerance), where no other
         * change is that near: the module's visibility there is the one the change list gives */
        if (l->exact || len <= 0) continue;
        for (uint32_t m = 0; m < l->changes; m++) {
            const double tc = (double)l->change[m].num / (double)l->change[m].den, dt = CHANGE_PX / len;
            for (int side = -1; side <= 1; side += 2) {
                const double t = tc + side * dt;
                if (t <= 0 || t >= 1) continue;
                const int nb = (int)m + side;
                if (nb >= 0 && nb < (int)l->changes &&
                    fabs((double)l->change[nb].num / (double)l->change[nb].den - tc) <= 2 * dt) { cnear++; continue; }
                const int v = vis_at(l, (int64_t)llround(t * 1099511627776.0), (int64_t)1099511627776);
                const int want = ref_class(ea.x + t * (eb.x - ea.x), ea.y + t * (eb.y - ea.y), ea.z + t * (eb.z - ea.z), ge, f, g);
                if (want < 0) { camb++; continue; }
                csure++;
                if (want == v && !cdis++ && !dis)
                    snprintf(dfirst, sizeof dfirst, "line %zu (half-edge %u) %s change %u at t = %.6f: %s, the reference says %s", i,
                             l->half, side < 0 ? "before" : "after", m, tc, v ? "visible" : "hidden", want ? "hidden" : "visible");
            }
        }
    }
    ref_free();
    if (dis || cdis) PROBLEM("the reference disagrees at %lu steps and %lu change sides; first: %s", dis, cdis, dfirst);

    /* the z-buffer method */
    gtarget z;
    gt_init(&z);
    RENDER(&lod, &view, PM.closed ? MC_MESH_CULL_BACK | MC_MESH_DRAW_PAPER : MC_MESH_DRAW_PAPER, &z.t, NULL, NULL);
    mc_mesh_lines(&lod, &view, MC_LINES_ALL, &z.t, lines_mem, NULL, &ls);
    unsigned long zonly = 0, qonly = 0, zlines = 0, qlines = 0;
    for (size_t i = 0; i < px; i++) {
        const unsigned zc = z.t.color[i], qc = q.t.depth[i] == MC_DEPTH_EMPTY ? 0 : q.t.color[i];
        const int zl = z.t.depth[i] != MC_DEPTH_EMPTY && zc > MC_MESH_PAPER && zc < MC_MESH_PALETTE_SIZE, ql = qc != 0;
        zlines += zl, qlines += ql, zonly += zl && !ql, qonly += ql && !zl;
    }
    gt_free(&z);

    if (problems)
        printf("not ok: %lu problems; first: %s\n", problems, first);
    else
        printf("ok: level %u, %u faces (%u flagged: hide nothing), %u lines clipped, %u lines (%u silhouettes, %u creases, %u borders), %u contours, "
               "grid 2^%u px (least work %u B: 2^%u); %u of %u pixels visible, %u changes, %u crossings, %u lines face by face; "
               "reference: %lu steps agree (%lu hidden, %lu visible), %lu within tolerance; %lu change sides agree, %lu within "
               "tolerance, %lu with another change near; "
               "line pixels: QI %lu, z-buffer %lu; the z-buffer draws %lu the QI does not, the QI %lu the z-buffer does not\n",
               lod.level, F, st.skipped_faces, st.clipped, st.lines, st.silhouettes, st.creases, st.borders, st.contours, st.grid_shift,
               st.work_needed, least_shift, st.visible, st.pixels, st.changes, st.crossings, st.exact_lines, sure_h + sure_v,
               sure_h, sure_v, amb, csure, camb, cnear, qlines, zlines, zonly, qonly);
    free(ec), free(ed);
    gt_free(&q);
    recs_free(&rs);
    return problems ? 1 : 0;
}

/* ---- the two boxes: a known answer ---------------------------------------------------------------------- */

static int boxes(void)
{
    mc_xform x;
    mc_xform_init(&x, &view, W, H);
    /* the front box: the 8 vertices of largest z */
    const uint32_t V = PM.vertices;
    if (V != 16) { printf("not ok: %u vertices, want two boxes' 16\n", V); return 1; }
    int32_t zs[16], order[16];
    for (uint32_t v = 0; v < V; v++) {
        int32_t p[3];
        mc_pmesh_position(&PM, v, p);
        zs[v] = p[2], order[v] = (int32_t)v;
    }
    for (int i = 0; i < 16; i++)
        for (int j = i + 1; j < 16; j++)
            if (zs[order[j]] > zs[order[i]]) { int32_t t = order[i]; order[i] = order[j]; order[j] = t; }
    uint8_t front[16] = {0};
    int32_t x0 = INT32_MAX, x1 = INT32_MIN, y0 = INT32_MAX, y1 = INT32_MIN;
    for (int i = 0; i < 8; i++) {
        front[order[i]] = 1;
        int32_t p[3];
        mc_xvertex xv;
        mc_pmesh_position(&PM, (uint32_t)order[i], p);
        mc_xform_vertex(&x, p, &xv);
        if (xv.x < x0) x0 = xv.x;
        if (xv.x > x1) x1 = xv.x;
        if (xv.y < y0) y0 = xv.y;
        if (xv.y > y1) y1 = xv.y;
    }
    recs rs = {0};
    mc_qi_stats st;
    gtarget q;
    gt_init(&q);
    int rc = run_qi(&q, MC_LINES_ALL, 1, 64u << 20, &rs, &st);
    unsigned long back_steps = 0, back_hidden = 0, front_steps = 0, bad = 0;
    for (size_t i = 0; i < rs.n; i++) {
        const mc_qi_line *l = &rs.r[i].info;
        uint32_t c[3];
        mc_pmesh_lod_face(&lod, MC_HALF_FACE(l->half), c);
        const int isfront = front[c[0]];
        const int64_t ax = l->a.x, ay = l->a.y, dx = (int64_t)l->b.x - ax, dy = (int64_t)l->b.y - ay;
        for (uint32_t j = 0; j < l->count; j++) {
            const uint32_t s = l->first + j;
            const int v = bitv(l->visible, j);
            int hidden = 0;
            if (!isfront) {
                /* t = n / D; the point (A D + n d) / D strictly inside [x0, x1] x [y0, y1] */
                const int64_t D = l->d ? l->d : 1, nn = l->d ? (l->from_b ? (int64_t)(l->d - s) : (int64_t)s) : 0;
                const int64_t X = ax * D + nn * dx, Y = ay * D + nn * dy;
                hidden = X > x0 * D && X < x1 * D && Y > y0 * D && Y < y1 * D;
                if (l->d == 0) {   /* both ends */
                    const int hb = l->b.x > x0 && l->b.x < x1 && l->b.y > y0 && l->b.y < y1;
                    hidden = hidden && hb;
                }
                back_steps++, back_hidden += hidden;
            } else {
                front_steps++;
            }
            bad += v == hidden;
        }
    }
    int ok = rc == MC_OK && !bad && back_hidden > 0 && back_hidden < back_steps && front_steps > 0;
    printf("%s: front box's rectangle (%d..%d) x (%d..%d) sixteenths; back box: %lu steps, %lu hidden inside it; front "
           "box: %lu steps, all drawn; %lu steps against the rectangle, %u changes, %u lines face by face\n",
           ok ? "ok" : "not ok", x0, x1, y0, y1, back_steps, back_hidden, front_steps, bad, st.changes, st.exact_lines);
    gt_free(&q);
    recs_free(&rs);
    return ok ? 0 : 1;
}

/* ---- images: the QI drawing and the z-buffer drawing as PPM, lines on white ------------------------------ */

static int write_ppm(const char *path, const mc_target *t)
{
    FILE *f = fopen(path, "wb");
    if (!f) return 1;
    fprintf(f, "P6\n%u %u\n255\n", (unsigned)t->width, (unsigned)t->height);
    for (uint32_t i = 0; i < (uint32_t)t->width * t->height; i++) {
        const unsigned c = t->color[i];
        const int line = t->depth[i] != MC_DEPTH_EMPTY && c > MC_MESH_PAPER && c < MC_MESH_PALETTE_SIZE;
        const uint8_t white[3] = {255, 255, 255};
        fwrite(line ? PM.palette + 3 * c : white, 1, 3, f);
    }
    return fclose(f) != 0;
}

static int image(const char *prefix)
{
    char path[1024];
    gtarget q, z;
    mc_qi_stats st;
    gt_init(&q), gt_init(&z);
    if (run_qi(&q, MC_LINES_ALL, 1, 64u << 20, NULL, &st) != MC_OK) return 1;
    RENDER(&lod, &view, PM.closed ? MC_MESH_CULL_BACK | MC_MESH_DRAW_PAPER : MC_MESH_DRAW_PAPER, &z.t, NULL, NULL);
    mc_mesh_lines(&lod, &view, MC_LINES_ALL, &z.t, lines_mem, NULL, NULL);
    snprintf(path, sizeof path, "%s.qi.ppm", prefix);
    int rc = write_ppm(path, &q.t);
    snprintf(path, sizeof path, "%s.zbuf.ppm", prefix);
    rc |= write_ppm(path, &z.t);
    printf("%u of %u line pixels visible\n", st.visible, st.pixels);
    return rc;
}

/* ---- timing ---------------------------------------------------------------------------------------------- */

static double now_ms(clockid_t id)
{
    struct timespec ts;
    clock_gettime(id, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec / 1e6;
}

static int cmpd(const void *a, const void *b) { double x = *(const double *)a, y = *(const double *)b; return x < y ? -1 : x > y; }
static double median(double *v, int n) { qsort(v, (size_t)n, sizeof *v, cmpd); return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2; }

static uint8_t *bwork;
static uint32_t bwork_bytes;

/* mode 0: z-buffer; 1: QI with caches; 2: z-buffer without the render's cache; 3: QI without the cache */
static void frame(int mode, const mc_target *t, mc_qi_stats *st)
{
    mc_clear(t);
    if (mode == 0 || mode == 2) {
        RENDER(&lod, &view, PM.closed ? MC_MESH_CULL_BACK | MC_MESH_DRAW_PAPER : MC_MESH_DRAW_PAPER, t, mode == 0 ? vcache : NULL, NULL);
        mc_mesh_lines(&lod, &view, MC_LINES_ALL, t, lines_mem, NULL, NULL);
    } else {
        mc_qi_buffers b = {facing, mode == 1 ? vcache : NULL, bwork, bwork_bytes};
        if (mc_mesh_qi(&lod, &view, MC_LINES_ALL, t, &b, NULL, st) != MC_OK) exit(3);
    }
}

static int bench(int frames, int untimed_mode)
{
    bwork_bytes = 64u << 20;
    bwork = malloc(bwork_bytes);
    uint8_t *color = malloc((size_t)W * H);
    uint16_t *depth = malloc(2 * (size_t)W * H);
    if (!bwork || !color || !depth) return 2;
    const mc_target t = {color, depth, (uint16_t)W, (uint16_t)H};
    view = mc_view_default();
    if (untimed_mode >= 0) {
        for (int i = 0; i < frames; i++) {
            view.yaw = (int32_t)((int64_t)MC_ANGLE_FULL * i / frames);
            frame(untimed_mode, &t, NULL);
        }
        printf("frames %d\n", frames);
        return 0;
    }
    static const char *names[4] = {"z-buffer (mc_mesh_render paper + mc_mesh_lines), render cache",
                                   "QI (mc_mesh_qi), vertex cache", "z-buffer, no render cache", "QI, no vertex cache"};
    double *ms = malloc(sizeof(double) * frames), *cpu = malloc(sizeof(double) * frames);
    for (int mode = 0; mode < 4; mode++) {
        double lines = 0, exact = 0, vis = 0, pix = 0, tests = 0, rays = 0;
        view.yaw = 0;
        frame(mode, &t, NULL);   /* warm up */
        for (int i = 0; i < frames; i++) {
            view.yaw = (int32_t)((int64_t)MC_ANGLE_FULL * i / frames);
            mc_qi_stats st = {0};
            const double t0 = now_ms(CLOCK_MONOTONIC), c0 = now_ms(CLOCK_PROCESS_CPUTIME_ID);
            frame(mode, &t, &st);
            ms[i] = now_ms(CLOCK_MONOTONIC) - t0, cpu[i] = now_ms(CLOCK_PROCESS_CPUTIME_ID) - c0;
            lines += st.lines, exact += st.exact_lines, vis += st.visible, pix += st.pixels, tests += st.pair_tests, rays += st.ray_tests;
        }
        printf("%s: ms per frame (median) %.3f, cpu ms %.3f", names[mode], median(ms, frames), median(cpu, frames));
        if (mode & 1)
            printf("; per frame: %.0f lines, %.1f face by face, %.0f of %.0f pixels visible, %.0f pair tests, %.0f ray tests",
                   lines / frames, exact / frames, vis / frames, pix / frames, tests / frames, rays / frames);
        printf("\n");
    }
    printf("level %u: %u faces, %u x %u, %d views\n", lod.level, lod.faces, W, H, frames);
    return 0;
}

static void parse_view(char **a)
{
    W = (uint32_t)atoi(a[0]), H = (uint32_t)atoi(a[1]);
    view = mc_view_default();
    view.projection = atoi(a[2]) ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    view.yaw = atoi(a[3]), view.pitch = atoi(a[4]), view.roll = atoi(a[5]), view.zoom = atoi(a[6]), view.eye = atoi(a[7]);
}

int main(int argc, char **argv)
{
    void *anc = malloc((size_t)PM.vertices * PM.index_bytes + 8);
    facing = malloc(MC_MESH_FACING_BYTES(PM.faces) + 8);
    lines_mem = calloc(MC_MESH_LINES_BYTES(PM.faces), 1);
    vcache = malloc(MC_QI_CACHE_BYTES(PM.vertices) + 16);
    if (!anc || !facing || !vcache) return 2;
    mc_pmesh_lod_init(&lod, &PM, anc);
    if (argc == 11 && !strcmp(argv[1], "check")) {
        mc_pmesh_lod_set(&lod, (uint32_t)strtoul(argv[2], 0, 10));
        parse_view(argv + 3);
        return check();
    }
    if (argc == 12 && !strcmp(argv[1], "image")) {
        mc_pmesh_lod_set(&lod, (uint32_t)strtoul(argv[2], 0, 10));
        parse_view(argv + 3);
        return image(argv[11]);
    }
    if (argc == 4 && !strcmp(argv[1], "boxes")) {
        mc_pmesh_lod_set(&lod, PM.vertices);
        W = (uint32_t)atoi(argv[2]), H = (uint32_t)atoi(argv[3]);
        view = mc_view_default();
        return boxes();
    }
    if (argc == 6 && !strcmp(argv[1], "bench")) {
        mc_pmesh_lod_set(&lod, (uint32_t)strtoul(argv[2], 0, 10));
        W = (uint32_t)atoi(argv[3]), H = (uint32_t)atoi(argv[4]);
        return bench(atoi(argv[5]), -1);
    }
    if (argc == 7 && !strcmp(argv[1], "frames")) {
        mc_pmesh_lod_set(&lod, (uint32_t)strtoul(argv[3], 0, 10));
        W = (uint32_t)atoi(argv[4]), H = (uint32_t)atoi(argv[5]);
        static const char *modes[4] = {"zbuf", "qi", "zbuf-nocache", "qi-nocache"};
        for (int m = 0; m < 4; m++)
            if (!strcmp(argv[2], modes[m])) return bench(atoi(argv[6]), m);
        return 2;
    }
    fprintf(stderr, "usage: qi_check check|image N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE [OUT] | boxes W H | bench N W H FRAMES | "
                    "frames zbuf|qi|zbuf-nocache|qi-nocache N W H FRAMES\n");
    return 2;
}
