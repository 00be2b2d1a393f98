/* The line drawings' crease bits: see mesh_creases.h; mc_mesh_crease: mesh_lines.h. */
#include "mesh_creases.h"
#include "modelc/bytes.h"

/* mesh_face.h's normal and crease test, each kept once (a firmware's flash) for the calls below */
static void normal15(const int32_t p[3][3], int32_t n[3]) { mc_mesh_normal15(p, n); }
static int crease_normals(const int32_t n[3], const int32_t m[3], int32_t crease_cos)
{
    return mc_mesh_crease_normals(n, m, crease_cos);
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

/* Face f's normal15 normal at the level (apart: called from six places, which a firmware's flash
 * keeps once). */
static MC_NOINLINE void face_normal(const mc_pmesh_lod *lod, uint32_t f, int32_t n[3])
{
    int32_t p[3][3];
    mc_mesh_face_positions(lod, f, p);
    normal15((const int32_t(*)[3])p, n);
}

/* Every crease bit of the level, each face's normal taken once for its later neighbours. An edge
 * between two faces as in the full mesh, across the opposite the arrays store, is as in the full
 * mesh too: its bit is the stored one (pmesh.h face_bits), where the part has them; at the full
 * level every bit is, read in order. */
static void creases_all(const mc_pmesh_lod *lod, uint8_t *cr)
{
    const mc_pmesh *pm = lod->pm;
    mc_bytes_zero(cr, (pm->faces + 1u) / 2u);
    if (pm->face_bits && lod->level == pm->vertices) {
        const unsigned shift = pm->record_shift;
        for (uint32_t f = 0; f < lod->faces; f++) {
            const uint32_t b = pm->face_bits[f >> shift].data[f & ((UINT32_C(1) << shift) - 1u)];
            cr[f >> 1] = (uint8_t)(cr[f >> 1] | (b >> 5) << ((f & 1u) * 4u));
        }
        return;
    }
    for (uint32_t f = 0; f < lod->faces; f++) {
        int32_t n[3];
        int normal = 0;   /* n is f's (taken only for a face with a later neighbour) */
        /* f's stored bits, with bit 8 set, when they may hold; else 0 */
        const uint32_t stored = pm->face_bits && mc_pmesh_lod_face_as_full(lod, f)
                                    ? 0x100u | *mc_chunk_record(pm->face_bits, pm->record_shift, 1u, f) : 0u;
        const uint8_t *across = mc_chunk_record(pm->opposite, pm->record_shift, 3u * pm->half_bytes, f);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), s = mc_pmesh_half(across + k * pm->half_bytes, pm->half_bytes);
            const uint32_t o = lod->nbr ? mc_pmesh_lod_opposite(lod, h) : mc_pmesh_lod_across(lod, s);
            if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) < f) continue;
            if (stored && o == s && mc_pmesh_lod_face_as_full(lod, MC_HALF_FACE(o))) {
                if (MC_FACE_BITS_CREASE(stored, k)) put_crease(cr, h, 1), put_crease(cr, o, 1);
                continue;
            }
            int32_t m[3];
            if (!normal) face_normal(lod, f, n), normal = 1;
            face_normal(lod, MC_HALF_FACE(o), m);
            if (crease_normals(n, m, pm->crease_cos)) put_crease(cr, h, 1), put_crease(cr, o, 1);
        }
    }
}

/* The crease bit of edge h, whose face has normal n, and of its opposite o (none: a border, never a
 * crease), whose face has normal m (ignored for a border). */
static void put_edge(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t h, uint32_t o, const int32_t n[3], const int32_t m[3])
{
    uint32_t c = 0;
    if (o != MC_NO_HALF_EDGE) {
        c = (uint32_t)crease_normals(n, m, lod->pm->crease_cos);
        put_crease(cr, o, c);
    }
    put_crease(cr, h, c);
}

/* The crease bits of edge k (not a spoke: the one across from the fan's vertex) of fan face f, whose
 * normal is n, on both sides. */
static void put_rim(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t f, uint32_t k, const int32_t n[3])
{
    const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
    int32_t m[3] = {0, 0, 0};
    if (o != MC_NO_HALF_EDGE) face_normal(lod, MC_HALF_FACE(o), m);
    put_edge(lod, cr, h, o, n, m);
}

/* One way round the fan of creases_fan from face g (normal ng) with the vertex at its corner j:
 * across the spoke that ends at the vertex (way 0) or leaves it (way 1), each face's normal taken
 * once, the spoke between two faces from their normals, each face's rim from the face across it.
 * Returns 1 at a border, 2 back at g (way 0 sets that last spoke, between the last face and g), 0
 * past `limit` faces counted in *count. */
static int fan_way(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t g, uint32_t j, const int32_t ng[3], unsigned way,
                   uint32_t limit, uint32_t *count)
{
    int32_t n[3] = {ng[0], ng[1], ng[2]}, m[3];
    uint32_t f = g, k = j;   /* corner k of f is the vertex: edge k leaves it, edge k + 2 ends there */
    for (;;) {
        const uint32_t h = MC_HALF_EDGE(f, way ? k : (k + 2u) % 3u), o = mc_pmesh_lod_opposite(lod, h);
        if (o == MC_NO_HALF_EDGE) {
            put_edge(lod, cr, h, o, n, n);
            return 1;
        }
        const uint32_t e = MC_HALF_FACE(o);
        if (e == g) {
            if (!way) put_edge(lod, cr, h, o, n, ng);
            return 2;
        }
        if (++*count > limit) return 0;
        face_normal(lod, e, m);
        put_edge(lod, cr, h, o, n, m);
        /* o leaves the vertex (way 0) or ends there (way 1) */
        f = e, k = way ? (MC_HALF_EDGE_INDEX(o) + 1u) % 3u : MC_HALF_EDGE_INDEX(o);
        put_rim(lod, cr, f, (k + 1u) % 3u, m);
        n[0] = m[0], n[1] = m[1], n[2] = m[2];
    }
}

/* The crease bits of every edge of every face around corner j of face g (the level's faces at that
 * vertex, turning through the neighbours one way until a border or back at g, then the other way),
 * on both sides, g's rim too. Returns 0, with some done, past `limit` faces (arrays whose neighbours
 * do not pair up could turn forever). */
static int creases_fan(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t g, uint32_t j, uint32_t limit)
{
    int32_t ng[3];
    uint32_t count = 1;
    face_normal(lod, g, ng);
    put_rim(lod, cr, g, (j + 1u) % 3u, ng);
    const int r = fan_way(lod, cr, g, j, ng, 0u, limit, &count);
    return r == 1 ? fan_way(lod, cr, g, j, ng, 1u, limit, &count) != 0 : r != 0;
}

/* The vertices whose fans a level step has just recomputed (the last few: a split's faces share
 * theirs), so that each is taken once. */
typedef struct recent_fans {
    uint32_t v[4];
    uint32_t next;
} recent_fans;

/* creases_fan around corner j of face g, vertex v at the level, unless v's was among the last few. */
static int fan_once(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t g, uint32_t j, uint32_t v, uint32_t limit,
                    recent_fans *r)
{
    if (v == r->v[0] || v == r->v[1] || v == r->v[2] || v == r->v[3]) return 1;
    r->v[r->next++ & 3u] = v;
    return creases_fan(lod, cr, g, j, limit);
}

/* Brings the crease bits of level `from` to the current level by recomputing the faces around the
 * vertices the splits between the two moved: refined, around both ends of edge 0 of every face they
 * made (a split's vertex and its parent, or the descendants standing for them at the level: a face
 * whose corner moved lies at such an end of some split between, and a face whose neighbour changed
 * has a new face across, all of whose edges are taken; the third corner moved nothing), a vertex
 * once for a split's two faces; coarsened, the faces they made cleared and the faces around both ends of
 * each edge they merged (the faces now across those faces' edges 1 and 2, pmesh.h). Returns 0, to
 * recompute all, when that would cost about as much (the faces changed over a `share`th of the
 * level's: a changed face costs some fifteen of the full pass's on bunny00, the fans of its vertices
 * being recomputed whole, so 16; some 250 of the full level's read from stored bits, so 256 there)
 * or when an edge or a fan cannot be found. Each fan's vertex is taken once among
 * the last few (fan_once). */
static int creases_step(const mc_pmesh_lod *lod, uint8_t *cr, uint32_t from, uint32_t share)
{
    const mc_pmesh *pm = lod->pm;
    const uint32_t to = lod->level, lo = from < to ? from : to, hi = from < to ? to : from;
    if (lo < pm->base_vertices || hi > pm->vertices) return 0;
    uint32_t nf = 0;
    for (uint32_t s = lo - pm->base_vertices; s < hi - pm->base_vertices; s++) {
        nf += mc_pmesh_split_faces(pm, s);
        if (nf > lod->faces / share) return 0;
    }
    const uint32_t limit = lod->faces < 1024u ? lod->faces : 1024u;
    recent_fans r = {{MC_NO_HALF_EDGE, MC_NO_HALF_EDGE, MC_NO_HALF_EDGE, MC_NO_HALF_EDGE}, 0};
    if (to > from) {   /* the new faces are the level's last nf */
        for (uint32_t f = lod->faces - nf; f < lod->faces; f++) {
            uint32_t c[3];
            mc_pmesh_lod_face(lod, f, c);
            for (uint32_t j = 0; j < 2u; j++)   /* the ends of edge 0: a split's vertex and its parent */
                if (!fan_once(lod, cr, f, j, c[j], limit, &r)) return 0;
        }
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
            uint32_t c[3];
            mc_pmesh_lod_face(lod, g, c);
            for (uint32_t i = 0; i < 2u; i++)   /* both ends of the merged edge */
                if (!fan_once(lod, cr, g, (j + i) % 3u, c[(j + i) % 3u], limit, &r)) return 0;
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
    /* (the full level from stored bits costs a few instructions a face: only small steps beat it) */
    const uint32_t share = pm->face_bits && lod->level == pm->vertices ? 256u : 16u;
    if (!tag || !creases_step(lod, cr, tag - 1u, share)) creases_all(lod, cr);
    const uint32_t any = (uint32_t)mc_bytes_any(cr, (lod->faces + 1u) / 2u);
    *mc_lines_tag(mem) = (lod->level + 1u) | any << 31;
}

