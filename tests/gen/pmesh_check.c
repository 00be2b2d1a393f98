/* Checks a baked progressive mesh through the runtime's level of detail (runtime/src/pmesh.c).
 * Built by tests/gen/pmesh.sh with -DPM=mc_pmesh_NAME -include build/.../NAME.h and the bake's files.
 * Long because its modes check one bake through the same level of detail and edge table, which
 * separate checkers would each rebuild.
 *
 *   pmesh_check levels        every level of a mesh up to 4000 vertices, else the first and last 200
 *                             and 400 spread between, visited in a shuffled order: every face present
 *                             has three distinct corners, each a vertex present at that level, and
 *                             the face count is F(n); the arrays' own invariants (subtree sizes, the
 *                             splits' parents present before them); at every eighth of those levels
 *                             and the coarsest and finest, every face's neighbour across each edge
 *                             (mc_pmesh_lod_opposite) is the face holding the same two corners the other way
 *                             round, found by search in the level's faces, or none where no face
 *                             does; the edge order names every full-mesh edge once, borders first;
 *                             mc_mesh_lines' crease bits kept through steps and jumps equal a fresh
 *                             memory's, and those from the stored face bits equal those worked out
 *                             with none (the full level, near it, halfway, the base);
 *                             one line "ok ..." or "not ok ..."
 *   pmesh_check faces N       the faces of level N, one line each: the corners' quantized positions
 *                             (x y z three times), in the format of modelc --dump-pmesh-level
 *   pmesh_check render N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE CULL   (zoom, eye Q16; xform.h)
 *                             level N drawn by mc_mesh_render (runtime/src/mesh_render.c) into a
 *                             W x H target inside guard zones (the same bytes with a vertex cache,
 *                             and with the bake's stored face bits dropped), against the same faces composed in
 *                             doubles: each face's corners as mc_mesh_face gives them (projected by
 *                             mc_xform_vertex, tested on its own, tests/unit/test_xform.c), covered
 *                             and depth-tested by the double
 *                             reference of the rasterizer (runtime/ref/raster_ref.c), shaded by
 *                             |n.z| / |n| in doubles. A face with a corner mc_mesh_face flags is
 *                             clipped as mesh_render.h promises, in doubles from the exact view
 *                             space (runtime/ref/xform_ref.c mc_ref_clip_triangle: the near plane,
 *                             and the band's lines, which lie far off the target), culled by its
 *                             plane (mc_ref_front), its polygon covering the centres inside it, at
 *                             the depth of its plane there; the runtime's cut vertices lie within
 *                             1/16 pixel of the exact ones (xform.h), so centres within 1/8 pixel of
 *                             such a polygon's outline are not judged, and its depth is allowed 2
 *                             units plus 1/16 pixel of its slopes more. The covered pixels must be
 *                             the same set; the colour the same wherever the two nearest faces are
 *                             more than 2 depth units (plus those allowances) apart and the shade is
 *                             not within 1/100 of a rounding point; the depth within 1 unit (plus
 *                             the allowance) of the nearest face's; the guard zones untouched; no
 *                             face skipped, and the clipped and clipped-away counts the reference's
 *                             (faces with a corner within 2^-26 cube side of the near plane or a
 *                             facing within rounding may go either way)
 *   pmesh_check lines N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE
 *                             mc_mesh_lines' edge kinds against a classification in doubles (a face
 *                             with a flagged corner faced by its plane, mc_ref_front), its lines the
 *                             union of its edges' mc_line between their ends (mc_mesh_edge_ends:
 *                             clipped where one is flagged), hidden ones a subset; guard zones
 *                             untouched; over the sparse depth buffer (mc_mesh_lines_sparse) the
 *                             same counts and the same pixels showing a line as the z-buffer way,
 *                             and with face groups (--mesh-groups) the same bytes as without them;
 *                             mc_mesh_project's returned flags those of the level's vertices, each
 *                             projected on its own
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "modelc/finish.h"   /* MC_DEPTH_FILLED */
#include "modelc/mesh_lines.h"
#include "modelc/mesh_render.h"
#include "modelc/pmesh.h"
#include "../../runtime/ref/raster_ref.h"
#include "../../runtime/ref/xform_ref.h"
#include "../../runtime/src/mesh_creases.h"   /* the line drawings' memory: where its tag and crease bits lie */

extern const mc_pmesh PM;

static uint32_t field(const mc_chunk *list, unsigned size, uint32_t i, unsigned at, unsigned bytes)
{
    return mc_le_index(mc_chunk_record(list, PM.record_shift, size, i) + at, bytes);
}

/* the reference's shade of a face: |n.z| / |n| * (MC_MESH_SHADES - 1) in doubles, rounded; *edge set
 * when it lies within 1/100 of the rounding point, where mesh_render.h lets either neighbour be drawn */
static unsigned ref_shade(const int32_t p[3][3], int *edge)
{
    double a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = (double)p[1][i] - p[0][i], b[i] = (double)p[2][i] - p[0][i];
    double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    double len = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    *edge = 0;
    if (!(len > 0)) return MC_MESH_SHADES / 2;
    double c = fabs(n[2]) / len * (MC_MESH_SHADES - 1);
    *edge = fabs(c - floor(c) - 0.5) < 0.01;   /* mesh_render.h: the runtime's 15-bit normal */
    return (unsigned)floor(c + 0.5);
}

/* A candidate of depth z, allowance t (how far the runtime's depth may be from z beyond its own
 * unit) and shade s at pixel i: the nearest so far goes to d1, any other's least depth to d2. */
static void nearest(size_t i, double z, double t, unsigned s, int amb, double *d1, double *d2, double *t1,
                    uint8_t *best_shade, uint8_t *best_amb)
{
    if (z < d1[i]) {
        const double lo = d1[i] - t1[i];
        if (lo < d2[i]) d2[i] = lo;
        d1[i] = z, t1[i] = t, best_shade[i] = (uint8_t)s, best_amb[i] = (uint8_t)amb;
    } else if (z - t < d2[i]) {
        d2[i] = z - t;
    }
}

/* Whether a corner of p lies within 2^-26 cube side of the near plane, where the runtime's view
 * space (rounded to 2^-31) and the reference's may put it on either side. */
static int near_border(const mc_view *v, uint32_t w, uint32_t h, const int32_t p[3][3])
{
    for (int k = 0; k < 3; k++) {
        const mc_ref_vertex e = mc_ref_project(v, w, h, p[k]);
        if (v->projection == MC_PERSPECTIVE && fabs(e.d - 1.0 / 64) < 0x1p-26) return 1;
    }
    return 0;
}

/* The clipped polygon poly (m vertices, pixels, convex, in its turning order) as the reference
 * composes it: centres farther than 1/8 pixel inside it covered at its plane's depth, allowed 2
 * units plus 1/16 pixel of its slopes (sure), those nearer its outline than 1/8 pixel set in unsure
 * (every centre not surely outside, when the face is not sure: a facing or near-plane tie). */
static void polygon(uint32_t w, uint32_t h, const mc_ref_vertex *poly, int m, int sure, unsigned s, int amb, double *d1,
                    double *d2, double *t1, uint8_t *best_shade, uint8_t *best_amb, uint8_t *unsure)
{
    const double tol = 1.0 / 8;
    double area = 0, best = 0, x0 = HUGE_VAL, x1 = -HUGE_VAL, y0 = HUGE_VAL, y1 = -HUGE_VAL;
    int at = 0;
    for (int i = 0; i < m; i++) {
        const mc_ref_vertex *a = &poly[i], *b = &poly[(i + 1) % m];
        area += a->x * b->y - b->x * a->y;
        x0 = fmin(x0, a->x), x1 = fmax(x1, a->x), y0 = fmin(y0, a->y), y1 = fmax(y1, a->y);
    }
    for (int i = 1; i + 1 < m; i++) {
        const double a = (poly[i].x - poly[0].x) * (poly[i + 1].y - poly[0].y) - (poly[i + 1].x - poly[0].x) * (poly[i].y - poly[0].y);
        if (fabs(a) > fabs(best)) best = a, at = i;
    }
    /* the plane's depth z0 + gx (x - x0) + gy (y - y0), from the largest triangle of the fan */
    double gx = 0, gy = 0;
    if (best != 0) {
        const mc_ref_vertex *a = &poly[0], *b = &poly[at], *c = &poly[at + 1];
        const double z1 = b->z - a->z, z2 = c->z - a->z, xa = b->x - a->x, ya = b->y - a->y, xb = c->x - a->x, yb = c->y - a->y;
        gx = (z1 * yb - z2 * ya) / best, gy = (xa * z2 - xb * z1) / best;
    }
    const double allow = 2 + (fabs(gx) + fabs(gy)) / 16, sg = area > 0 ? 1 : -1;
    const int i0 = (int)fmax(0, floor(x0 - tol - 0.5)), i1 = (int)fmin(w - 1.0, ceil(x1 + tol));
    const int j0 = (int)fmax(0, floor(y0 - tol - 0.5)), j1 = (int)fmin(h - 1.0, ceil(y1 + tol));
    for (int j = j0; j <= j1; j++)
        for (int i = i0; i <= i1; i++) {
            const double cx = i + 0.5, cy = j + 0.5;
            double dmin = HUGE_VAL;
            for (int k = 0; k < m; k++) {
                const mc_ref_vertex *a = &poly[k], *b = &poly[(k + 1) % m];
                const double ex = b->x - a->x, ey = b->y - a->y, len = hypot(ex, ey);
                if (!(len > 0)) continue;
                /* positive inside: the polygon turns with the sign of its area */
                dmin = fmin(dmin, sg * (ex * (cy - a->y) - ey * (cx - a->x)) / len);
            }
            const size_t px = (size_t)j * w + (size_t)i;
            if (dmin < -tol) continue;
            if (!sure || best == 0 || dmin <= tol) { unsure[px] = 1; continue; }
            nearest(px, poly[0].z + gx * (cx - poly[0].x) + gy * (cy - poly[0].y), allow, s, amb, d1, d2, t1, best_shade,
                    best_amb);
        }
}

static int render_check(mc_pmesh_lod *lod, char **a)
{
    const uint32_t n = (uint32_t)strtoul(a[0], 0, 10), w = (uint32_t)atoi(a[1]), h = (uint32_t)atoi(a[2]);
    mc_view v = mc_view_default();
    v.projection = atoi(a[3]) ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    v.yaw = atoi(a[4]), v.pitch = atoi(a[5]), v.roll = atoi(a[6]), v.zoom = atoi(a[7]), v.eye = atoi(a[8]);
    const unsigned cull = (unsigned)atoi(a[9]);
    mc_pmesh_lod_set(lod, n);
    const size_t px = (size_t)w * h, G = 4096;
    uint8_t *cmem = malloc(px + 2 * G), *cov = malloc(px), *best_shade = malloc(px), *best_amb = malloc(px);
    uint16_t *dmem = malloc(2 * (px + 2 * G));
    double *d1 = malloc(sizeof(double) * px), *d2 = malloc(sizeof(double) * px), *fd = malloc(sizeof(double) * px);
    double *t1 = malloc(sizeof(double) * px);
    uint8_t *unsure = calloc(px, 1);
    if (!cmem || !cov || !best_shade || !best_amb || !dmem || !d1 || !d2 || !fd || !t1 || !unsure) return 2;
    memset(cmem, 0xA5, px + 2 * G);
    for (size_t i = 0; i < px + 2 * G; i++) dmem[i] = 0x5A5A;
    mc_target t = {cmem + G, dmem + G, (uint16_t)w, (uint16_t)h};
    mc_clear(&t);
    mc_mesh_stats st;
    int rc = mc_mesh_render(lod, &v, cull ? MC_MESH_CULL_BACK : 0u, &t, NULL, &st);
    {   /* with a vertex cache (filled with junk first): the same bytes, stats and return (mesh_render.h) */
        mc_xvertex *vc = malloc(MC_MESH_CACHE_BYTES(PM.vertices));
        uint8_t *cc = malloc(px);
        uint16_t *dc = malloc(2 * px);
        if (!vc || !cc || !dc) return 2;
        memset(vc, 0xA5, MC_MESH_CACHE_BYTES(PM.vertices));
        mc_target tc = {cc, dc, (uint16_t)w, (uint16_t)h};
        mc_mesh_stats sc;
        mc_clear(&tc);
        const int rcc = mc_mesh_render(lod, &v, cull ? MC_MESH_CULL_BACK : 0u, &tc, vc, &sc);
        if (rcc != rc || memcmp(&sc, &st, sizeof st) || memcmp(cc, t.color, px) || memcmp(dc, t.depth, 2 * px)) {
            printf("not ok: level %u: with a vertex cache mc_mesh_render returns %d (%d without), draws %u faces "
                   "(%u), %u pixels (%u), skips %u (%u), %s colours, %s depths\n", n, rcc, rc, sc.drawn, st.drawn,
                   sc.pixels, st.pixels, sc.skipped, st.skipped, memcmp(cc, t.color, px) ? "other" : "the same",
                   memcmp(dc, t.depth, 2 * px) ? "other" : "the same");
            return 1;
        }
        free(vc), free(cc), free(dc);
    }
    {   /* the bake stores every face's shade (pmesh.h face_bits); without them (a streamed mesh's
         * null) every shade is worked out: the same bytes and stats */
        if (!PM.face_bits) {
            printf("not ok: the bake stores no face bits\n");
            return 1;
        }
        mc_pmesh bare = PM;
        bare.face_bits = 0;
        void *anc = malloc((size_t)PM.vertices * PM.index_bytes + 8);
        uint8_t *cc = malloc(px);
        uint16_t *dc = malloc(2 * px);
        if (!anc || !cc || !dc) return 2;
        mc_pmesh_lod bl;
        mc_pmesh_lod_init(&bl, &bare, anc);
        mc_pmesh_lod_set(&bl, n);
        mc_target tc = {cc, dc, (uint16_t)w, (uint16_t)h};
        mc_mesh_stats sc;
        mc_clear(&tc);
        const int rcc = mc_mesh_render(&bl, &v, cull ? MC_MESH_CULL_BACK : 0u, &tc, NULL, &sc);
        size_t differ = 0;
        for (size_t i = 0; i < px; i++) differ += cc[i] != t.color[i];
        if (rcc != rc || memcmp(&sc, &st, sizeof st) || differ || memcmp(dc, t.depth, 2 * px)) {
            printf("not ok: level %u: with its shades worked out mc_mesh_render returns %d (%d with the stored), "
                   "draws %u faces (%u), %zu pixels of another colour, %s depths\n", n, rcc, rc, sc.drawn, st.drawn,
                   differ, memcmp(dc, t.depth, 2 * px) ? "other" : "the same");
            return 1;
        }
        free(anc), free(cc), free(dc);
    }
    /* the reference: per pixel the nearest face's depth d1 and its allowance t1 (0 for a face drawn
     * from the runtime's corners), and d2 the least depth another face may have there */
    for (size_t i = 0; i < px; i++) d1[i] = d2[i] = HUGE_VAL, t1[i] = 0, best_shade[i] = 0, best_amb[i] = 0;
    mc_xform x;
    mc_xform_init(&x, &v, w, h);
    uint32_t flagged = 0, kept = 0, away = 0, either = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        int32_t p[3][3];
        mc_raster_vertex rv[3];
        int amb;
        if (mc_mesh_face(lod, &x, f, p, rv)) {
            flagged++;
            const int border = near_border(&v, w, h, p), front = mc_ref_front(&v, w, h, p);
            if (cull && front < 0 && !border) continue;   /* culled: in neither count */
            mc_ref_vertex poly[MC_REF_CLIP_MAX];
            const int m = mc_ref_clip_triangle(&v, w, h, (const int32_t(*)[3])p, poly);
            const int sure = !border && !(cull && front == 0);
            if (!sure) either++;
            else if (m == 0) away++;
            else kept++;
            if (m) polygon(w, h, poly, m, sure, ref_shade(p, &amb), amb, d1, d2, t1, best_shade, best_amb, unsure);
            continue;
        }
        memset(cov, 0, px);
        if (!mc_raster_ref_triangle(w, h, rv, cull ? MC_RASTER_CULL_BACK : 0u, cov, fd)) continue;
        unsigned s = ref_shade(p, &amb);
        for (size_t i = 0; i < px; i++)
            if (cov[i]) nearest(i, fd[i], 0, s, amb, d1, d2, t1, best_shade, best_amb);
    }
    unsigned long coverage = 0, colour = 0, depth = 0, ties = 0, guard = 0, covered = 0;
    for (size_t i = 0; i < G; i++)
        guard += cmem[i] != 0xA5 || cmem[G + px + i] != 0xA5 || dmem[i] != 0x5A5A || dmem[G + px + i] != 0x5A5A;
    unsigned long beside = 0;
    for (size_t i = 0; i < px; i++) {
        const int ref_cov = d1[i] < HUGE_VAL, got = t.depth[i] != MC_DEPTH_EMPTY;
        if (unsure[i] && (got || !ref_cov)) { beside++; continue; }   /* beside a clipped polygon's outline */
        if (ref_cov != got) { coverage++; continue; }
        if (!got) continue;
        covered++;
        if (d2[i] - d1[i] <= 2 + t1[i] || best_amb[i]) { ties++; continue; }
        colour += t.color[i] != best_shade[i];
        depth += fabs(t.depth[i] - floor(d1[i] + 0.5)) > 1 + t1[i];
    }
    const int counts = st.skipped == 0 && st.clipped >= kept && st.clipped <= kept + either && st.clipped_away >= away &&
                       st.clipped_away <= away + either && st.clipped + st.clipped_away <= kept + away + either;
    int ok = rc == MC_OK && !coverage && !colour && !depth && !guard && counts && covered > 0;
    printf("%s: level %u, %u faces (%u with a flagged corner: %u clipped, %u clipped away, %u skipped; the reference "
           "%u, %u, %u either way), %lu pixels covered; %lu coverage, %lu colour, %lu depth differences, %lu guard-zone "
           "bytes touched, %lu pixels on depth or shade ties, %lu beside a clipped outline\n",
           ok ? "ok" : "not ok", n, lod->faces, flagged, st.clipped, st.clipped_away, st.skipped, kept, away, either,
           covered, coverage, colour, depth, guard, ties, beside);
    free(cmem), free(cov), free(best_shade), free(best_amb), free(dmem), free(d1), free(d2), free(fd), free(t1), free(unsure);
    return ok ? 0 : 1;
}


/* The level's directed edges (corner pairs) in an open-addressed table, half-edges as values. */
typedef struct { uint64_t key; uint32_t half; } slot;

static slot *table_put_level(const mc_pmesh_lod *lod, uint32_t *cap_out)
{
    uint32_t cap = 16;
    while (cap < 6u * lod->faces + 16) cap <<= 1;
    slot *t = malloc(sizeof(slot) * cap);
    if (!t) return NULL;
    for (uint32_t i = 0; i < cap; i++) t[i].key = UINT64_MAX;
    for (uint32_t f = 0; f < lod->faces; f++) {
        uint32_t c[3];
        mc_pmesh_lod_face(lod, f, c);
        for (uint32_t k = 0; k < 3; k++) {
            uint64_t key = (uint64_t)c[k] << 32 | c[(k + 1) % 3];
            uint32_t i = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 40) & (cap - 1);
            while (t[i].key != UINT64_MAX && t[i].key != key) i = (i + 1) & (cap - 1);
            if (t[i].key == key) t[i].half = MC_NO_HALF_EDGE - 1;   /* used twice: not a manifold level */
            else t[i].key = key, t[i].half = MC_HALF_EDGE(f, k);
        }
    }
    *cap_out = cap;
    return t;
}

static uint32_t table_get(const slot *t, uint32_t cap, uint64_t key)
{
    uint32_t i = (uint32_t)((key * 0x9E3779B97F4A7C15ull) >> 40) & (cap - 1);
    while (t[i].key != UINT64_MAX) {
        if (t[i].key == key) return t[i].half;
        i = (i + 1) & (cap - 1);
    }
    return MC_NO_HALF_EDGE;
}

/* Neighbours at the current level against a search of its faces: the number of problems. */
static unsigned long adjacency_check(const mc_pmesh_lod *lod, char *first, size_t n_first, unsigned long before)
{
    uint32_t cap;
    slot *t = table_put_level(lod, &cap);
    if (!t) return 1;
    unsigned long bad = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        uint32_t c[3];
        mc_pmesh_lod_face(lod, f, c);
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t want = table_get(t, cap, (uint64_t)c[(k + 1) % 3] << 32 | c[k]);
            uint32_t got = mc_pmesh_lod_opposite(lod, MC_HALF_EDGE(f, k));
            if (want == MC_NO_HALF_EDGE - 1 || table_get(t, cap, (uint64_t)c[k] << 32 | c[(k + 1) % 3]) == MC_NO_HALF_EDGE - 1) {
                if (!before && !bad) snprintf(first, n_first, "level %u: directed edge %u-%u used twice", lod->level, c[k], c[(k + 1) % 3]);
                bad++;
            } else if (got != want) {
                if (!before && !bad)
                    snprintf(first, n_first, "level %u face %u edge %u: neighbour %d, the level's faces say %d", lod->level, f, k,
                             (int)got, (int)want);
                bad++;
            }
        }
    }
    free(t);
    return bad;
}

/* The edge order: E entries, each full-mesh edge once (an entry or its opposite), borders first. */
static unsigned long edge_order_check(char *first, size_t n_first)
{
    const uint32_t F = PM.faces;
    uint8_t *seen = calloc((size_t)F * 4, 1);
    uint32_t edges = 0;
    if (!seen) return 1;
    for (uint32_t f = 0; f < F; f++)
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t o = field(PM.opposite, 3u * PM.half_bytes, f, k * PM.half_bytes, PM.half_bytes);
            if (PM.half_bytes == 2 && o == 0xFFFF) o = MC_NO_HALF_EDGE;
            edges += o == MC_NO_HALF_EDGE || o > MC_HALF_EDGE(f, k);
        }
    unsigned long bad = 0;
    int interior = 0;
    if (edges != PM.edges) { snprintf(first, n_first, "the full mesh has %u edges, the descriptor says %u", edges, PM.edges); bad++; }
    for (uint32_t i = 0; i < PM.edges && !bad; i++) {
        uint32_t h = mc_pmesh_edge(&PM, i);
        if (MC_HALF_FACE(h) >= F || MC_HALF_EDGE_INDEX(h) > 2) { snprintf(first, n_first, "edge %u: half-edge %u out of range", i, h); bad++; break; }
        uint32_t o = field(PM.opposite, 3u * PM.half_bytes, MC_HALF_FACE(h), MC_HALF_EDGE_INDEX(h) * PM.half_bytes, PM.half_bytes);
        if (PM.half_bytes == 2 && o == 0xFFFF) o = MC_NO_HALF_EDGE;
        if (o == MC_NO_HALF_EDGE && interior) { snprintf(first, n_first, "edge %u: a border after interior edges", i); bad++; }
        interior |= o != MC_NO_HALF_EDGE;
        if (seen[h] || (o != MC_NO_HALF_EDGE && seen[o])) { snprintf(first, n_first, "edge %u: listed twice", i); bad++; }
        seen[h] = 1;
        if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < MC_HALF_FACE(h)) { snprintf(first, n_first, "edge %u: not the first face's half-edge", i); bad++; }
    }
    free(seen);
    return bad;
}


/* ---- lines: the level's edges classified in doubles, against mc_mesh_lines ---------------------- */

typedef struct ref_face {
    double area;      /* twice the exact signed screen area, pixels^2 (a flagged face: -1 front, 1 not) */
    double tol;       /* how far the runtime's rounded corners (within 1/16 pixel) can move it */
    double n[3];      /* normal in the model frame */
} ref_face;

/* the reference's kind of an edge: a set of MC_EDGE_* kinds the runtime may give (more than one
 * where a facing or the crease angle is within rounding of its threshold) */
static unsigned ref_kinds(const ref_face *a, const ref_face *b, double crease_cos)
{
    if (!b) return 1u << MC_EDGE_BORDER;
    unsigned fa = a->area < -a->tol ? 2u : a->area > a->tol ? 1u : 3u;   /* 1 back, 2 front */
    unsigned fb = b->area < -b->tol ? 2u : b->area > b->tol ? 1u : 3u;
    unsigned kinds = 0;
    if ((fa | fb) == 3u) kinds |= 1u << MC_EDGE_SILHOUETTE;                /* they can differ */
    if ((fa & fb) != 0) {                                                  /* they can agree */
        double la = sqrt(a->n[0] * a->n[0] + a->n[1] * a->n[1] + a->n[2] * a->n[2]);
        double lb = sqrt(b->n[0] * b->n[0] + b->n[1] * b->n[1] + b->n[2] * b->n[2]);
        if (!(la > 0 && lb > 0)) kinds |= 1u << MC_EDGE_PLAIN;
        else {
            double c = (a->n[0] * b->n[0] + a->n[1] * b->n[1] + a->n[2] * b->n[2]) / (la * lb);
            /* the runtime's 15-bit normals: the cosine within 2^-12 (mesh_lines.h) */
            if (c < crease_cos + 1.0 / 4096) kinds |= 1u << MC_EDGE_CREASE;
            if (c > crease_cos - 1.0 / 4096) kinds |= 1u << MC_EDGE_PLAIN;
        }
    }
    return kinds;
}

static int lines_check(mc_pmesh_lod *lod, char **a)
{
    const uint32_t n = (uint32_t)strtoul(a[0], 0, 10), w = (uint32_t)atoi(a[1]), h = (uint32_t)atoi(a[2]);
    mc_view v = mc_view_default();
    v.projection = atoi(a[3]) ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
    v.yaw = atoi(a[4]), v.pitch = atoi(a[5]), v.roll = atoi(a[6]), v.zoom = atoi(a[7]), v.eye = atoi(a[8]);
    mc_pmesh_lod_set(lod, n);
    const uint32_t F = lod->faces;
    ref_face *rf = malloc(sizeof(ref_face) * (F + 1));
    uint8_t *facing = malloc(MC_MESH_FACING_BYTES(PM.faces) + 1);
    uint8_t *lmem = calloc(MC_MESH_LINES_BYTES(PM.faces), 1);
    uint32_t cap;
    slot *table = table_put_level(lod, &cap);
    if (!rf || !facing || !lmem || !table) return 2;
    for (uint32_t f = 0; f < F; f++) {
        int32_t p[3][3];
        mc_ref_vertex e[3];
        uint32_t c[3];
        mc_pmesh_lod_face(lod, f, c);
        int flagged = 0;
        for (int k = 0; k < 3; k++) {
            mc_pmesh_position(&PM, c[k], p[k]);
            e[k] = mc_ref_project(&v, w, h, p[k]);
            flagged |= e[k].near || e[k].out;
        }
        double ax = e[1].x - e[0].x, ay = e[1].y - e[0].y, bx = e[2].x - e[0].x, by = e[2].y - e[0].y;
        double cx = e[2].x - e[1].x, cy = e[2].y - e[1].y, u = 1.0 / 16;
        rf[f].area = ax * by - bx * ay;
        rf[f].tol = 2 * u * (fabs(ax) + fabs(ay) + fabs(bx) + fabs(by) + fabs(cx) + fabs(cy)) + 8 * u * u;
        if (flagged) {   /* faced by its plane (mesh_lines.h), either way within rounding */
            const int front = mc_ref_front(&v, w, h, (const int32_t(*)[3])p);
            rf[f].area = -front, rf[f].tol = front ? 0 : HUGE_VAL;
        }
        double d1[3], d2[3];
        for (int i = 0; i < 3; i++) d1[i] = (double)p[1][i] - p[0][i], d2[i] = (double)p[2][i] - p[0][i];
        rf[f].n[0] = d1[1] * d2[2] - d1[2] * d2[1];
        rf[f].n[1] = d1[2] * d2[0] - d1[0] * d2[2];
        rf[f].n[2] = d1[0] * d2[1] - d1[1] * d2[0];
    }
    /* the runtime's classification, edge by edge, against the reference's */
    mc_xform x;
    mc_xform_init(&x, &v, w, h);
    mc_mesh_facing(lod, &x, facing);
    const double crease_cos = PM.crease_cos / 16384.0;
    uint32_t count[8] = {0}, edges = 0, ties = 0, bad = 0;
    char first[240] = "";
    for (uint32_t f = 0; f < F; f++)
        for (uint32_t k = 0; k < 3; k++) {
            uint32_t c[3];
            mc_pmesh_lod_face(lod, f, c);
            const uint32_t want_o = table_get(table, cap, (uint64_t)c[(k + 1) % 3] << 32 | c[k]);
            const uint32_t o = mc_pmesh_lod_opposite(lod, MC_HALF_EDGE(f, k));
            if (o != want_o) {
                if (!bad++) snprintf(first, sizeof first, "face %u edge %u: neighbour %d, want %d", f, k, (int)o, (int)want_o);
                continue;
            }
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;
            edges++;
            const unsigned kind = mc_mesh_edge_kind(lod, facing, MC_HALF_EDGE(f, k), o);
            const unsigned kinds = ref_kinds(&rf[f], o == MC_NO_HALF_EDGE ? NULL : &rf[MC_HALF_FACE(o)], crease_cos);
            count[kind]++;
            ties += (kinds & (kinds - 1)) != 0;
            if (!(kinds & (1u << kind)) && !bad++)
                snprintf(first, sizeof first, "face %u edge %u: kind %u, the reference allows mask %u (areas %g, %g)", f, k,
                         kind, kinds, rf[f].area, o == MC_NO_HALF_EDGE ? 0.0 : rf[MC_HALF_FACE(o)].area);
        }
    /* mc_mesh_lines: its counts; unhidden, its line pixels are the union of its edges' lines (mc_line,
     * tested on its own) in their colours; hidden, a subset of them; guard zones untouched */
    const size_t px = (size_t)w * h, G = 4096;
    uint8_t *cmem = malloc(px + 2 * G), *cmem2 = malloc(px + 2 * G);
    uint16_t *dmem = malloc(2 * (px + 2 * G)), *dmem2 = malloc(2 * (px + 2 * G));
    if (!cmem || !cmem2 || !dmem || !dmem2) return 2;
    memset(cmem, 0xA5, px + 2 * G), memset(cmem2, 0xA5, px + 2 * G);
    for (size_t i = 0; i < px + 2 * G; i++) dmem[i] = dmem2[i] = 0x5A5A;
    mc_target t = {cmem + G, dmem + G, (uint16_t)w, (uint16_t)h}, t2 = {cmem2 + G, dmem2 + G, (uint16_t)w, (uint16_t)h};
    mc_lines_stats st, st2;
    mc_clear(&t);
    mc_clear(&t2);
    mc_mesh_lines(lod, &v, MC_LINES_ALL | MC_LINES_NO_HIDING, &t, lmem, NULL, &st);
    mc_mesh_render(lod, &v, MC_MESH_DRAW_PAPER, &t2, NULL, NULL);
    mc_mesh_lines(lod, &v, MC_LINES_ALL, &t2, lmem, NULL, &st2);
    if (!bad && (st.edges != edges || st.silhouettes != count[MC_EDGE_SILHOUETTE] || st.creases != count[MC_EDGE_CREASE] ||
                 st.borders != count[MC_EDGE_BORDER] || st2.pixels != st.pixels))
        bad++, snprintf(first, sizeof first, "mc_mesh_lines counts %u edges %u %u %u, the scan %u edges %u %u %u", st.edges,
                        st.silhouettes, st.creases, st.borders, edges, count[1], count[2], count[4]);
    /* the union, drawn edge by edge with mc_line from the runtime's own kinds and projections */
    uint8_t *want = calloc(px, 1);
    if (!want) return 2;
    uint32_t line_px = 0, hidden = 0, shown = 0, mism = 0;
    for (uint32_t f = 0; f < F; f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t o = mc_pmesh_lod_opposite(lod, MC_HALF_EDGE(f, k));
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;
            const unsigned kind = mc_mesh_edge_kind(lod, facing, MC_HALF_EDGE(f, k), o);
            if (kind == MC_EDGE_PLAIN) continue;
            mc_raster_vertex rv[2];   /* the corners projected, or the edge clipped where one is flagged */
            if (mc_mesh_edge_ends(lod, &x, MC_HALF_EDGE(f, k), rv) == 2) continue;
            mc_line_vertex la = {rv[0].x >> 4, rv[0].y >> 4, 0}, lb = {rv[1].x >> 4, rv[1].y >> 4, 0};
            uint8_t one[1] = {0};
            (void)one;
            /* mark the line's pixels with the kind's bit */
            static uint8_t mc[4096 * 4096];
            static uint16_t md[4096 * 4096];
            mc_target m = {mc, md, (uint16_t)w, (uint16_t)h};
            mc_clear(&m);
            mc_line_style ns = {0, MC_LINE_NO_DEPTH_TEST | MC_LINE_WRITE_DEPTH};
            mc_line(&m, la, lb, 1, &ns);
            for (size_t i = 0; i < px; i++)
                if (md[i] != MC_DEPTH_EMPTY) want[i] |= (uint8_t)kind;
        }
    for (size_t i = 0; i < px; i++) {
        const unsigned c = t.depth[i] == MC_DEPTH_EMPTY ? 0u : t.color[i];
        const unsigned k = c == MC_LINES_SILHOUETTE_COLOR ? MC_EDGE_SILHOUETTE : c == MC_LINES_CREASE_COLOR ? MC_EDGE_CREASE
                         : c == MC_LINES_BORDER_COLOR    ? MC_EDGE_BORDER : 0u;
        line_px += want[i] != 0;
        if ((want[i] == 0) != (k == 0) || (k && !(want[i] & k))) mism++;
        const unsigned c2 = t2.depth[i] == MC_DEPTH_EMPTY ? 0u : t2.color[i];
        const int l2 = c2 == MC_LINES_SILHOUETTE_COLOR || c2 == MC_LINES_CREASE_COLOR || c2 == MC_LINES_BORDER_COLOR;
        if (l2) shown++;
        else if (want[i]) hidden++;
        if (l2 && !(want[i] & (c2 == MC_LINES_SILHOUETTE_COLOR ? MC_EDGE_SILHOUETTE : c2 == MC_LINES_CREASE_COLOR ? MC_EDGE_CREASE : MC_EDGE_BORDER)))
            mism++;
    }
    size_t guard = 0;
    for (size_t i = 0; i < G; i++)
        guard += (cmem[i] != 0xA5) + (cmem[G + px + i] != 0xA5) + (dmem[i] != 0x5A5A) + (dmem[G + px + i] != 0x5A5A) +
                 (cmem2[i] != 0xA5) + (cmem2[G + px + i] != 0xA5) + (dmem2[i] != 0x5A5A) + (dmem2[G + px + i] != 0x5A5A);
    /* the crease bits kept in the memory follow a level change: after drawing another level, the
     * same memory draws this level again as fresh memory does */
    if (!bad && lod->level > PM.base_vertices) {
        mc_pmesh_lod_set(lod, PM.base_vertices + (lod->level - PM.base_vertices) / 2);
        mc_clear(&t2);
        mc_mesh_lines(lod, &v, MC_LINES_ALL | MC_LINES_NO_HIDING, &t2, lmem, NULL, NULL);
        mc_pmesh_lod_set(lod, n);
        mc_clear(&t2);
        mc_mesh_lines(lod, &v, MC_LINES_ALL | MC_LINES_NO_HIDING, &t2, lmem, NULL, NULL);
        if (memcmp(t2.color, t.color, px) || memcmp(t2.depth, t.depth, 2 * px))
            bad++, snprintf(first, sizeof first, "after a level change the kept crease bits draw a different frame");
    }
    if (!bad && (mism || guard))
        bad++, snprintf(first, sizeof first, "%u line pixels not as their edges' lines, %zu guard-zone entries touched", mism, guard);
    /* hidden lines over the sparse depth buffer (mc_mesh_lines_sparse, with the vertex cache) against
     * the z-buffer way the front end takes without one: the faces drawn in paper with the same culling
     * (closed parts), then mc_mesh_lines. A pixel shows a line in one exactly where it does in the
     * other (either keeps a pixel whose nearest line pixel, or any, is not hidden by the faces); the
     * colour may differ only where lines of two kinds pass (each keeps another of them) */
    uint32_t sparse_shown = 0, kind_ties = 0;
    {
        uint8_t *c3 = malloc(px), *c4 = malloc(px);
        uint16_t *d3 = malloc(2 * px), *d4 = malloc(2 * px);
        uint32_t *bits = malloc(4u * MC_SDEPTH_WORDS(w, h));
        mc_xvertex *cache = malloc(MC_MESH_CACHE_BYTES(PM.vertices));
        if (!c3 || !c4 || !d3 || !d4 || !bits || !cache) return 2;
        mc_target t4 = {c4, d4, (uint16_t)w, (uint16_t)h};
        mc_clear(&t4);
        mc_mesh_render(lod, &v, MC_MESH_DRAW_PAPER | (PM.closed ? MC_MESH_CULL_BACK : 0u), &t4, NULL, NULL);
        mc_lines_stats s4, s3;
        mc_mesh_lines(lod, &v, MC_LINES_ALL, &t4, lmem, NULL, &s4);
        mc_sdepth sd;
        int rc = mc_sdepth_init(&sd, (uint16_t)w, (uint16_t)h, bits, d3, c3, MC_DEPTH_FILLED, MC_MESH_PAPER);
        if (rc == MC_OK) rc = mc_mesh_lines_sparse(lod, &v, MC_LINES_ALL, &sd, lmem, cache, &s3);
        uint32_t mask_diff = 0, color_diff = 0;
        for (size_t i = 0; i < px; i++) {
            const int l4 = d4[i] != MC_DEPTH_EMPTY && (c4[i] == MC_LINES_SILHOUETTE_COLOR || c4[i] == MC_LINES_CREASE_COLOR ||
                                                       c4[i] == MC_LINES_BORDER_COLOR);
            const int l3 = c3[i] == MC_LINES_SILHOUETTE_COLOR || c3[i] == MC_LINES_CREASE_COLOR || c3[i] == MC_LINES_BORDER_COLOR;
            const int in_use = mc_sdepth_in_use(&sd, (uint32_t)(i % w), (uint32_t)(i / w));
            if (l3 != l4 || l3 != in_use || (!l3 && (c3[i] != MC_MESH_PAPER || d3[i] != MC_DEPTH_FILLED))) mask_diff++;
            if (l3 && l4 && c3[i] != c4[i]) {
                if (want[i] & (want[i] - 1u)) kind_ties++;
                else color_diff++;
            }
            sparse_shown += l3;
        }
        if (!bad && (rc != MC_OK || s3.edges != s4.edges || s3.silhouettes != s4.silhouettes || s3.creases != s4.creases ||
                     s3.borders != s4.borders || s3.pixels != s4.pixels || s3.skipped != s4.skipped ||
                     s3.clipped != s4.clipped || s3.clipped_away != s4.clipped_away))
            bad++, snprintf(first, sizeof first, "mc_mesh_lines_sparse: rc %d, counts %u edges %u %u %u %u px, z-buffer %u %u %u %u %u",
                            rc, s3.edges, s3.silhouettes, s3.creases, s3.borders, s3.pixels, s4.edges, s4.silhouettes,
                            s4.creases, s4.borders, s4.pixels);
        if (!bad && (mask_diff || color_diff))
            bad++, snprintf(first, sizeof first, "mc_mesh_lines_sparse against the z-buffer: %u pixels differ in showing a line "
                            "(or hold other than paper), %u in colour where one kind passes", mask_diff, color_diff);
        /* the same drawing, byte for byte, with the level's neighbours from a table (pmesh.h) */
        uint8_t *nbr = malloc(MC_PMESH_NEIGHBOUR_BYTES(PM.faces, PM.half_bytes) + 1);
        if (!nbr) return 2;
        mc_pmesh_lod_neighbours(lod, nbr);
        mc_lines_stats s5;
        rc = mc_sdepth_init(&sd, (uint16_t)w, (uint16_t)h, bits, d4, c4, MC_DEPTH_FILLED, MC_MESH_PAPER);
        if (rc == MC_OK) rc = mc_mesh_lines_sparse(lod, &v, MC_LINES_ALL, &sd, lmem, cache, &s5);
        if (!bad && (rc != MC_OK || memcmp(c3, c4, px) || memcmp(d3, d4, 2 * px) || s5.edges != s3.edges ||
                     s5.silhouettes != s3.silhouettes || s5.creases != s3.creases || s5.borders != s3.borders ||
                     s5.pixels != s3.pixels))
            bad++, snprintf(first, sizeof first, "mc_mesh_lines_sparse with a neighbour table: not the same drawing");
        /* with face groups (pmesh.h), the same drawing, byte for byte, as with them left out */
        if (PM.group_size) {
            mc_pmesh plain = PM;
            plain.groups = plain.group_faces = 0, plain.group_size = 0, plain.group_bytes = 0;
            mc_pmesh_lod l2 = *lod;
            l2.pm = &plain;
            rc = mc_sdepth_init(&sd, (uint16_t)w, (uint16_t)h, bits, d4, c4, MC_DEPTH_FILLED, MC_MESH_PAPER);
            if (rc == MC_OK) rc = mc_mesh_lines_sparse(&l2, &v, MC_LINES_ALL, &sd, lmem, cache, &s5);
            if (!bad && (rc != MC_OK || memcmp(c3, c4, px) || memcmp(d3, d4, 2 * px) || s5.pixels != s3.pixels))
                bad++, snprintf(first, sizeof first, "mc_mesh_lines_sparse without the face groups: not the same drawing");
        }
        /* mc_mesh_project's answer (the sparse way reads no corner's flag at the full level when it
         * is 0) against the flags of the level's vertices, each projected on its own */
        {
            mc_xform x;
            mc_xform_init(&x, &v, (uint32_t)w, (uint32_t)h);
            uint32_t want_flags = 0;
            for (uint32_t u = 0; u < PM.vertices; u++) {
                /* (a vertex of the level is its own ancestor) */
                if ((PM.index_bytes == 2 ? ((const uint16_t *)lod->anc)[u] : ((const uint32_t *)lod->anc)[u]) != u) continue;
                int32_t p[3];
                mc_xvertex e;
                mc_pmesh_position(&PM, u, p);
                mc_xform_vertex(&x, p, &e);
                want_flags |= e.flags;
            }
            const uint32_t got_flags = mc_mesh_project(lod, &x, cache);
            if (!bad && got_flags != want_flags)
                bad++, snprintf(first, sizeof first, "mc_mesh_project returned flags %u, the level's vertices have %u",
                                got_flags, want_flags);
        }
        mc_pmesh_lod_neighbours(lod, NULL);
        free(nbr);
        free(c3), free(c4), free(d3), free(d4), free(bits), free(cache);
    }
    if (bad)
        printf("not ok: %u problems; first: %s\n", bad, first);
    else
        printf("ok: level %u, %u edges: %u silhouettes, %u creases, %u borders (%u on a rounding tie); %u line pixels, "
               "%u hidden by the faces, %u shown; sparse depth buffer: the same %u shown (%u where two kinds pass take "
               "the other's colour), and with a neighbour table\n", n, edges, count[MC_EDGE_SILHOUETTE], count[MC_EDGE_CREASE],
               count[MC_EDGE_BORDER], ties, line_px, hidden, shown, sparse_shown, kind_ties);
    free(lmem), free(rf), free(facing), free(table), free(cmem), free(cmem2), free(dmem), free(dmem2), free(want);
    return bad ? 1 : 0;
}

int main(int argc, char **argv)
{
    const mc_pmesh *pm = &PM;
    const uint32_t V = pm->vertices, V0 = pm->base_vertices, ib = pm->index_bytes;
    void *anc = malloc((size_t)V * ib + 8);
    uint32_t *rank = malloc(sizeof(uint32_t) * V), *fcount = malloc(sizeof(uint32_t) * (V + 1));
    if (!anc || !rank || !fcount) return 2;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, pm, anc);
    if (argc == 3 && !strcmp(argv[1], "faces")) {
        mc_pmesh_lod_set(&lod, (uint32_t)strtoul(argv[2], 0, 10));
        for (uint32_t f = 0; f < lod.faces; f++) {
            uint32_t c[3];
            mc_pmesh_lod_face(&lod, f, c);
            for (int k = 0; k < 3; k++) {
                const uint8_t *p = mc_chunk_record(pm->positions, pm->record_shift, 6, c[k]);
                printf("%u %u %u ", (unsigned)mc_le16(p), (unsigned)mc_le16(p + 2), (unsigned)mc_le16(p + 4));
            }
            printf("\n");
        }
        return 0;
    }
    if (argc == 12 && !strcmp(argv[1], "render")) return render_check(&lod, argv + 2);
    if (argc == 11 && !strcmp(argv[1], "lines")) return lines_check(&lod, argv + 2);
    if (argc != 2 || strcmp(argv[1], "levels")) {
        fprintf(stderr, "usage: pmesh_check levels | faces N | render N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE CULL | "
                        "lines N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE\n");
        return 2;
    }
    /* ranks and F(n) from the arrays; the tree's invariants */
    unsigned long problems = 0;
    char first[200] = "";
#define PROBLEM(...) do { if (!problems++) snprintf(first, sizeof first, __VA_ARGS__); } while (0)
    for (uint32_t v = 0; v < V; v++) rank[v] = UINT32_MAX;
    fcount[V0] = pm->base_faces;
    for (uint32_t s = 0; s < V - V0; s++) {
        uint32_t v = field(pm->splits, ib, s, 0, ib);
        uint32_t nf = mc_pmesh_split_faces(pm, s);
        if (v >= V || rank[v] != UINT32_MAX) { PROBLEM("split %u brings back vertex %u twice or out of range", s, v); break; }
        rank[v] = V0 + s;
        if (nf < 1 || nf > 2) PROBLEM("split %u adds %u faces", s, nf);
        fcount[V0 + s + 1] = fcount[V0 + s] + nf;
    }
    if (fcount[V] != pm->faces) PROBLEM("the splits add up to %u faces, the descriptor says %u", fcount[V], pm->faces);
    /* the forest from the subtree sizes alone (depth-first order: v's parent is the nearest vertex
     * before it whose subtree holds it; none for a root) */
    uint32_t roots = 0, *parent = malloc(sizeof(uint32_t) * V), *open = malloc(sizeof(uint32_t) * V), top = 0;
    if (!parent || !open) return 2;
    for (uint32_t v = 0; v < V && !problems; v++) {
        const uint32_t size = field(pm->tree, ib, v, 0, ib);
        if (size < 1 || v + size > V) PROBLEM("vertex %u: subtree size %u", v, size);
        while (top && v >= open[top - 1] + field(pm->tree, ib, open[top - 1], 0, ib)) top--;
        parent[v] = top ? open[top - 1] : v;
        if (top && v + size > parent[v] + field(pm->tree, ib, parent[v], 0, ib))
            PROBLEM("vertex %u's subtree runs past its parent %u's", v, parent[v]);
        open[top++] = v;
        if (parent[v] == v) {
            roots++;
            if (rank[v] != UINT32_MAX) PROBLEM("root %u is also split", v);
            rank[v] = 0;
        } else if (rank[v] == UINT32_MAX || rank[parent[v]] >= rank[v])
            PROBLEM("vertex %u splits before its parent %u", v, parent[v]);
    }
    if (roots != V0) PROBLEM("%u roots, the descriptor says %u base vertices", roots, V0);
    /* what a collapse reads the parent from: a split's first face's corners 0 and 1 stand for its
     * vertex and the parent at the split's level (each corner's nearest ancestor present there) */
    for (uint32_t s = 0, f = pm->base_faces; s < V - V0 && !problems; f += fcount[V0 + s + 1] - fcount[V0 + s], s++) {
        const uint32_t v = field(pm->splits, ib, s, 0, ib);
        uint32_t c[2];
        for (int k = 0; k < 2; k++)
            for (c[k] = field(pm->corners, 3 * ib, f, (unsigned)k * ib, ib); rank[c[k]] > V0 + s;) c[k] = parent[c[k]];
        if (!((c[0] == v && c[1] == parent[v]) || (c[1] == v && c[0] == parent[v])))
            PROBLEM("split %u: its first face's edge 0 is %u %u at its level, not vertex %u and its parent %u", s, c[0],
                    c[1], v, parent[v]);
    }
    free(open);
    free(parent);
    /* the levels, shuffled */
    uint32_t *levels = malloc(sizeof(uint32_t) * (V - V0 + 1)), nl = 0;
    if (!levels) return 2;
    for (uint32_t n = V0; n <= V; n++)
        if (V <= 4000 || n < V0 + 200 || n + 200 > V || (n - V0) % ((V - V0) / 400 + 1) == 0) levels[nl++] = n;
    uint64_t x = 88172645463325252ull;
    for (uint32_t i = nl; i > 1; i--) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        uint32_t j = (uint32_t)(x % i), t = levels[i - 1];
        levels[i - 1] = levels[j], levels[j] = t;
    }
    uint64_t faces_checked = 0;
    uint32_t adjacency_levels = 0, table_levels = 0;
    /* a second state keeping a neighbour table from the base level on, through the same levels; at
     * the adjacency levels its neighbours against the search too, and its bytes (map and table)
     * against a third state set straight to the level and given its table there */
    const size_t nbr_bytes = MC_PMESH_NEIGHBOUR_BYTES(pm->faces, pm->half_bytes);
    void *anc_t = malloc((size_t)V * ib + 8), *anc_f = malloc((size_t)V * ib + 8);
    uint8_t *nbr_t = malloc(nbr_bytes + 1), *nbr_f = malloc(nbr_bytes + 1);
    if (!anc_t || !anc_f || !nbr_t || !nbr_f) return 2;
    mc_pmesh_lod tl, fl;
    mc_pmesh_lod_init(&tl, pm, anc_t);
    mc_pmesh_lod_neighbours(&tl, nbr_t);
    for (uint32_t i = 0; i < nl && !problems; i++) {
        uint32_t n = levels[i];
        if (mc_pmesh_lod_set(&lod, n) != n || lod.level != n) PROBLEM("level %u not set", n);
        if (mc_pmesh_lod_set(&tl, n) != n || tl.faces != lod.faces) PROBLEM("level %u not set with the table", n);
        if (lod.faces != fcount[n]) PROBLEM("level %u: %u faces, want %u", n, lod.faces, fcount[n]);
        for (uint32_t f = 0; f < lod.faces; f++) {
            uint32_t c[3];
            mc_pmesh_lod_face(&lod, f, c);
            for (int k = 0; k < 3; k++)
                if (c[k] >= V || rank[c[k]] >= n) PROBLEM("level %u face %u: corner %u is not present", n, f, c[k]);
            if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2])
                PROBLEM("level %u face %u: corners %u %u %u repeat", n, f, c[0], c[1], c[2]);
        }
        faces_checked += lod.faces;
        if (i % 8 == 0 || n == V0 || n == V) {
            unsigned long bad = adjacency_check(&lod, first, sizeof first, problems);
            problems += bad;
            adjacency_levels += !bad;
            if (!bad) {
                bad = adjacency_check(&tl, first, sizeof first, problems);
                if (bad) snprintf(first + strlen(first), sizeof first - strlen(first), " (the neighbour table)");
                problems += bad;
                mc_pmesh_lod_init(&fl, pm, anc_f);
                mc_pmesh_lod_set(&fl, n);
                mc_pmesh_lod_neighbours(&fl, nbr_f);
                if (memcmp(anc_t, anc_f, (size_t)V * ib) || memcmp(nbr_t, nbr_f, nbr_bytes))
                    PROBLEM("level %u: the state kept through %u levels differs from one set straight there", n, i + 1);
                table_levels += !bad;
            }
        }
    }
    /* mc_mesh_lines' memory kept through steps small and large (crease bits brought over from the last
     * level, or all tested) and jumps, by a state without and one with a neighbour table, against a memory that saw
     * only the level: the same level tag and crease bits (the facing bits past the level's faces are
     * whatever an earlier level left) */
    const size_t lbytes = MC_MESH_LINES_BYTES(pm->faces);
    uint8_t *lm_k = calloc(lbytes, 1), *lm_t = calloc(lbytes, 1), *lm_f = malloc(lbytes);
    if (!lm_k || !lm_t || !lm_f) return 2;
    uint8_t col[64];
    uint16_t dep[64];
    mc_target tiny = {col, dep, 8, 8};
    const mc_view view = mc_view_default();
    uint32_t cn = V0 + (V - V0) / 2, crease_levels = 0;
    for (uint32_t i = 0; i < 240 && !problems; i++) {
        x ^= x << 13, x ^= x >> 7, x ^= x << 17;
        /* a jump, steps of up to an eighth of the splits (brought over under a 16th of the faces), small steps */
        const uint32_t span = i % 40 == 39 ? V - V0 + 1 : i % 5 == 4 ? (V - V0) / 8u + 1u : i % 3 ? 9u : 129u;
        const int64_t next = i % 40 == 39 ? (int64_t)V0 + (int64_t)(x % span) : (int64_t)cn + (int64_t)(x % span) - (int64_t)(span / 2);
        cn = next < (int64_t)V0 ? V0 : next > (int64_t)V ? V : (uint32_t)next;
        mc_pmesh_lod_set(&lod, cn), mc_pmesh_lod_set(&tl, cn);
        mc_mesh_lines(&lod, &view, MC_LINES_ALL, &tiny, lm_k, NULL, NULL);
        mc_mesh_lines(&tl, &view, MC_LINES_ALL, &tiny, lm_t, NULL, NULL);
        if (i % 8 == 7) {
            memset(lm_f, 0, lbytes);
            mc_mesh_lines(&lod, &view, MC_LINES_ALL, &tiny, lm_f, NULL, NULL);
            const size_t cb = (size_t)(mc_lines_creases(lm_f, pm->faces) - lm_f), tb = sizeof *mc_lines_tag(lm_f);
            if (memcmp(lm_k, lm_f, tb) || memcmp(lm_k + cb, lm_f + cb, lbytes - cb)) PROBLEM("level %u: mc_mesh_lines' crease bits kept through %u levels differ from a fresh memory's", cn, i + 1);
            else if (memcmp(lm_t, lm_f, tb) || memcmp(lm_t + cb, lm_f + cb, lbytes - cb)) PROBLEM("level %u: mc_mesh_lines' crease bits kept with a neighbour table differ from a fresh memory's", cn);
            else crease_levels++;
        }
    }
    /* the stored face bits (pmesh.h: the full mesh's crease bits, which a level's edge between two
     * faces as in the full mesh keeps) against every crease worked out (a streamed mesh's null): the
     * same memory at the full level, near it, halfway and at the base */
    {
        mc_pmesh bare = *pm;
        bare.face_bits = 0;
        mc_pmesh_lod bl;
        void *anc_b = malloc((size_t)V * ib + 8);
        if (!anc_b) return 2;
        mc_pmesh_lod_init(&bl, &bare, anc_b);
        const uint32_t at[5] = {V, V - 1u, V - (V - V0) / 100u, V0 + (V - V0) / 2u, V0};
        for (unsigned i = 0; i < 5 && !problems; i++) {
            mc_pmesh_lod_set(&lod, at[i]), mc_pmesh_lod_set(&bl, at[i]);
            memset(lm_f, 0, lbytes), memset(lm_k, 0, lbytes);
            mc_mesh_lines(&lod, &view, MC_LINES_ALL, &tiny, lm_f, NULL, NULL);
            mc_mesh_lines(&bl, &view, MC_LINES_ALL, &tiny, lm_k, NULL, NULL);
            const size_t cb = (size_t)(mc_lines_creases(lm_f, pm->faces) - lm_f), tb = sizeof *mc_lines_tag(lm_f);
            if (!pm->face_bits) PROBLEM("the bake stores no face bits");
            else if (memcmp(lm_k, lm_f, tb) || memcmp(lm_k + cb, lm_f + cb, lbytes - cb))
                PROBLEM("level %u: the crease bits from the stored face bits differ from those worked out", at[i]);
        }
        free(anc_b);
    }
    free(lm_k), free(lm_t), free(lm_f);
    /* dropping the table: the walks again */
    mc_pmesh_lod_neighbours(&tl, 0);
    if (!problems) problems += adjacency_check(&tl, first, sizeof first, problems);
    if (!problems) problems += edge_order_check(first, sizeof first);
    if (problems)
        printf("not ok: %lu problems; first: %s\n", problems, first);
    else
        printf("ok: %u vertices (%u base), %u faces (%u base), %u levels, %llu faces checked, neighbours at %u levels "
               "(a neighbour table's kept through the levels at %u, the same bytes as one set there), %u edges ordered, "
               "crease bits kept through steps and jumps the same as fresh at %u levels, and from the stored face bits the same as "
               "worked out at 5\n",
               V, V0, pm->faces, pm->base_faces, nl, (unsigned long long)faces_checked, adjacency_levels, table_levels,
               pm->edges, crease_levels);
    free(levels), free(anc), free(rank), free(fcount), free(anc_t), free(anc_f), free(nbr_t), free(nbr_f);
    return problems ? 1 : 0;
}
