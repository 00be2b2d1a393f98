/* Level of detail of a progressive mesh (pmesh.h): the ancestor map, refined and coarsened. */
#include "modelc/pmesh.h"

/* Record i of a list of one index field each, ib bytes wide, 2^shift records a chunk: the tree's
 * subtree sizes and the splits' vertices (the level change passes the fields in locals). */
MC_ALWAYS_INLINE uint32_t index_record(const mc_chunk *list, unsigned shift, unsigned ib, uint32_t i)
{
    return mc_le_index(mc_chunk_record(list, shift, ib, i), ib);
}

/* The size of vertex v's subtree (its tree record). */
MC_ALWAYS_INLINE uint32_t subtree_size(const mc_pmesh *pm, uint32_t v)
{
    return index_record(pm->tree, pm->record_shift, pm->index_bytes, v);
}

/* The parent of v, the vertex of the split whose first face is f0, at a level where v is present and
 * its children are not: f0's corners 0 and 1 stand for v and its parent there (pmesh.h, corners). */
static uint32_t split_parent(const mc_pmesh_lod *lod, uint32_t v, uint32_t f0)
{
    const mc_pmesh *pm = lod->pm;
    const unsigned ib = pm->index_bytes;
    const uint8_t *r = mc_chunk_record(pm->corners, pm->record_shift, 3u * ib, f0);
    const uint32_t c0 = mc_le_index(r, ib);
    if (mc_pmesh_lod_vertex(lod, c0) != v) return mc_pmesh_lod_vertex(lod, c0);
    return mc_pmesh_lod_vertex(lod, mc_le_index(r + ib, ib));
}

/* anc[v .. v+n) = a */
static void anc_fill(mc_pmesh_lod *lod, uint32_t v, uint32_t n, uint32_t a)
{
    if (lod->pm->index_bytes == 2) {
        uint16_t *p = (uint16_t *)lod->anc + v;
        while (n--) *p++ = (uint16_t)a;
    } else {
        uint32_t *p = (uint32_t *)lod->anc + v;
        while (n--) *p++ = a;
    }
}

void mc_pmesh_lod_init(mc_pmesh_lod *lod, const mc_pmesh *pm, void *anc)
{
    lod->pm = pm;
    lod->anc = anc;
    lod->nbr = 0;
    lod->level = pm->base_vertices;
    lod->faces = pm->base_faces;
    /* depth-first order: the roots' subtrees tile 0 .. V-1, each root first in its own; only the
     * roots' tree records are read, so a mesh still arriving (stream.h) starts the same way */
    for (uint32_t v = 0, size; v < pm->vertices; v += size) {
        size = mc_pmesh_root_span(pm, v);
        anc_fill(lod, v, size, v);
    }
}

static void nbr_added(mc_pmesh_lod *lod, uint32_t f0);
static void nbr_removed(mc_pmesh_lod *lod, uint32_t f0, uint32_t f1);

uint32_t mc_pmesh_lod_set(mc_pmesh_lod *lod, uint32_t level)
{
    const mc_pmesh *pm = lod->pm;
    /* the fields in locals: the map's stores could alias the byte-wide ones */
    const unsigned ib = pm->index_bytes, shift = pm->record_shift;
    const mc_chunk *splits = pm->splits, *tree = pm->tree, *bits = pm->split_faces;
    const uint32_t base = pm->base_vertices;
    if (level < base) level = base;
    if (level > pm->vertices) level = pm->vertices;
    while (lod->level < level) {   /* split: the vertex's subtree now stands for it */
        const uint32_t s = lod->level - base, nf = mc_pmesh_split_faces_in(bits, shift, s);
        const uint32_t v = index_record(splits, shift, ib, s);
        anc_fill(lod, v, index_record(tree, shift, ib, v), v);
        lod->faces += nf;
        lod->level++;
        if (lod->nbr) nbr_added(lod, lod->faces - nf);
    }
    while (lod->level > level) {   /* collapse: the subtree goes back to the parent, which split
                                    * earlier and so is present */
        const uint32_t s = lod->level - 1u - base, nf = mc_pmesh_split_faces_in(bits, shift, s);
        const uint32_t v = index_record(splits, shift, ib, s);
        anc_fill(lod, v, index_record(tree, shift, ib, v), split_parent(lod, v, lod->faces - nf));
        lod->level--;
        if (lod->nbr) nbr_removed(lod, lod->faces - nf, lod->faces);
        lod->faces -= nf;
    }
    return level;
}

uint32_t mc_pmesh_lod_fit(mc_pmesh_lod *lod, uint32_t max_faces) { return mc_pmesh_lod_fit_to(lod, max_faces, lod->pm->vertices); }

uint32_t mc_pmesh_lod_fit_to(mc_pmesh_lod *lod, uint32_t max_faces, uint32_t max_level)
{
    const mc_pmesh *pm = lod->pm;
    if (max_level > pm->vertices) max_level = pm->vertices;
    if (lod->level > max_level) mc_pmesh_lod_set(lod, max_level);
    while (lod->faces > max_faces && lod->level > pm->base_vertices) mc_pmesh_lod_set(lod, lod->level - 1u);
    while (lod->level < max_level) {
        if (lod->faces + mc_pmesh_split_faces(pm, lod->level - pm->base_vertices) > max_faces) break;
        mc_pmesh_lod_set(lod, lod->level + 1u);
    }
    return lod->level;
}

uint32_t mc_pmesh_split_vertex(const mc_pmesh *pm, uint32_t s)
{
    return index_record(pm->splits, pm->record_shift, pm->index_bytes, s);
}

uint32_t mc_pmesh_root_span(const mc_pmesh *pm, uint32_t v)
{
    const uint32_t size = subtree_size(pm, v);
    return size < 1 || size > pm->vertices - v ? pm->vertices - v : size;   /* never with the generator's arrays */
}

void mc_pmesh_position(const mc_pmesh *pm, uint32_t v, int32_t xyz[3])
{
    mc_pmesh_position_at(mc_chunk_record(pm->positions, pm->record_shift, 6u, v), xyz);
}

/* Field k of record i of list (per half-edge fields a record, 2^shift records a chunk), a half-edge
 * id read hb bytes wide; hb is a constant where the walk calls it (one loop for each width), and the
 * walk keeps shift in a register. */
MC_ALWAYS_INLINE uint32_t half_field(const mc_chunk *list, unsigned shift, unsigned per, uint32_t i, unsigned k,
                                     unsigned hb)
{
    return mc_pmesh_half(mc_chunk_record(list, shift, per * hb, i) + k * hb, hb);
}

static uint32_t half_at(const mc_pmesh *pm, const mc_chunk *list, unsigned per, uint32_t i, unsigned k)
{
    return half_field(list, pm->record_shift, per, i, k, pm->half_bytes);
}

/* The walk with the opposite records hb bytes wide, a constant where called: one loop for each
 * width, a step a few instructions (at coarse levels most edges walk, several steps each). */
MC_ALWAYS_INLINE uint32_t opposite_walk(const mc_pmesh_lod *lod, uint32_t o, unsigned hb)
{
    const mc_pmesh *pm = lod->pm;
    const unsigned shift = pm->record_shift;
    /* bounded by F steps, so arrays not made by the generator cannot hang it */
    for (uint32_t steps = 0; o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) >= lod->faces; steps++) {
        const uint32_t j = MC_HALF_EDGE_INDEX(o);
        if (j == 0u || j == 3u || steps >= pm->faces) return MC_NO_HALF_EDGE;
        o = half_field(pm->opposite, shift, 3u, MC_HALF_FACE(o), 3u - j, hb);
    }
    return o;
}

uint32_t mc_pmesh_lod_opposite_walk(const mc_pmesh_lod *lod, uint32_t o)
{
    return lod->pm->half_bytes == 2 ? opposite_walk(lod, o, 2) : opposite_walk(lod, o, 4);
}

uint32_t mc_pmesh_edge(const mc_pmesh *pm, uint32_t i) { return half_at(pm, pm->edge_order, 1u, i, 0u); }

uint32_t mc_pmesh_opposite(const mc_pmesh *pm, uint32_t h)
{
    return half_at(pm, pm->opposite, 3u, MC_HALF_FACE(h), MC_HALF_EDGE_INDEX(h));
}

/* ---- the neighbour table (mc_pmesh_lod_neighbours) ---------------------------------------------- */

/* The table's entry for half-edge h. */
static uint32_t nbr_get(const mc_pmesh_lod *lod, uint32_t h)
{
    const unsigned hb = lod->pm->half_bytes;
    return mc_pmesh_half(MC_PMESH_NEIGHBOUR_AT(lod->nbr, h, hb), hb);
}

static void nbr_put(mc_pmesh_lod *lod, uint32_t h, uint32_t o)
{
    const unsigned hb = lod->pm->half_bytes;
    uint8_t *p = MC_PMESH_NEIGHBOUR_AT(lod->nbr, h, hb);
    p[0] = (uint8_t)o, p[1] = (uint8_t)(o >> 8);
    if (hb == 4) p[2] = (uint8_t)(o >> 16), p[3] = (uint8_t)(o >> 24);
}

/* Half-edge h's neighbour at the current level by definition: the walk from its stored opposite. */
static uint32_t nbr_walk(const mc_pmesh_lod *lod, uint32_t h)
{
    return mc_pmesh_lod_across(lod, mc_pmesh_opposite(lod->pm, h));
}

/* Faces f0 .. lod->faces-1 have just come: their entries by their walks, and the faces across them
 * now have them across (a level's neighbours pair up: the walk that now stops at a new face's edge is
 * the one from the face it found). Never past the table's F faces, whatever the splits' face counts
 * say (arrays not made by the generator: a forged stream). */
static void nbr_added(mc_pmesh_lod *lod, uint32_t f0)
{
    for (uint32_t f = f0; f < lod->faces && f < lod->pm->faces; f++)
        for (uint32_t k = 0; k < 3u; k++) {
            const uint32_t o = nbr_walk(lod, MC_HALF_EDGE(f, k));
            nbr_put(lod, MC_HALF_EDGE(f, k), o);
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f0) nbr_put(lod, o, MC_HALF_EDGE(f, k));
        }
}

/* Faces f0 .. f1-1, the last of the level, are about to go (lod->faces is f1): their entries to all
 * ones; across a removed face's merged edges 1 and 2 the faces found there now face each other (the
 * walk's step through a removed face), or, where one of them goes too, the other walks again. */
static void nbr_removed(mc_pmesh_lod *lod, uint32_t f0, uint32_t f1)
{
    uint32_t again[6], n = 0;   /* a split adds at most two faces */
    for (uint32_t f = f0; f < f1 && f < lod->pm->faces; f++) {
        /* across edge 0, the collapsed edge, lies the other face going (or nothing): else walk again */
        const uint32_t c = nbr_get(lod, MC_HALF_EDGE(f, 0));
        if (c != MC_NO_HALF_EDGE && MC_HALF_FACE(c) < f0 && n < 6u) again[n++] = c;
        const uint32_t a = nbr_get(lod, MC_HALF_EDGE(f, 1)), b = nbr_get(lod, MC_HALF_EDGE(f, 2));
        const int a_stays = a != MC_NO_HALF_EDGE && MC_HALF_FACE(a) < f0;
        const int b_stays = b != MC_NO_HALF_EDGE && MC_HALF_FACE(b) < f0;
        const int b_known = b == MC_NO_HALF_EDGE || b_stays, a_known = a == MC_NO_HALF_EDGE || a_stays;
        if (a_stays) { if (b_known) nbr_put(lod, a, b); else if (n < 6u) again[n++] = a; }
        if (b_stays) { if (a_known) nbr_put(lod, b, a); else if (n < 6u) again[n++] = b; }
        for (uint32_t k = 0; k < 3u; k++) nbr_put(lod, MC_HALF_EDGE(f, k), MC_NO_HALF_EDGE);
    }
    const uint32_t faces = lod->faces;
    lod->faces = f0;
    for (uint32_t i = 0; i < n; i++) nbr_put(lod, again[i], nbr_walk(lod, again[i]));
    lod->faces = faces;
}

void mc_pmesh_lod_neighbours(mc_pmesh_lod *lod, uint8_t *nbr)
{
    lod->nbr = nbr;
    if (!nbr) return;
    /* one store per entry, of a computed value (a constant fill could become a memset call) */
    for (uint32_t f = 0; f < lod->pm->faces; f++)
        for (uint32_t k = 0; k < 3u; k++)
            nbr_put(lod, MC_HALF_EDGE(f, k), f < lod->faces ? nbr_walk(lod, MC_HALF_EDGE(f, k)) : MC_NO_HALF_EDGE);
}
