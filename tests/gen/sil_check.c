/* Checks and measures the silhouette search (runtime/src/silhouette.c) on a baked progressive mesh.
 * Built by tests/gen/silhouette.sh and tests/bench/silhouette.sh with -DPM=mc_pmesh_NAME -include
 * NAME.h and the bake's files.
 *
 *   sil_check check W H           over a turn of views at three levels (every fourth view in
 *                                 perspective with the eye inside the model's cube: corners flagged
 *                                 at the near plane): mc_sil_exact's list equals the silhouette edges
 *                                 of mesh_lines.h's classification (mc_mesh_facing + mc_mesh_edge_kind
 *                                 over every edge: checked against a double-precision classification in
 *                                 pmesh_check.c lines), each once, with the vertex cache (mc_sil_cache)
 *                                 at every other view; mc_sil_search's list, at several budgets, is a
 *                                 subset of it with no edge twice, its tests within the budget, and
 *                                 the same lists from the same calls (a second state run alongside,
 *                                 with the vertex cache); one line "ok ..." or "not ok ..."
 *   sil_check run W H FRAMES DEG BUDGET SEEDS MODE [cache]
 *                                 a turn of FRAMES views DEG degrees apart (yaw, pitch 20 degrees),
 *                                 MODE search or exact; per frame the found silhouettes' screen length
 *                                 against the exact set's; prints the recall (median, 5th percentile,
 *                                 minimum after the first 10 frames) and the mean tests and facings per
 *                                 frame; with cache, search and exact project each vertex once a call
 *                                 (mc_sil_cache). Under callgrind, --toggle-collect=mc_sil_search or mc_sil_exact
 *                                 counts the mode's instructions alone (the exact set for the recall is
 *                                 found by mc_mesh_facing + mc_mesh_edge_kind, outside both).
 *                                 MODE lines: the exact set as the lines style finds it, its frame's
 *                                 passes without drawing (mc_mesh_lines_sparse with no edge kind and
 *                                 MC_LINES_NO_HIDING, the vertex cache on: the projection, every face's
 *                                 facing, the edge pass); its count of silhouettes must equal the exact
 *                                 set's every frame (recall 1, else "not ok" and exit 1);
 *                                 --toggle-collect=mc_mesh_lines_sparse (the crease bits, which the
 *                                 first frame works out and the rest keep, included).
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "modelc/mesh_lines.h"
#include "modelc/sdepth.h"
#include "modelc/silhouette.h"

extern const mc_pmesh PM;

/* 1 for every half-edge (both sides) of a silhouette edge at the level, by mesh_lines' classification */
static uint32_t classify(const mc_pmesh_lod *lod, const mc_xform *x, uint8_t *facing, uint8_t *is_sil)
{
    uint32_t n = 0;
    mc_mesh_facing(lod, x, facing);
    memset(is_sil, 0, 4u * lod->faces);
    for (uint32_t f = 0; f < lod->faces; f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
            if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) < f) continue;
            if (mc_mesh_edge_kind(lod, facing, h, o) == MC_EDGE_SILHOUETTE) is_sil[h] = is_sil[o] = 1, n++;
        }
    return n;
}

static double edge_length(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t h)
{
    uint32_t c[3];
    mc_pmesh_lod_face(lod, MC_HALF_FACE(h), c);
    int32_t a[3], b[3];
    mc_pmesh_position(lod->pm, c[MC_HALF_EDGE_INDEX(h)], a);
    mc_pmesh_position(lod->pm, c[(MC_HALF_EDGE_INDEX(h) + 1) % 3], b);
    mc_xvertex va, vb;
    mc_xform_vertex(x, a, &va);
    mc_xform_vertex(x, b, &vb);
    return hypot((double)va.x - vb.x, (double)va.y - vb.y) / 16.0;
}

static mc_view view_at(double deg)
{
    mc_view v = mc_view_default();
    v.yaw = (int32_t)lround(deg * MC_ANGLE_FULL / 360.0);
    v.pitch = (int32_t)lround(20.0 * MC_ANGLE_FULL / 360.0);
    return v;
}

/* view_at in perspective with the eye a fifth of the cube from its centre: the near plane cuts
 * the model, so some corners are flagged */
static mc_view view_inside(double deg)
{
    mc_view v = view_at(deg);
    v.projection = MC_PERSPECTIVE;
    v.eye = MC_ZOOM_ONE / 5;
    return v;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: sil_check check W H | run W H FRAMES DEG BUDGET SEEDS search|exact|lines [cache]\n");
        return 2;
    }
    const uint32_t w = (uint32_t)atoi(argv[2]), h = (uint32_t)atoi(argv[3]), F = PM.faces, cap = 4u * F;
    void *anc = malloc((size_t)PM.vertices * 4 + 8);
    uint8_t *facing = malloc(MC_MESH_FACING_BYTES(F) + 8), *is_sil = malloc(4u * F + 8), *seen = malloc(4u * F + 8);
    uint32_t *marks = malloc(MC_SIL_FACE_BYTES(F) + 8), *marks2 = malloc(MC_SIL_FACE_BYTES(F) + 8);
    uint32_t *list = malloc(4u * cap), *list2 = malloc(4u * cap);
    mc_xvertex *vcache = malloc(MC_MESH_CACHE_BYTES(PM.vertices));   /* mc_sil_cache's */
    uint32_t *vseen = malloc(4u * MC_SIL_SEEN_WORDS(PM.vertices));
    if (!anc || !facing || !is_sil || !seen || !marks || !marks2 || !list || !list2 || !vcache || !vseen) return 2;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, &PM, anc);
    if (!strcmp(argv[1], "check")) {
        unsigned long bad = 0, frames = 0, exact_total = 0, searched_total = 0;
        char first[240] = "";
        const uint32_t levels[3] = {PM.base_vertices + (PM.vertices - PM.base_vertices) / 10,
                                    PM.base_vertices + (PM.vertices - PM.base_vertices) / 2, PM.vertices};
        const uint32_t budgets[3] = {50, 2000, 100000};
        for (int l = 0; l < 3; l++) {
            mc_pmesh_lod_set(&lod, levels[l]);
            for (int b = 0; b < 3; b++) {
                mc_sil s, s2;
                mc_sil_init(&s, (uint8_t *)marks, list, cap, 12345);
                mc_sil_init(&s2, (uint8_t *)marks2, list2, cap, 12345);
                mc_sil_cache(&s2, vcache, vseen);
                for (int i = 0; i < 24; i++, frames++) {
                    mc_view v = i % 4 == 3 ? view_inside(i * 15.0 + l * 7.0) : view_at(i * 15.0 + l * 7.0);
                    mc_xform x;
                    mc_xform_init(&x, &v, w, h);
                    const uint32_t want = classify(&lod, &x, facing, is_sil);
                    mc_sil_stats st;
                    if (b == 0) {   /* the exact scan, once per view */
                        mc_sil e;
                        mc_sil_init(&e, (uint8_t *)marks, list, cap, 1);
                        if (i & 1) mc_sil_cache(&e, vcache, vseen);
                        const uint32_t n = mc_sil_exact(&e, &lod, &x, &st);
                        memset(seen, 0, 4u * F);
                        uint32_t ok = n == want && e.count == want;
                        for (uint32_t j = 0; j < e.count && ok; j++) {
                            const uint32_t he = e.list[j], o = mc_pmesh_lod_opposite(&lod, he);
                            ok = is_sil[he] && !seen[he] && o != MC_NO_HALF_EDGE && !seen[o];
                            seen[he] = 1;
                            if (o != MC_NO_HALF_EDGE) seen[o] = 1;
                        }
                        if (!ok && !bad++)
                            snprintf(first, sizeof first, "level %u view %d: exact scan lists %u (returns %u), want %u",
                                     lod.level, i, e.count, n, want);
                        exact_total += want;
                        mc_sil_init(&s, (uint8_t *)marks, list, cap, 12345);   /* the exact scan used the buffers */
                        continue;
                    }
                    const uint32_t seeds = 20;
                    mc_sil_search(&s, &lod, &x, budgets[b], seeds, &st);
                    mc_sil_stats st2;
                    mc_sil_search(&s2, &lod, &x, budgets[b], seeds, &st2);
                    memset(seen, 0, 4u * F);
                    int ok = st.tests <= budgets[b] && s.count == s2.count && !memcmp(s.list, s2.list, 4u * s.count) &&
                             st.tests == st2.tests;
                    for (uint32_t j = 0; j < s.count && ok; j++) {
                        const uint32_t he = s.list[j], o = mc_pmesh_lod_opposite(&lod, he);
                        ok = MC_HALF_FACE(he) < lod.faces && is_sil[he] && !seen[he] && o != MC_NO_HALF_EDGE && !seen[o];
                        seen[he] = 1;
                        if (o != MC_NO_HALF_EDGE) seen[o] = 1;
                    }
                    if (!ok && !bad++)
                        snprintf(first, sizeof first, "level %u view %d budget %u: search listed %u (tests %u), not a "
                                 "repeatable subset of the %u silhouettes", lod.level, i, budgets[b], s.count, st.tests, want);
                    searched_total += s.count;
                }
            }
        }
        if (bad) printf("not ok: %lu problems; first: %s\n", bad, first);
        else
            printf("ok: %lu frames at 3 levels: exact scans equal the classification (%lu silhouette edges), searches at "
                   "budgets 50, 2000, 100000 list only silhouettes, each once, within budget, repeatably, the same with "
                   "the vertex cache (%lu listed)\n",
                   frames, exact_total, searched_total);
        return bad ? 1 : 0;
    }
    if (!strcmp(argv[1], "run") && (argc == 9 || (argc == 10 && !strcmp(argv[9], "cache")))) {
        const int frames = atoi(argv[4]);
        const double deg = atof(argv[5]);
        const uint32_t budget = (uint32_t)strtoul(argv[6], 0, 10), seeds = (uint32_t)strtoul(argv[7], 0, 10);
        const int exact = !strcmp(argv[8], "exact"), lines = !strcmp(argv[8], "lines");
        mc_pmesh_lod_set(&lod, PM.vertices);
        /* MODE lines: the lines style's memory, vertex cache and (empty) sparse buffer */
        uint32_t *mem = calloc(MC_MESH_LINES_BYTES(F) / 4u + 1u, 4), *sbits = malloc(4u * MC_SDEPTH_WORDS(w, h));
        uint16_t *sdepth = malloc(2u * w * h);
        uint8_t *scolor = malloc((size_t)w * h);
        mc_xvertex *cache = malloc(MC_MESH_CACHE_BYTES(PM.vertices));
        mc_sdepth sd;
        if (!mem || !sbits || !sdepth || !scolor || !cache ||
            mc_sdepth_init(&sd, (uint16_t)w, (uint16_t)h, sbits, sdepth, scolor, 0xFFFFu, 0) != MC_OK)
            return 2;
        unsigned long miscounted = 0;
        mc_sil s;
        mc_sil_init(&s, (uint8_t *)marks, list, cap, 12345);
        if (argc == 10) mc_sil_cache(&s, vcache, vseen);
        double *recall = malloc(sizeof(double) * (size_t)frames);
        double tests = 0, facings = 0;
        int n = 0;
        if (!recall) return 2;
        for (int i = 0; i < frames; i++) {
            mc_view v = view_at(i * deg);
            mc_xform x;
            mc_xform_init(&x, &v, w, h);
            mc_sil_stats st;
            mc_lines_stats ls;
            if (lines) {
                if (mc_mesh_lines_sparse(&lod, &v, MC_LINES_NO_HIDING, &sd, (uint8_t *)mem, cache, &ls) != MC_OK) return 2;
                st.tests = 0, st.facings = lod.faces;   /* (no edge tests counted: a pass over the faces) */
            } else if (exact) {
                mc_sil_exact(&s, &lod, &x, &st);
            } else {
                mc_sil_search(&s, &lod, &x, budget, seeds, &st);
            }
            classify(&lod, &x, facing, is_sil);
            double all = 0, got = 0;
            uint32_t count = 0;
            for (uint32_t f = 0; f < lod.faces; f++)
                for (uint32_t k = 0; k < 3; k++) {
                    const uint32_t he = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(&lod, he);
                    if (is_sil[he] && MC_HALF_FACE(o) > f) all += edge_length(&lod, &x, he), count++;
                }
            if (lines) {   /* a count, not a list: all of them, or a miscount */
                got = ls.silhouettes == count ? all : 0;
                miscounted += ls.silhouettes != count;
            }
            for (uint32_t j = 0; !lines && j < s.count; j++) got += edge_length(&lod, &x, s.list[j]);
            if (i >= 10) recall[n++] = all > 0 ? got / all : 1.0, tests += st.tests, facings += st.facings;
        }
        qsort(recall, (size_t)n, sizeof(double), cmp_double);
        printf("frames %d recall median %.4f p5 %.4f min %.4f tests %.0f facings %.0f edges %u faces %u\n", n,
               recall[n / 2], recall[n / 20], recall[0], tests / n, facings / n, PM.edges, lod.faces);
        if (miscounted) printf("not ok: the lines style's edge pass counted other silhouettes in %lu frames\n", miscounted);
        return miscounted ? 1 : 0;
    }
    fprintf(stderr, "sil_check: bad arguments\n");
    return 2;
}
