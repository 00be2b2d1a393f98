/* Clipped faces and lines in whole frames of a baked progressive mesh (mesh_render.h, mesh_lines.h,
 * xform.h's clipping), against the reference of tests/unit/test_clip.c (the same planes and cuts in
 * long doubles, projected as runtime/ref/xform_ref.c projects). Built by tests/gen/clip.sh with
 * -DPM=mc_pmesh_NAME -include NAME.h and the bake's files, also under ASan + UBSan.
 *
 *   clip_check frame N W H YAW PITCH ZOOM EYE   (zoom, eye Q16; perspective)
 *       level N drawn by mc_mesh_render into a W x H target inside guard zones, culled and not, with
 *       and without a vertex cache:
 *         - nothing written outside the target; with a cache the same bytes and stats;
 *         - coverage: every pixel centre inside some drawn face's reference polygon (its corners'
 *           view-space triangle clipped in real numbers, each vertex's error budget as margin plus
 *           1/64 pixel) is covered, and none is covered that no face's polygon comes that near;
 *           where one face alone can cover a centre, it has that face's shade; a face whose facing
 *           is within rounding of edge-on counts as maybe drawn;
 *         - stats: skipped 0; clipped + clipped_away (+ the flagged faces culled by their plane)
 *           = the faces with a flagged corner; clipped_away = those whose clipped polygon is empty;
 *         - facing of the flagged faces (mc_mesh_face_front) as the reference's plane test.
 *       Then mc_mesh_lines, unhidden: its pixels are the union of its edges' mc_line between their
 *       ends, clipped by mc_xform_clip_segment where an end is flagged, in their kinds' colours
 *       (kinds from mc_mesh_facing + mc_mesh_edge_kind); clipped + clipped_away = the drawn kinds'
 *       edges with a flagged end, skipped 0; hidden over the faces: a subset; with a cache the same;
 *       guard zones untouched. One line "ok ..." or "not ok ...".
 *   clip_check random COUNT SEED
 *       COUNT random views across and beyond mc_view_clamp's ranges (both projections, eye from
 *       1/32 to 512, zoom 1/128 to 128, translations, targets 1..200, any level), faces and lines
 *       with every flag, with and without a cache: guard zones untouched, the cache changing
 *       nothing, the counts adding up. Meant for the sanitizers' build.
 */
#define CLIP_REFERENCE_ONLY
#include "../unit/test_clip.c"

#include "modelc/finish.h"   /* MC_DEPTH_FILLED */
#include "modelc/mesh_lines.h"
#include "modelc/sdepth.h"
#include "modelc/pmesh.h"

extern const mc_pmesh PM;

#define G 4096   /* guard bytes either side of a target */

typedef struct gtarget {
    mc_target t;
    uint8_t *cmem;
    uint16_t *dmem;
    size_t px;
} gtarget;

static gtarget gt_new(uint32_t w, uint32_t h)
{
    gtarget g;
    g.px = (size_t)w * h;
    g.cmem = malloc(g.px + 2 * G);
    g.dmem = malloc(2 * (g.px + 2 * G));
    if (!g.cmem || !g.dmem) exit(2);
    memset(g.cmem, 0xA5, g.px + 2 * G);
    for (size_t i = 0; i < g.px + 2 * G; i++) g.dmem[i] = 0x5A5A;
    g.t.color = g.cmem + G, g.t.depth = g.dmem + G, g.t.width = (uint16_t)w, g.t.height = (uint16_t)h;
    mc_clear(&g.t);
    return g;
}

static size_t gt_guard(const gtarget *g)
{
    size_t bad = 0;
    for (size_t i = 0; i < G; i++)
        bad += (g->cmem[i] != 0xA5) + (g->cmem[G + g->px + i] != 0xA5) + (g->dmem[i] != 0x5A5A) + (g->dmem[G + g->px + i] != 0x5A5A);
    return bad;
}

static void gt_free(gtarget *g) { free(g->cmem), free(g->dmem); }

static unsigned long problems;
static char first[400];
#define PROBLEM(...) do { if (!problems++) snprintf(first, sizeof first, __VA_ARGS__); } while (0)

/* The reference's facing of view-space triangle q: 1 front, 0 back, -1 within rounding of edge-on
 * (the runtime decides unflagged faces by their rounded projected area, flagged ones by the exact
 * plane test) */
static int ref_front(const refview *r, const int32_t q[3][3], int flagged)
{
    real a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = ((real)q[1][i] - q[0][i]) / Q30, b[i] = ((real)q[2][i] - q[0][i]) / Q30;
    const real n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const real e[3] = {-q[0][0] / Q30, -q[0][1] / Q30, r->persp ? r->eye - q[0][2] / Q30 : 1};
    const real s = r->persp ? e[0] * n[0] + e[1] * n[1] + e[2] * n[2] : n[2];
    const real size = (fabsl(e[0] * n[0]) + fabsl(e[1] * n[1]) + fabsl(e[2] * n[2])) * 1e-15L + 1e-30L;
    if (!flagged) {
        /* the rounded corners (1/32 pixel each) against the exact projected area */
        rvert v[3];
        for (int k = 0; k < 3; k++) {
            for (int i = 0; i < 3; i++) v[k].q[i] = q[k][i] / Q30;
            ref_project(r, &v[k]);
        }
        const real ax = v[1].x - v[0].x, ay = v[1].y - v[0].y, bx = v[2].x - v[0].x, by = v[2].y - v[0].y;
        const real cx = v[2].x - v[1].x, cy = v[2].y - v[1].y;
        const real area = ax * by - bx * ay;
        const real slack = (fabsl(ax) + fabsl(ay) + fabsl(bx) + fabsl(by) + fabsl(cx) + fabsl(cy)) / 16 + 1.0L / 64;
        if (fabsl(area) <= slack) return -1;
        return area < 0;
    }
    if (fabsl(s) <= size) return -1;
    return s > 0;
}

/* A centre's place against a convex polygon: 1 inside it by more than m, 0 outside by more than m
 * (beyond one edge's line), -1 neither */
static int poly_side(const rvert *p, int n, real px, real py, real m)
{
    real area = 0, mn = 1e30L;
    for (int i = 0; i < n; i++) area += p[i].x * p[(i + 1) % n].y - p[(i + 1) % n].x * p[i].y;
    const real sgn = area < 0 ? -1 : 1;
    for (int i = 0; i < n; i++) {
        const rvert *a = &p[i], *b = &p[(i + 1) % n];
        const real ex = b->x - a->x, ey = b->y - a->y, len = sqrtl(ex * ex + ey * ey);
        if (len == 0) continue;
        const real s = sgn * (ex * (py - a->y) - ey * (px - a->x)) / len;   /* towards the inside */
        if (s < mn) mn = s;
    }
    return mn > m ? 1 : mn < -m ? 0 : -1;
}

static int frame_check(mc_pmesh_lod *lod, char **a)
{
    const uint32_t n = (uint32_t)strtoul(a[0], 0, 10), w = (uint32_t)atoi(a[1]), h = (uint32_t)atoi(a[2]);
    mc_view v = mc_view_default();
    v.projection = MC_PERSPECTIVE;
    v.yaw = atoi(a[3]), v.pitch = atoi(a[4]), v.zoom = atoi(a[5]), v.eye = atoi(a[6]);
    mc_pmesh_lod_set(lod, n);
    const uint32_t F = lod->faces;
    const size_t px = (size_t)w * h;
    mc_xform x;
    mc_xform_init(&x, &v, w, h);
    const refview r = ref_view(&v, w, h);
    uint8_t *sure = malloc(px), *sure_face_shade = malloc(px);
    uint32_t *maybe = malloc(sizeof(uint32_t) * px);
    mc_xvertex *cache = malloc(MC_MESH_CACHE_BYTES(PM.vertices));
    if (!sure || !sure_face_shade || !maybe || !cache) return 2;
    unsigned long flagged_faces = 0, culled_flagged = 0, empty_runtime = 0, empty_ref = 0, facing_bad = 0, edge_on = 0;
    unsigned long covered = 0, sure_px = 0, one_face_px = 0, band_cut_faces = 0;
    for (int cull = 0; cull < 2; cull++) {
        memset(sure, 0, px), memset(maybe, 0, sizeof(uint32_t) * px);
        gtarget t = gt_new(w, h), tc = gt_new(w, h);
        mc_mesh_stats st, sc;
        const unsigned fl = cull ? MC_MESH_CULL_BACK : 0u;
        const int rc = mc_mesh_render(lod, &v, fl, &t.t, NULL, &st);
        memset(cache, 0xA5, MC_MESH_CACHE_BYTES(PM.vertices));
        const int rcc = mc_mesh_render(lod, &v, fl, &tc.t, cache, &sc);
        if (rc != MC_OK || rcc != rc || memcmp(&st, &sc, sizeof st) || memcmp(t.t.color, tc.t.color, px) ||
            memcmp(t.t.depth, tc.t.depth, 2 * px))
            PROBLEM("cull %d: with a vertex cache another frame or other stats (rc %d %d)", cull, rc, rcc);
        if (gt_guard(&t) || gt_guard(&tc)) PROBLEM("cull %d: guard zones written", cull);
        /* the reference, face by face */
        unsigned long nflag = 0, ncull = 0, nempty = 0;
        for (uint32_t f = 0; f < F; f++) {
            int32_t p[3][3], q[3][3];
            mc_raster_vertex rv[3], cv[MC_XFORM_CLIP_MAX];
            const uint32_t flags = mc_mesh_face(lod, &x, f, p, rv);
            for (int k = 0; k < 3; k++) mc_xform_view(&x, p[k], q[k]);
            const int rf = ref_front(&r, (const int32_t(*)[3])q, flags != 0);
            if (flags) {
                nflag++;
                const int front = mc_mesh_face_front(&x, (const int32_t(*)[3])p);
                if (rf >= 0 && front != rf) facing_bad++;
                if (cull && !front) { ncull++; continue; }
                const unsigned m = mc_mesh_clip_face(&x, (const int32_t(*)[3])p, cv);
                nempty += m == 0;
            }
            edge_on += rf < 0;
            if (cull && rf == 0) continue;
            rvert poly[16];
            const int m = ref_clip(&r, (const int32_t(*)[3])q, poly);
            if (flags && !cull) empty_ref += m == 0;
            if (m < 3) continue;
            real err = 0, x0 = 1e30L, x1 = -1e30L, y0 = 1e30L, y1 = -1e30L;
            int band = 0;
            for (int i = 0; i < m; i++) {
                if (poly[i].err > err) err = poly[i].err;
                band |= poly[i].plane > 0;
                if (poly[i].x < x0) x0 = poly[i].x;
                if (poly[i].x > x1) x1 = poly[i].x;
                if (poly[i].y < y0) y0 = poly[i].y;
                if (poly[i].y > y1) y1 = poly[i].y;
            }
            if (!cull) band_cut_faces += band;
            const real margin = (0.5L + err) / 16 + 1.0L / 64;
            const int drawn_surely = !(cull && rf < 0);
            const int shade = (int)mc_mesh_shade(p[0], p[1], p[2]);
            long i0 = (long)floorl(x0 - margin - 1), i1 = (long)ceill(x1 + margin + 1);
            long j0 = (long)floorl(y0 - margin - 1), j1 = (long)ceill(y1 + margin + 1);
            if (i0 < 0) i0 = 0;
            if (j0 < 0) j0 = 0;
            if (i1 > (long)w - 1) i1 = (long)w - 1;
            if (j1 > (long)h - 1) j1 = (long)h - 1;
            for (long j = j0; j <= j1; j++)
                for (long i = i0; i <= i1; i++) {
                    const int side = poly_side(poly, m, i + 0.5L, j + 0.5L, margin);
                    if (side == 0) continue;
                    const size_t k = (size_t)j * w + (size_t)i;
                    maybe[k]++;
                    if (side == 1 && drawn_surely) sure[k] = 1, sure_face_shade[k] = (uint8_t)shade;
                }
        }
        if (!cull && st.clipped + st.clipped_away != nflag)
            PROBLEM("stats: clipped %u + clipped away %u, %lu faces with a flagged corner", st.clipped, st.clipped_away, nflag);
        if (cull && st.clipped + st.clipped_away + ncull != nflag)
            PROBLEM("stats (culled): clipped %u + clipped away %u + %lu culled, %lu flagged", st.clipped, st.clipped_away, ncull, nflag);
        if (st.clipped_away != nempty) PROBLEM("stats: clipped away %u, %lu empty polygons", st.clipped_away, nempty);
        if (st.skipped != 0 || st.faces != F || st.drawn > F) PROBLEM("stats: skipped %u faces %u drawn %u", st.skipped, st.faces, st.drawn);
        if (!cull) flagged_faces = nflag, empty_runtime = nempty;
        else culled_flagged = ncull;
        unsigned long cov_bad = 0, col_bad = 0, here = 0;
        for (size_t k = 0; k < px; k++) {
            const int got = t.t.depth[k] != MC_DEPTH_EMPTY;
            here += got;
            if (sure[k]) sure_px += !cull;
            if ((sure[k] && !got) || (got && maybe[k] == 0)) {
                if (!cov_bad++) PROBLEM("cull %d: pixel (%zu, %zu) %s, the reference %s", cull, k % w, k / w, got ? "covered" : "empty",
                                        sure[k] ? "covers it" : "has no face near it");
                continue;
            }
            if (got && sure[k] && maybe[k] == 1) {
                one_face_px += !cull;
                if (t.t.color[k] != sure_face_shade[k] && !col_bad++)
                    PROBLEM("cull %d: pixel (%zu, %zu) colour %u, its one face's shade %u", cull, k % w, k / w, t.t.color[k], sure_face_shade[k]);
            }
        }
        if (st.pixels < here) PROBLEM("stats: %u pixels drawn, %lu covered", st.pixels, here);
        if (!cull) covered = here;
        gt_free(&t), gt_free(&tc);
    }
    if (facing_bad) PROBLEM("%lu flagged faces faced otherwise than the reference's plane test", facing_bad);

    /* lines: unhidden, the union of the edges' lines; hidden over the faces, a subset */
    uint8_t *mem = calloc(MC_MESH_LINES_BYTES(PM.faces), 1), *facing = malloc(MC_MESH_FACING_BYTES(PM.faces) + 1);
    uint8_t *want = calloc(px, 1);
    if (!mem || !facing || !want) return 2;
    gtarget t = gt_new(w, h), t2 = gt_new(w, h), t3 = gt_new(w, h), one = gt_new(w, h);
    mc_lines_stats ls, ls2, ls3;
    mc_mesh_lines(lod, &v, MC_LINES_ALL | MC_LINES_NO_HIDING, &t.t, mem, NULL, &ls);
    mc_mesh_render(lod, &v, MC_MESH_DRAW_PAPER, &t2.t, cache, NULL);
    mc_mesh_lines(lod, &v, MC_LINES_ALL, &t2.t, mem, NULL, &ls2);
    mc_mesh_lines(lod, &v, MC_LINES_ALL | MC_LINES_NO_HIDING, &t3.t, mem, cache, &ls3);
    if (memcmp(&ls, &ls3, sizeof ls) || memcmp(t.t.color, t3.t.color, px) || memcmp(t.t.depth, t3.t.depth, 2 * px))
        PROBLEM("lines: with the vertex cache another frame or other stats");
    if (memcmp(&ls, &ls2, sizeof ls)) PROBLEM("lines: hidden and unhidden count differently");
    if (gt_guard(&t) || gt_guard(&t2) || gt_guard(&t3)) PROBLEM("lines: guard zones written");
    mc_mesh_facing(lod, &x, facing);
    uint32_t edges = 0, count[8] = {0}, with_flag = 0, sil_at_clip = 0, cut = 0;
    for (uint32_t f = 0; f < F; f++) {
        int32_t p[3][3];
        mc_raster_vertex rv[3];
        mc_mesh_face(lod, &x, f, p, rv);
        if (((facing[f >> 3] >> (f & 7u)) & 1u) != (unsigned)mc_mesh_front(lod, &x, f)) PROBLEM("lines: facing bit %u not mc_mesh_front's", f);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t o = mc_pmesh_lod_opposite(lod, MC_HALF_EDGE(f, k));
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;
            edges++;
            const unsigned kind = mc_mesh_edge_kind(lod, facing, MC_HALF_EDGE(f, k), o);
            count[kind]++;
            if (kind == MC_EDGE_PLAIN) continue;
            mc_xvertex e[2];
            mc_xform_vertex(&x, p[k], &e[0]);
            mc_xform_vertex(&x, p[(k + 1) % 3], &e[1]);
            if (kind == MC_EDGE_SILHOUETTE) {
                int32_t pg[3][3];
                mc_raster_vertex gv[3];
                sil_at_clip += (mc_mesh_face(lod, &x, MC_HALF_FACE(o), pg, gv) != 0) != (mc_mesh_face(lod, &x, f, pg, gv) != 0);
            }
            if (e[0].flags | e[1].flags) {
                with_flag++;
                int32_t qa[3], qb[3];
                mc_xform_view(&x, p[k], qa);
                mc_xform_view(&x, p[(k + 1) % 3], qb);
                if (!mc_xform_clip_segment(&x, qa, qb, e)) continue;
                cut++;
            }
            mc_line_vertex la = {e[0].x >> 4, e[0].y >> 4, 0}, lb = {e[1].x >> 4, e[1].y >> 4, 0};
            mc_line_style ns = {0, MC_LINE_NO_DEPTH_TEST | MC_LINE_WRITE_DEPTH};
            if (!mc_line(&one.t, la, lb, 1, &ns)) continue;
            /* the line's pixels lie in its ends' box: mark them, and clear the box again */
            const long i0 = la.x < lb.x ? la.x : lb.x, i1 = la.x < lb.x ? lb.x : la.x;
            const long j0 = la.y < lb.y ? la.y : lb.y, j1 = la.y < lb.y ? lb.y : la.y;
            for (long j = j0 < 0 ? 0 : j0; j <= j1 && j < (long)h; j++)
                for (long i = i0 < 0 ? 0 : i0; i <= i1 && i < (long)w; i++) {
                    const size_t at = (size_t)j * w + (size_t)i;
                    if (one.t.depth[at] != MC_DEPTH_EMPTY) want[at] |= (uint8_t)kind, one.t.depth[at] = MC_DEPTH_EMPTY;
                }
        }
    }
    if (ls.edges != edges || ls.silhouettes != count[MC_EDGE_SILHOUETTE] || ls.creases != count[MC_EDGE_CREASE] ||
        ls.borders != count[MC_EDGE_BORDER])
        PROBLEM("lines: counts %u edges %u %u %u, the scan %u edges %u %u %u", ls.edges, ls.silhouettes, ls.creases, ls.borders, edges,
                count[1], count[2], count[4]);
    if (ls.skipped != 0 || ls.clipped + ls.clipped_away != with_flag || ls.clipped != cut)
        PROBLEM("lines: skipped %u, clipped %u + clipped away %u, the scan %u with a flagged end (%u left)", ls.skipped, ls.clipped,
                ls.clipped_away, with_flag, cut);
    unsigned long mism = 0, line_px = 0, shown = 0;
    for (size_t i = 0; i < px; i++) {
        const unsigned c = t.t.depth[i] == MC_DEPTH_EMPTY ? 0u : t.t.color[i];
        const unsigned k = c == MC_LINES_SILHOUETTE_COLOR ? MC_EDGE_SILHOUETTE : c == MC_LINES_CREASE_COLOR ? MC_EDGE_CREASE
                         : c == MC_LINES_BORDER_COLOR    ? MC_EDGE_BORDER : 0u;
        line_px += want[i] != 0;
        if ((want[i] == 0) != (k == 0) || (k && !(want[i] & k))) mism++;
        const unsigned c2 = t2.t.color[i];
        const unsigned k2 = c2 == MC_LINES_SILHOUETTE_COLOR ? MC_EDGE_SILHOUETTE : c2 == MC_LINES_CREASE_COLOR ? MC_EDGE_CREASE
                          : c2 == MC_LINES_BORDER_COLOR    ? MC_EDGE_BORDER : 0u;
        shown += k2 != 0;
        if (k2 && !(want[i] & k2)) mism++;
    }
    if (mism) PROBLEM("lines: %lu pixels not as their edges' lines", mism);
    gt_free(&t), gt_free(&t2), gt_free(&t3), gt_free(&one);
    if (problems)
        printf("not ok: %lu problems; first: %s\n", problems, first);
    else
        printf("ok: level %u, %u faces, %lu with a flagged corner (%lu clipped away, the reference %lu; %lu culled by their plane; "
               "%lu cut at the band), %lu pixels covered, %lu surely, %lu by one face alone (shade checked), %lu faces within "
               "rounding of edge-on; lines: %u edges, %u with a flagged end (%u left), %u silhouettes between a flagged and an "
               "unflagged face, %lu line pixels, %lu shown over the faces\n",
               n, F, flagged_faces, empty_runtime, empty_ref, culled_flagged, band_cut_faces, covered, sure_px, one_face_px, edge_on,
               edges, with_flag, cut, sil_at_clip, line_px, shown);
    free(sure), free(sure_face_shade), free(maybe), free(cache), free(mem), free(facing), free(want);
    return problems ? 1 : 0;
}

/* ---- random views (for the sanitizers) ----------------------------------------------------------- */

/* The hidden lines over the sparse depth buffer (mc_mesh_lines_sparse, with the vertex cache) against
 * the z-buffer way (the faces in paper, culled when the part is closed, then mc_mesh_lines): the same
 * counts, and a line shown at the same pixels (the colour may differ where lines of two kinds meet).
 * The buffer's arrays are allocated to the byte, so that a read past them is the sanitizers' finding,
 * and its depths and colours sit between guard zones. Returns 1 when some line shows. */
static int sparse_check(mc_pmesh_lod *lod, const mc_view *v, uint32_t w, uint32_t h, uint8_t *mem, mc_xvertex *cache, long k)
{
    gtarget z = gt_new(w, h), s = gt_new(w, h);
    uint32_t *bits = malloc(4u * MC_SDEPTH_WORDS(w, h));
    if (!bits) exit(2);
    mc_mesh_render(lod, v, MC_MESH_DRAW_PAPER | (PM.closed ? MC_MESH_CULL_BACK : 0u), &z.t, NULL, NULL);
    mc_lines_stats lz, ls;
    mc_mesh_lines(lod, v, MC_LINES_ALL, &z.t, mem, NULL, &lz);
    mc_sdepth sd;
    int rc = mc_sdepth_init(&sd, (uint16_t)w, (uint16_t)h, bits, s.t.depth, s.t.color, MC_DEPTH_FILLED, MC_MESH_PAPER);
    if (rc == MC_OK) rc = mc_mesh_lines_sparse(lod, v, MC_LINES_ALL, &sd, mem, cache, &ls);
    if (rc != MC_OK || memcmp(&lz, &ls, sizeof lz))
        PROBLEM("view %ld: sparse lines rc %d, %u edges %u %u %u %u px; z-buffer %u edges %u %u %u %u px", k, rc, ls.edges,
                ls.silhouettes, ls.creases, ls.borders, ls.pixels, lz.edges, lz.silhouettes, lz.creases, lz.borders, lz.pixels);
    unsigned long diff = 0, shown = 0;
    for (size_t i = 0; i < z.px; i++) {
        const unsigned cz = z.t.color[i], cs = s.t.color[i];
        const int lzi = z.t.depth[i] != MC_DEPTH_EMPTY && (cz == MC_LINES_SILHOUETTE_COLOR || cz == MC_LINES_CREASE_COLOR ||
                                                          cz == MC_LINES_BORDER_COLOR);
        const int lsi = cs == MC_LINES_SILHOUETTE_COLOR || cs == MC_LINES_CREASE_COLOR || cs == MC_LINES_BORDER_COLOR;
        diff += lzi != lsi || (!lsi && (cs != MC_MESH_PAPER || s.t.depth[i] != MC_DEPTH_FILLED));
        shown += lsi;
    }
    if (diff) PROBLEM("view %ld: %lu pixels show a line over the sparse depth buffer and not by the z-buffer, or the other way", k, diff);
    if (gt_guard(&z) || gt_guard(&s)) PROBLEM("view %ld: sparse lines: guard zones written", k);
    free(bits), gt_free(&z), gt_free(&s);
    return shown != 0;
}

static int random_check(mc_pmesh_lod *lod, long count, uint64_t seed)
{
    mc_rng g;
    mc_rng_seed(&g, seed, 7);
    mc_xvertex *cache = malloc(MC_MESH_CACHE_BYTES(PM.vertices));
    uint8_t *mem = calloc(MC_MESH_LINES_BYTES(PM.faces), 1);
    if (!cache || !mem) return 2;
    unsigned long flagged_views = 0, clipped = 0, away = 0, lines_clipped = 0, sparse_views = 0;
    for (long k = 0; k < count && !problems; k++) {
        mc_view v = mc_view_default();
        v.projection = mc_rng_below(&g, 5) ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;
        v.yaw = (int32_t)mc_rng_next(&g), v.pitch = (int32_t)mc_rng_next(&g), v.roll = (int32_t)mc_rng_next(&g);
        v.eye = mc_rng_below(&g, 4) ? rnd(&g, 2048, 70000) : rnd(&g, 2048, 65536 * 512);
        v.zoom = mc_rng_below(&g, 2) ? rnd(&g, 512, 65536 * 4) : rnd(&g, 512, 65536 * 128);
        v.tx = mc_rng_below(&g, 4) ? rnd(&g, -60, 60) : rnd(&g, -MC_COORD_LIMIT, MC_COORD_LIMIT);
        v.ty = mc_rng_below(&g, 4) ? rnd(&g, -60, 60) : rnd(&g, -MC_COORD_LIMIT, MC_COORD_LIMIT);
        const uint32_t w = (uint32_t)rnd(&g, 1, 200), h = (uint32_t)rnd(&g, 1, 200);
        const uint32_t level = PM.base_vertices + mc_rng_below(&g, PM.vertices - PM.base_vertices + 1) / (mc_rng_below(&g, 4) ? 8u : 1u);
        mc_pmesh_lod_set(lod, level);
        mc_xform x;
        mc_xform_init(&x, &v, w, h);
        uint32_t nflag = 0;
        for (uint32_t f = 0; f < lod->faces; f++) {
            int32_t p[3][3];
            mc_raster_vertex rv[3];
            nflag += mc_mesh_face(lod, &x, f, p, rv) != 0;
        }
        flagged_views += nflag != 0;
        for (unsigned fl = 0; fl < 4; fl++) {
            gtarget a = gt_new(w, h), b = gt_new(w, h);
            mc_mesh_stats sa, sb;
            memset(cache, 0x5A, MC_MESH_CACHE_BYTES(PM.vertices));
            const int ra = mc_mesh_render(lod, &v, fl, &a.t, NULL, &sa), rb = mc_mesh_render(lod, &v, fl, &b.t, cache, &sb);
            if (ra != MC_OK || rb != ra || memcmp(&sa, &sb, sizeof sa) || memcmp(a.t.color, b.t.color, a.px) ||
                memcmp(a.t.depth, b.t.depth, 2 * a.px))
                PROBLEM("view %ld flags %u: the vertex cache changes the frame", k, fl);
            if (sa.skipped || (!(fl & MC_MESH_CULL_BACK) && sa.clipped + sa.clipped_away != nflag) ||
                ((fl & MC_MESH_CULL_BACK) && sa.clipped + sa.clipped_away > nflag))
                PROBLEM("view %ld flags %u: clipped %u + away %u, %u flagged", k, fl, sa.clipped, sa.clipped_away, nflag);
            if (!(fl & MC_MESH_CULL_BACK)) clipped += sa.clipped, away += sa.clipped_away;
            mc_lines_stats la, lb;
            const unsigned lf = MC_LINES_ALL | ((fl & 1u) ? MC_LINES_NO_HIDING : 0u);
            mc_mesh_lines(lod, &v, lf, &a.t, mem, NULL, &la);
            mc_mesh_lines(lod, &v, lf, &b.t, mem, cache, &lb);
            if (memcmp(&la, &lb, sizeof la) || memcmp(a.t.color, b.t.color, a.px) || memcmp(a.t.depth, b.t.depth, 2 * a.px))
                PROBLEM("view %ld flags %u: the vertex cache changes the lines", k, fl);
            if (la.skipped) PROBLEM("view %ld: lines skipped %u", k, la.skipped);
            lines_clipped += la.clipped;
            if (gt_guard(&a) || gt_guard(&b)) PROBLEM("view %ld flags %u: guard zones written", k, fl);
            gt_free(&a), gt_free(&b);
        }
        sparse_views += sparse_check(lod, &v, w, h, mem, cache, k);
    }
    if (problems)
        printf("not ok: %lu problems; first: %s\n", problems, first);
    else
        printf("ok: %ld views (%lu with a flagged corner): %lu faces clipped, %lu clipped away, %lu lines clipped; guard zones "
               "untouched, the cache changing nothing; over the sparse depth buffer the same lines shown in %lu views with one\n",
               count, flagged_views, clipped, away, lines_clipped, sparse_views);
    free(cache), free(mem);
    return problems ? 1 : 0;
}

int main(int argc, char **argv)
{
    void *anc = malloc((size_t)PM.vertices * PM.index_bytes + 8);
    if (!anc) return 2;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    int rc = 2;
    if (argc == 9 && !strcmp(argv[1], "frame")) rc = frame_check(&lod, argv + 2);
    else if (argc == 4 && !strcmp(argv[1], "random")) rc = random_check(&lod, atol(argv[2]), strtoull(argv[3], 0, 10));
    else fprintf(stderr, "usage: clip_check frame N W H YAW PITCH ZOOM EYE | random COUNT SEED\n");
    free(anc);
    return rc;
}
