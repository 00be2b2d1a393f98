/* Checks a baked progressive mesh through the runtime's level of detail (runtime/src/pmesh.c).
 * Built by tests/gen/pmesh.sh with -DPM=mc_pmesh_NAME -include build/.../NAME.h and the bake's files.
 *
 *   pmesh_check levels        every level of a mesh up to 4000 vertices, else the first and last 200
 *                             and 400 spread between, visited in a shuffled order: every face present
 *                             has three distinct corners, each a vertex present at that level, and
 *                             the face count is F(n); the arrays' own invariants (subtree sizes, the
 *                             splits' parents present before them); one line "ok ..." or "not ok ..."
 *   pmesh_check faces N       the faces of level N, one line each: the corners' quantized positions
 *                             (x y z three times), in the format of modelc --dump-pmesh-level
 *   pmesh_check render N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE CULL   (zoom, eye Q16; xform.h)
 *                             level N drawn by mc_mesh_render (runtime/src/mesh_render.c) into a
 *                             W x H target inside guard zones, against the same faces composed in
 *                             doubles: each face's corners as mc_mesh_face gives them (projected by
 *                             mc_xform_vertex, tested on its own, tests/unit/test_xform.c), covered
 *                             and depth-tested by the double
 *                             reference of the rasterizer (runtime/ref/raster_ref.c), shaded by
 *                             |n.z| / |n| in doubles. The covered pixels must be the same set; the
 *                             colour the same wherever the two nearest faces are more than 2 depth
 *                             units apart and the shade is not within 1/100 of a rounding point; the depth
 *                             within 1 unit of the nearest face's; the guard zones untouched; the
 *                             skipped-face count the reference's
 */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <math.h>

#include "modelc/mesh_render.h"
#include "modelc/pmesh.h"
#include "../../runtime/ref/raster_ref.h"

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
    if (!cmem || !cov || !best_shade || !best_amb || !dmem || !d1 || !d2 || !fd) return 2;
    memset(cmem, 0xA5, px + 2 * G);
    for (size_t i = 0; i < px + 2 * G; i++) dmem[i] = 0x5A5A;
    mc_target t = {cmem + G, dmem + G, (uint16_t)w, (uint16_t)h};
    mc_clear(&t);
    mc_mesh_stats st;
    int rc = mc_mesh_render(lod, &v, cull ? MC_MESH_CULL_BACK : 0u, &t, &st);
    /* the reference */
    for (size_t i = 0; i < px; i++) d1[i] = d2[i] = HUGE_VAL, best_shade[i] = 0, best_amb[i] = 0;
    mc_xform x;
    mc_xform_init(&x, &v, w, h);
    uint32_t skipped = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        int32_t p[3][3];
        mc_raster_vertex rv[3];
        if (mc_mesh_face(lod, &x, f, p, rv)) { skipped++; continue; }
        memset(cov, 0, px);
        if (!mc_raster_ref_triangle(w, h, rv, cull ? MC_RASTER_CULL_BACK : 0u, cov, fd)) continue;
        int amb;
        unsigned s = ref_shade(p, &amb);
        for (size_t i = 0; i < px; i++) {
            if (!cov[i]) continue;
            if (fd[i] < d1[i]) d2[i] = d1[i], d1[i] = fd[i], best_shade[i] = (uint8_t)s, best_amb[i] = (uint8_t)amb;
            else if (fd[i] < d2[i]) d2[i] = fd[i];
        }
    }
    unsigned long coverage = 0, colour = 0, depth = 0, ties = 0, guard = 0, covered = 0;
    for (size_t i = 0; i < G; i++)
        guard += cmem[i] != 0xA5 || cmem[G + px + i] != 0xA5 || dmem[i] != 0x5A5A || dmem[G + px + i] != 0x5A5A;
    for (size_t i = 0; i < px; i++) {
        const int ref_cov = d1[i] < HUGE_VAL, got = t.depth[i] != MC_DEPTH_EMPTY;
        if (ref_cov != got) { coverage++; continue; }
        if (!got) continue;
        covered++;
        if (d2[i] - d1[i] <= 2 || best_amb[i]) { ties++; continue; }
        colour += t.color[i] != best_shade[i];
        depth += fabs(t.depth[i] - floor(d1[i] + 0.5)) > 1;
    }
    int ok = rc == MC_OK && !coverage && !colour && !depth && !guard && st.skipped == skipped && covered > 0;
    printf("%s: level %u, %u faces (%u skipped), %lu pixels covered; %lu coverage, %lu colour, %lu depth "
           "differences, %lu guard-zone bytes touched, %lu pixels on depth or shade ties\n",
           ok ? "ok" : "not ok", n, lod->faces, st.skipped, covered, coverage, colour, depth, guard, ties);
    free(cmem), free(cov), free(best_shade), free(best_amb), free(dmem), free(d1), free(d2), free(fd);
    return ok ? 0 : 1;
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
    if (argc != 2 || strcmp(argv[1], "levels")) {
        fprintf(stderr, "usage: pmesh_check levels | faces N | render N W H PERSPECTIVE YAW PITCH ROLL ZOOM EYE CULL\n");
        return 2;
    }
    /* ranks and F(n) from the arrays; the tree's invariants */
    unsigned long problems = 0;
    char first[200] = "";
#define PROBLEM(...) do { if (!problems++) snprintf(first, sizeof first, __VA_ARGS__); } while (0)
    for (uint32_t v = 0; v < V; v++) rank[v] = UINT32_MAX;
    fcount[V0] = pm->base_faces;
    for (uint32_t s = 0; s < V - V0; s++) {
        uint32_t v = field(pm->splits, ib + 1, s, 0, ib);
        uint32_t nf = mc_chunk_record(pm->splits, pm->record_shift, ib + 1, s)[ib];
        if (v >= V || rank[v] != UINT32_MAX) { PROBLEM("split %u brings back vertex %u twice or out of range", s, v); break; }
        rank[v] = V0 + s;
        if (nf < 1 || nf > 2) PROBLEM("split %u adds %u faces", s, nf);
        fcount[V0 + s + 1] = fcount[V0 + s] + nf;
    }
    if (fcount[V] != pm->faces) PROBLEM("the splits add up to %u faces, the descriptor says %u", fcount[V], pm->faces);
    uint32_t roots = 0;
    for (uint32_t v = 0; v < V && !problems; v++) {
        uint32_t parent = field(pm->tree, 2 * ib, v, 0, ib), size = field(pm->tree, 2 * ib, v, ib, ib);
        if (size < 1 || v + size > V) PROBLEM("vertex %u: subtree size %u", v, size);
        if (parent == v) {
            roots++;
            if (rank[v] != UINT32_MAX) PROBLEM("root %u is also split", v);
            rank[v] = 0;
        } else {
            uint32_t psize = field(pm->tree, 2 * ib, parent, ib, ib);
            if (parent > v || v >= parent + psize) PROBLEM("vertex %u lies outside its parent %u's subtree", v, parent);
            if (rank[v] == UINT32_MAX || rank[parent] >= rank[v]) PROBLEM("vertex %u splits before its parent %u", v, parent);
        }
    }
    if (roots != V0) PROBLEM("%u roots, the descriptor says %u base vertices", roots, V0);
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
    for (uint32_t i = 0; i < nl && !problems; i++) {
        uint32_t n = levels[i];
        if (mc_pmesh_lod_set(&lod, n) != n || lod.level != n) PROBLEM("level %u not set", n);
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
    }
    if (problems)
        printf("not ok: %lu problems; first: %s\n", problems, first);
    else
        printf("ok: %u vertices (%u base), %u faces (%u base), %u levels, %llu faces checked\n", V, V0, pm->faces,
               pm->base_faces, nl, (unsigned long long)faces_checked);
    free(levels), free(anc), free(rank), free(fcount);
    return problems ? 1 : 0;
}
