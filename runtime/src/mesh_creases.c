/* The line drawings' crease bits: see mesh_creases.h; mc_mesh_crease: mesh_lines.h. */
#include "mesh_creases.h"

/* The normal of the face with corners p, its components shifted right together (towards zero, signs
 * kept) until each fits 15 bits; all zero for a face with no area. The edges (17 bits) and the
 * components (15 bits) are int32, so that a 32-bit core takes each product in one step. */
static void normal15(const int32_t p[3][3], int32_t n[3])
{
    int32_t a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = p[1][i] - p[0][i], b[i] = p[2][i] - p[0][i];
    int64_t w[3];   /* components below 2^35 (mesh_render.c) */
    w[0] = (int64_t)a[1] * b[2] - (int64_t)a[2] * b[1];
    w[1] = (int64_t)a[2] * b[0] - (int64_t)a[0] * b[2];
    w[2] = (int64_t)a[0] * b[1] - (int64_t)a[1] * b[0];
    const uint64_t m = mc_mag64(w[0]) | mc_mag64(w[1]) | mc_mag64(w[2]);
    const uint32_t top = (uint32_t)(m >> 15);   /* (below 2^20) */
    const unsigned s = top ? 32u - mc_clz32(top) : 0u;   /* as mc_mesh_shade's: the least with m >> s < 2^15 */
    /* w / 2^s truncated, as a shift of the magnitude with the sign put back (a 64-bit division is a
     * library call on a 32-bit core; the sign is a coin toss to a predictor) */
    for (int i = 0; i < 3; i++) {
        const uint32_t neg = 0u - (uint32_t)(w[i] < 0);
        n[i] = (int32_t)((((uint32_t)(mc_mag64(w[i]) >> s)) ^ neg) - neg);
    }
}

/* Whether faces with normal15 normals n and m meet at more than the crease angle. */
static int crease_normals(const int32_t n[3], const int32_t m[3], int32_t crease_cos)
{
    const int64_t d = (int64_t)n[0] * m[0] + (int64_t)n[1] * m[1] + (int64_t)n[2] * m[2];   /* |d| < 3 * 2^30 */
    const uint32_t ln = (uint32_t)(n[0] * n[0]) + (uint32_t)(n[1] * n[1]) + (uint32_t)(n[2] * n[2]);   /* < 3 * 2^30 */
    const uint32_t lm = (uint32_t)(m[0] * m[0]) + (uint32_t)(m[1] * m[1]) + (uint32_t)(m[2] * m[2]);
    if (ln == 0 || lm == 0) return 0;
    /* cos = d / sqrt(ln lm) < c = crease_cos / 2^14; squared: d^2 against c^2 ln lm / 2^28, with
     * ln lm < 9 * 2^60 and (ln lm >> 28) c^2 < 9 * 2^60: no overflow */
    const uint64_t d2 = mc_mag64(d) * mc_mag64(d), rhs = (((uint64_t)ln * lm) >> 28) * (uint64_t)((int64_t)crease_cos * crease_cos);
    if (crease_cos >= 0) return d < 0 || d2 < rhs;
    return d < 0 && d2 > rhs;
}

int mc_mesh_crease(const int32_t a[3][3], const int32_t b[3][3], int32_t crease_cos)
{
    int32_t n[3], m[3];
    normal15(a, n);
    normal15(b, m);
    return crease_normals(n, m, crease_cos);
}

/* Sets (c 1) or clears (c 0) the crease bit of half-edge h. */
static void put_crease(uint8_t *cr, uint32_t h, uint32_t c)
{
    const uint32_t f = MC_HALF_FACE(h);
    const uint8_t bit = (uint8_t)((1u << MC_HALF_EDGE_INDEX(h)) << ((f & 1u) * 4u));
    cr[f >> 1] = (uint8_t)(c ? cr[f >> 1] | bit : cr[f >> 1] & ~bit);
}

/* Every crease bit of the level, each face's normal taken once for its later neighbours. */
static void creases_all(const mc_pmesh_lod *lod, uint8_t *cr)
{
    const mc_pmesh *pm = lod->pm;
    for (uint32_t i = 0; i < (pm->faces + 1u) / 2u; i++) cr[i] = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        int32_t n[3];
        int normal = 0;   /* n is f's (taken only for a face with a later neighbour) */
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
            if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) < f) continue;
            int32_t p[3][3], m[3];
            if (!normal) mc_mesh_face_positions(lod, f, p), normal15((const int32_t(*)[3])p, n), normal = 1;
            mc_mesh_face_positions(lod, MC_HALF_FACE(o), p);
            normal15((const int32_t(*)[3])p, m);
            if (crease_normals(n, m, pm->crease_cos)) put_crease(cr, h, 1), put_crease(cr, o, 1);
        }
    }
}

/* The crease bits of face f's three edges, on both sides of each. */
static void creases_face(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t f)
{
    int32_t p[3][3], n[3];
    mc_mesh_face_positions(lod, f, p);
    normal15((const int32_t(*)[3])p, n);
    for (uint32_t k = 0; k < 3; k++) {
        const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
        uint32_t c = 0;
        if (o != MC_NO_HALF_EDGE) {
            int32_t q[3][3], m[3];
            mc_mesh_face_positions(lod, MC_HALF_FACE(o), q);
            normal15((const int32_t(*)[3])q, m);
            c = (uint32_t)crease_normals(n, m, lod->pm->crease_cos);
            put_crease(cr, o, c);
        }
        put_crease(cr, h, c);
    }
}

/* creases_face for every face around corner j of face g (the level's faces at that vertex, turning
 * through the neighbours one way until a border or back at g, then the other way). Returns 0, with
 * some done, past `limit` faces (arrays whose neighbours do not pair up could turn forever). */
static int creases_fan(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t g, uint32_t j, uint32_t limit)
{
    uint32_t f = g, k = j, n = 0;   /* corner k of f is the vertex: edge k leaves it, edge k + 2 ends there */
    for (;;) {
        creases_face(lod, cr, f);
        if (++n > limit) return 0;
        const uint32_t o = mc_pmesh_lod_opposite(lod, MC_HALF_EDGE(f, (k + 2u) % 3u));
        if (o == MC_NO_HALF_EDGE) break;
        f = MC_HALF_FACE(o), k = MC_HALF_EDGE_INDEX(o);   /* o leaves the vertex */
        if (f == g) return 1;
    }
    for (f = g, k = j;;) {
        const uint32_t o = mc_pmesh_lod_opposite(lod, MC_HALF_EDGE(f, k));
        if (o == MC_NO_HALF_EDGE) return 1;
        f = MC_HALF_FACE(o), k = (MC_HALF_EDGE_INDEX(o) + 1u) % 3u;   /* o ends at the vertex */
        if (f == g) return 1;
        creases_face(lod, cr, f);
        if (++n > limit) return 0;
    }
}

/* Brings the crease bits of level `from` to the current level by recomputing the faces around the
 * vertices the splits between the two moved: refined, around every corner of the faces they made
 * (each split vertex and its parent is one, and a face whose corner moved, or whose neighbour
 * changed, lies at one); coarsened, the faces they made cleared and the faces around both ends of
 * each edge they merged (the faces now across those faces' edges 1 and 2, pmesh.h). Returns 0, to
 * recompute all, when that would cost about as much (the faces changed over a 48th of the level's:
 * a changed face costs some forty of the full pass's, its corners' fans being recomputed whole) or
 * when an edge or a fan cannot be found. */
static int creases_step(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t from)
{
    const mc_pmesh *pm = lod->pm;
    const unsigned ib = pm->index_bytes, shift = pm->record_shift;
    const uint32_t to = lod->level, lo = from < to ? from : to, hi = from < to ? to : from;
    if (lo < pm->base_vertices || hi > pm->vertices) return 0;
    uint32_t nf = 0;
    for (uint32_t s = lo - pm->base_vertices; s < hi - pm->base_vertices; s++) {
        nf += mc_chunk_record(pm->splits, shift, ib + 1u, s)[ib];
        if (nf > lod->faces / 48u) return 0;
    }
    const uint32_t limit = lod->faces < 1024u ? lod->faces : 1024u;
    if (to > from) {   /* the new faces are the level's last nf */
        for (uint32_t f = lod->faces - nf; f < lod->faces; f++)
            for (uint32_t j = 0; j < 3u; j++)
                if (!creases_fan(lod, cr, f, j, limit)) return 0;
        return 1;
    }
    if (lod->faces + nf > pm->faces) return 0;
    for (uint32_t f = lod->faces; f < lod->faces + nf; f++) cr[f >> 1] &= (uint8_t)(f & 1u ? 0x0Fu : 0xF0u);
    for (uint32_t f = lod->faces; f < lod->faces + nf; f++) {
        int found = 0;
        for (uint32_t k = 1; k < 3u; k++) {
            const uint32_t o = mc_pmesh_lod_across(lod, mc_pmesh_opposite(pm, MC_HALF_EDGE(f, k)));
            if (o == MC_NO_HALF_EDGE) continue;
            const uint32_t g = MC_HALF_FACE(o), j = MC_HALF_EDGE_INDEX(o);
            if (!creases_fan(lod, cr, g, j, limit) || !creases_fan(lod, cr, g, (j + 1u) % 3u, limit)) return 0;
            found = 1;
        }
        if (!found) return 0;
    }
    return 1;
}

/* Kept while the level is unchanged, brought over from the last level by creases_step when that is
 * near, else recomputed; then the tag. */
void mc_mesh_creases_update(const mc_pmesh_lod *lod, uint8_t *mem)
{
    const mc_pmesh *pm = lod->pm;
    const uint32_t tag = *mc_lines_tag(mem) & 0x7FFFFFFFu;
    if (tag == lod->level + 1u) return;
    uint8_t *cr = mc_lines_creases(mem, pm->faces);
    if (!tag || !creases_step(lod, cr, tag - 1u)) creases_all(lod, cr);
    uint32_t any = 0;
    for (uint32_t i = 0; i < (lod->faces + 1u) / 2u; i++) any |= cr[i];
    *mc_lines_tag(mem) = (lod->level + 1u) | (uint32_t)(any != 0) << 31;
}

