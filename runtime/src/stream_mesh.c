/* A version-2 or -3 stream's mesh records (modelc/stream.h): the progressive mesh, base first, then its
 * splits, then its adjacency, placed into pmesh.h's arrays in the caller's buffer. */
#include "stream_mesh.h"
#include "modelc/mesh_face.h"

#define SHIFT 30   /* one chunk per array: every index fits below 2^30 (checked with the header) */
#define LIMIT (UINT32_C(1) << SHIFT)

static uint32_t le(const uint8_t *p, unsigned bytes) { return mc_le_index(p, bytes); }

static void copy(uint8_t *to, const uint8_t *from, uint32_t n)
{
    while (n--) *to++ = *from++;
}

/* The mesh arrays in the buffer, after the stream's own bytes. */
static uint8_t *area(const mc_stream *s) { return s->buf + ((s->total + 3u) & ~3u); }



static int mesh_header(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at_record)
{
    mc_pmesh *pm = &s->pmesh;
    if (n < 28) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at_record);
    const uint32_t V = le(p, 4), V0 = le(p + 4, 4), F = le(p + 8, 4), F0 = le(p + 12, 4), E = le(p + 16, 4);
    const unsigned ib = p[20], hb = p[21], closed = p[22], palette = le(p + 26, 2);
    if (n != 28u + 3u * palette) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at_record);
    if (V >= LIMIT || F >= LIMIT || E >= LIMIT || V0 < 1 || V0 > V || F0 > F || F < 1 || E < 1 ||
        F - F0 < V - V0 || F - F0 > 2u * (V - V0) || ib != (V <= 65535u ? 2u : 4u) ||
        hb != (4u * F + 3u < 65535u ? 2u : 4u) || closed > 1 || p[23] != 0 || palette < 1 || palette > 256)
        return mc_stream_fail(s, MC_STREAM_ERR_MESH, at_record + 8);
    const uint64_t need = (uint64_t)((s->total + 3u) & ~3u) + 6u * (uint64_t)V + ib * (uint64_t)V +
                          ib * (uint64_t)(V - V0) + 3u * ib * (uint64_t)F + F + (V - V0 + 7u) / 8u +
                          (s->version == 3 ? 24u * (uint64_t)F + 12u * (uint64_t)V + 4u : 0u);   /* MC_STREAM_PACKED_BYTES */
    if (need > s->cap) return mc_stream_fail(s, MC_STREAM_ERR_SIZE, at_record + 8);
    pm->vertices = V, pm->base_vertices = V0, pm->faces = F, pm->base_faces = F0, pm->edges = E;
    pm->index_bytes = (uint8_t)ib, pm->half_bytes = (uint8_t)hb, pm->record_shift = SHIFT;
    pm->closed = (uint8_t)closed;
    pm->crease_cos = (int16_t)le(p + 24, 2);
    pm->palette_size = (uint16_t)palette;
    pm->palette = p + 28;
    /* in the buffer: positions, tree, splits, corners, face bits, split faces; the adjacency stays
     * where it lies */
    const uint32_t bytes[8] = {6u * V, ib * V, ib * (V - V0), 3u * ib * F, 0, 0, F, (V - V0 + 7u) / 8u};
    uint8_t *a = area(s);
    for (unsigned k = 0; k < 8; k++) {
        s->mesh_chunks[k][0].data = k < 4 || k >= 6 ? a : 0;   /* (the adjacency's: where it lies, later) */
        s->mesh_chunks[k][0].size = bytes[k];
        s->mesh_chunks[k][1].data = 0;
        s->mesh_chunks[k][1].size = 0;
        a += bytes[k];
    }
    /* absent vertices have subtree size 0: what the base and the splits check against */
    for (uint8_t *z = area(s); z < a; z++) *z = 0;
    if (s->version == 3) mc_stream_packed_start(s, a);
    pm->positions = s->mesh_chunks[0], pm->tree = s->mesh_chunks[1], pm->splits = s->mesh_chunks[2];
    pm->corners = s->mesh_chunks[3], pm->opposite = 0, pm->edge_order = 0, pm->face_bits = 0;
    pm->split_faces = s->mesh_chunks[7];
    s->mesh_state = 1;
    return MC_STREAM_OK;
}

/* Three corners at p into the corner array at face f; each must be a vertex of the mesh. */
static int corners(mc_stream *s, const uint8_t *p, uint32_t f, uint32_t at)
{
    const unsigned ib = s->pmesh.index_bytes;
    for (unsigned k = 0; k < 3; k++)
        if (le(p + k * ib, ib) >= s->pmesh.vertices) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at + k * ib);
    copy(mc_stream_array(s, 3) + f * 3u * ib, p, 3u * ib);
    return MC_STREAM_OK;
}

static int base(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at)
{
    const mc_pmesh *pm = &s->pmesh;
    const unsigned ib = pm->index_bytes, per = 2u * ib + 6u;
    if ((uint64_t)pm->base_vertices * per + 3u * ib * (uint64_t)pm->base_faces != n)
        return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at - 8);
    const uint8_t *roots = p;
    uint32_t next = 0;   /* the roots' subtrees tile 0 .. V-1 in order */
    for (uint32_t i = 0; i < pm->base_vertices; i++, p += per, at += per) {
        const uint32_t v = le(p, ib), size = le(p + ib + 6, ib);
        if (v != next || size < 1 || size > pm->vertices - v) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at);
        copy(mc_stream_array(s, 0) + 6u * v, p + ib, 6);
        mc_stream_put(mc_stream_tree(s, v), size, ib);
        next = v + size;
    }
    if (next != pm->vertices) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at - per);
    for (uint32_t f = 0; f < pm->base_faces; f++, p += 3u * ib, at += 3u * ib)
        if (corners(s, p, f, at)) return s->error;
    s->faces_read = pm->base_faces;
    if (s->version == 3) mc_stream_packed_base(s, roots, per);
    s->mesh_state = 2;
    return MC_STREAM_OK;
}

/* A batch of splits. What the level of detail indexes with is checked: the vertex is new, its parent
 * present (so it split earlier), the vertex's subtree lies inside the parent's, every corner is a
 * vertex; then a split moves only runs of the ancestor map inside 0 .. V-1. And what a collapse reads
 * the parent from (pmesh.h): the first face's corners 0 and 1 lie one in the vertex's subtree, the
 * other in the parent's outside it. */
static int splits(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at)
{
    const mc_pmesh *pm = &s->pmesh;
    const unsigned ib = pm->index_bytes, per = 3u * ib + 7u;
    const uint32_t S = pm->vertices - pm->base_vertices;
    if (n < 8) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at - 8);
    const uint32_t first = le(p, 4), k = le(p + 4, 4);
    if (first != s->splits_read || k < 1 || k > S - first) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at);
    const uint8_t *end = p + n;
    p += 8, at += 8;
    uint32_t faces = s->faces_read;
    for (uint32_t i = 0; i < k; i++) {
        if ((uint32_t)(end - p) < per) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at);
        const uint32_t v = le(p, ib), nf = p[ib], parent = le(p + ib + 7, ib), size = le(p + 2u * ib + 7, ib);
        if (v >= pm->vertices || parent >= pm->vertices || nf < 1 || nf > 2 || nf > pm->faces - faces)
            return mc_stream_fail(s, MC_STREAM_ERR_MESH, at);
        const uint32_t psize = le(mc_stream_tree(s, parent), ib);
        if (le(mc_stream_tree(s, v), ib) != 0 || psize == 0 || v <= parent || v - parent >= psize || size < 1 ||
            size > psize - (v - parent))
            return mc_stream_fail(s, MC_STREAM_ERR_MESH, at);
        if ((uint32_t)(end - p) - per < 3u * ib * nf) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at);
        mc_stream_put_split(s, first + i, v, nf);
        copy(mc_stream_array(s, 0) + 6u * v, p + ib + 1, 6);
        mc_stream_put(mc_stream_tree(s, v), size, ib);
        p += per, at += per;
        const uint32_t c0 = le(p, ib), c1 = le(p + ib, ib);
        const int v0 = c0 - v < size, v1 = c1 - v < size, p0 = c0 - parent < psize, p1 = c1 - parent < psize;
        if (!((v0 && p1 && !v1) || (v1 && p0 && !v0))) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at);
        for (uint32_t j = 0; j < nf; j++, faces++, p += 3u * ib, at += 3u * ib)
            if (corners(s, p, faces, at)) return s->error;
    }
    if (p != end) return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at);
    s->splits_read += k;
    s->faces_read = faces;
    return MC_STREAM_OK;
}

/* The adjacency, read where it lies: every opposite a half-edge of the mesh whose own opposite is the
 * one it was read for (or a border, which a part said to be closed has none of: the line drawings
 * read a closed part's neighbours without asking), every edge of the order a half-edge of the mesh. */
static int adjacency(mc_stream *s, const uint8_t *p, uint32_t n, uint32_t at)
{
    const mc_pmesh *pm = &s->pmesh;
    const unsigned hb = pm->half_bytes;
    if (s->splits_read != pm->vertices - pm->base_vertices || s->faces_read != pm->faces ||
        (uint64_t)pm->faces * 3u * hb + (uint64_t)pm->edges * hb != n)
        return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at - 8);
    return mc_stream_adjacency(s, p, p + 3u * hb * pm->faces, at, 1);
}

int mc_stream_adjacency(mc_stream *s, const uint8_t *opposite, const uint8_t *order, uint32_t at, int in_place)
{
    mc_pmesh *pm = &s->pmesh;
    const unsigned hb = pm->half_bytes;
    const uint32_t none = hb == 2 ? 0xFFFFu : MC_NO_HALF_EDGE;
    for (uint32_t f = 0; f < pm->faces; f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t i = 3u * f + k, o = le(opposite + i * hb, hb);
            if (o == none && pm->closed) return mc_stream_fail(s, MC_STREAM_ERR_MESH, at + (in_place ? i * hb : 0u));
            if (o == none) continue;
            const uint32_t g = MC_HALF_FACE(o), j = MC_HALF_EDGE_INDEX(o);
            if (g >= pm->faces || j > 2 || le(opposite + (3u * g + j) * hb, hb) != MC_HALF_EDGE(f, k))
                return mc_stream_fail(s, MC_STREAM_ERR_MESH, at + (in_place ? i * hb : 0u));
        }
    for (uint32_t e = 0; e < pm->edges; e++) {
        const uint32_t h = le(order + e * hb, hb);
        if (h == none || MC_HALF_FACE(h) >= pm->faces || MC_HALF_EDGE_INDEX(h) > 2)
            return mc_stream_fail(s, MC_STREAM_ERR_MESH, at + (in_place ? 3u * hb * pm->faces + e * hb : 0u));
    }
    s->mesh_chunks[4][0].data = opposite, s->mesh_chunks[4][0].size = 3u * hb * pm->faces;
    s->mesh_chunks[5][0].data = order, s->mesh_chunks[5][0].size = hb * pm->edges;
    pm->opposite = s->mesh_chunks[4];
    pm->edge_order = s->mesh_chunks[5];
    /* the mesh is whole: its faces' shades and crease bits, as a bake stores them */
    mc_mesh_face_bits(pm, (uint8_t *)s->mesh_chunks[6][0].data);
    pm->face_bits = s->mesh_chunks[6];
    s->mesh_state = 3;
    return MC_STREAM_OK;
}

int mc_stream_mesh_record(mc_stream *s, unsigned kind, uint32_t at, uint32_t n, uint32_t at_record)
{
    const uint8_t *p = s->buf + at;
    const int in_order = s->has_mesh && s->palette_at != 0;   /* the order among themselves: below */
    if (in_order && kind == MC_STREAM_KIND_MESH && s->mesh_state == 0) return mesh_header(s, p, n, at_record);
    if (in_order && kind == MC_STREAM_KIND_BASE && s->mesh_state == 1) return base(s, p, n, at);
    if (in_order && kind == MC_STREAM_KIND_SPLITS && s->mesh_state == 2 && s->version == 2) return splits(s, p, n, at);
    if (in_order && kind == MC_STREAM_KIND_PACKED && s->mesh_state == 2 && s->version == 3)
        return mc_stream_packed_splits(s, p, n, at);
    if (in_order && kind == MC_STREAM_KIND_ADJACENCY && s->mesh_state == 2 && s->version == 2) return adjacency(s, p, n, at);
    if (in_order && kind == MC_STREAM_KIND_PACKED_ADJACENCY && s->mesh_state == 2 && s->version == 3)
        return mc_stream_packed_adjacency(s, p, n, at);
    return mc_stream_fail(s, MC_STREAM_ERR_RECORD, at_record);
}

const mc_pmesh *mc_stream_pmesh(const mc_stream *s) { return s && s->mesh_state >= 2 ? &s->pmesh : 0; }

uint32_t mc_stream_mesh_level(const mc_stream *s)
{
    return s && s->mesh_state >= 2 ? s->pmesh.base_vertices + s->splits_read : 0;
}
