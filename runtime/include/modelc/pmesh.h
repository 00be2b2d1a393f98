/* The progressive-mesh part of a baked model, and its level of detail.
 *
 * The generator decimates the mesh by half-edge collapses only (a removed vertex v goes into its
 * neighbour, its parent, and every vertex keeps its original position) and records the sequence in
 * reverse: a base mesh of V0 vertices and F0 faces, then V - V0 vertex splits, each bringing back one
 * vertex and the one or two faces its collapse removed. Level n (V0 <= n <= V) is the mesh after the
 * first n - V0 splits: its vertices are the base vertices and those of the first splits, its faces
 * are a prefix of the face array, F(n) long, faces stored in the order the splits create them.
 *
 * Every face stores the corners it has in the full mesh. At level n a corner stands for its nearest
 * ancestor present at n (ancestor: parent, parent's parent... in the forest of collapses; a vertex
 * is its own ancestor), because a half-edge collapse moves every face of the removed vertex to its
 * parent. Vertices are numbered in depth-first order of that forest (roots: the base vertices;
 * children in the order of their splits), so a vertex's descendants are the indices just after it,
 * [v, v + size(v)), and a split or collapse rewrites one contiguous run of the ancestor map.
 *
 * Promise (mc_pmesh_lod): the state of level n is the same bytes however n was reached (any sequence
 * of refinements and coarsenings, from any level); setting a level costs the sizes of the subtrees
 * of the vertices split or collapsed on the way, nothing else; the state is the caller's memory,
 * MC_PMESH_LOD_BYTES of it, with no heap. Every face of level n has three distinct corners, each a
 * vertex present at n, when the arrays are the generator's. Freestanding, no floating point.
 *
 * Data layout (every array chunked, chunk.h indexed records: each chunk but the last holds exactly
 * 2^record_shift records; multi-byte fields little-endian; an index field is index_bytes wide):
 *   positions  per vertex: x, y, z as uint16; the unit-cube coordinate is (q - 32768) / 65536
 *              (model.h: the cube the model was normalized into; +y up)
 *   tree       per vertex: its subtree size (its parent is not stored: a split's first face names
 *              it, below)
 *   splits     per split s = 0 .. V-V0-1: the index of the vertex it brings back
 *   split_faces per split, one bit: set when it adds two faces, clear when one (a border); a chunk
 *              holds the bits of 2^record_shift splits, split i of the chunk at bit i & 7 of its
 *              byte i >> 3, in (2^record_shift + 7) / 8 bytes
 *   corners    per face, in creation order: three corner indices, counter-clockwise seen from outside;
 *              a split's faces start at the split vertex or its parent (as they are at the split's
 *              level), so edge 0 is the edge its collapse removes and edges 1 and 2 the two it merges;
 *              so at any level where a split's vertex is present and its later splits are not made,
 *              its first face's corners 0 and 1 stand for that vertex and its parent, which is how a
 *              collapse finds the parent
 *   opposite   per face: for each edge k (corner k to corner k+1 mod 3), the half-edge across it in
 *              the full mesh, 4 g + j for edge j of face g, or all ones (a border); half_bytes wide
 *   edge_order per edge of the full mesh, one half-edge (of the face created first): borders first,
 *              then by decreasing angle between the normals of its two faces, where the silhouette
 *              search starts (mesh_lines.h)
 *   face_bits  per face: one byte, its shade and its edges' crease bits in the full mesh (mesh_face.h),
 *              which a face of any level whose corners are their own ancestors keeps (and an edge
 *              whose faces both do, across the stored opposite); may be null (then every shade and
 *              crease is worked out; a stream's reader works them out once its mesh is whole:
 *              mc_mesh_face_bits)
 *   groups     may be null (group_size 0): the full mesh's faces in groups of group_size (a power of
 *              two, at most 2^record_shift), near faces together; per group its box, the least and
 *              then the greatest x, y, z of its faces' corners as positions records hold them (12
 *              bytes), so that a pass can bound where a group lies in a view before visiting its faces
 *   group_faces per face, group after group: a face's index, group_bytes (2 or 3) wide; group g's
 *              faces are records g * group_size .. (g + 1) * group_size - 1 (the last group maybe
 *              fewer), in one chunk
 * and, not chunked, the palette (mesh_render.h): MC_MESH_SHADES greys, then the line colours.
 *
 * Neighbours at level n (mc_pmesh_lod_opposite): a face g missing at n was removed by the collapse
 * of its edge 0, which merged its edges 1 and 2 into one edge; so whatever lay across g's edge j
 * (1 or 2) at the full mesh now lies across the edge it had with g's edge 3 - j. Following that from
 * the full mesh's neighbour until a present face (or a border) is found gives the level's neighbour
 * exactly, with no state beyond the ancestor map.
 */
#ifndef MODELC_PMESH_H
#define MODELC_PMESH_H

#include <stdint.h>
#include "chunk.h"

/* The layout of the arrays below that this runtime reads. A bake's NAME_pmesh.c states the layout it
 * wrote and stops the build when the two differ, so that arrays from another modelc are never read
 * as this layout (layout 1 stored each vertex's parent and each split's face count as a byte). */
#define MC_PMESH_LAYOUT 2

typedef struct mc_pmesh {
    uint32_t vertices;           /* V: vertices of the full mesh */
    uint32_t base_vertices;      /* V0: vertices of the base mesh (>= 1) */
    uint32_t faces;              /* F: faces of the full mesh */
    uint32_t base_faces;         /* F0: faces of the base mesh */
    uint32_t edges;              /* E: edges of the full mesh */
    uint8_t index_bytes;         /* 2 (V <= 65535) or 4 */
    uint8_t half_bytes;          /* 2 (4 F + 3 < 65535) or 4: a half-edge id */
    uint8_t record_shift;        /* 2^record_shift records in each chunk but the last, every array */
    uint8_t closed;              /* 1: no border edge (every level then is closed: back faces are hidden);
                                    the line drawings rely on it: a stream's reader refuses a border then */
    uint16_t palette_size;       /* entries of palette */
    int16_t crease_cos;          /* Q14 cosine of the crease angle (mesh_lines.h) */
    const mc_chunk *positions;   /* V records of 6 bytes */
    const mc_chunk *tree;        /* V records of index_bytes: subtree sizes */
    const mc_chunk *splits;      /* V - V0 records of index_bytes: split vertices */
    const mc_chunk *corners;     /* F records of 3 * index_bytes: the faces */
    const mc_chunk *opposite;    /* F records of 3 * half_bytes */
    const mc_chunk *edge_order;  /* E records of half_bytes: the edges */
    const uint8_t *palette;      /* RGB triplets: the shades and line colours mesh drawings use */
    const mc_chunk *face_bits;   /* F records of 1 byte, or null */
    const mc_chunk *split_faces; /* V - V0 bits: the faces each split adds */
    const mc_chunk *groups;      /* ceil(F / group_size) records of 12 bytes, or null */
    const mc_chunk *group_faces; /* F records of group_bytes, or null */
    uint16_t group_size;         /* faces a group: a power of two; 0 with no groups */
    uint8_t group_bytes;         /* 2 (F <= 65536) or 3 */
} mc_pmesh;

/* A half-edge: edge k (corner k to corner k+1 mod 3) of face f is 4 f + k. */
#define MC_HALF_EDGE(f, k) (4u * (uint32_t)(f) + (uint32_t)(k))
#define MC_HALF_FACE(h) ((h) >> 2)
#define MC_HALF_EDGE_INDEX(h) ((h) & 3u)
#define MC_NO_HALF_EDGE 0xFFFFFFFFu

/* A half-edge id as the opposite and edge-order arrays (and a neighbour table) store it, hb (2 or 4)
 * bytes wide at r: all ones is MC_NO_HALF_EDGE. */
MC_ALWAYS_INLINE uint32_t mc_pmesh_half(const uint8_t *r, unsigned hb)
{
    if (hb == 4) return mc_le32(r);
    const uint32_t o = mc_le16(r);
    return o == 0xFFFFu ? MC_NO_HALF_EDGE : o;
}

/* A face index as group_faces stores it, gb (2 or 3) bytes wide at r. */
MC_ALWAYS_INLINE uint32_t mc_pmesh_group_face(const uint8_t *r, unsigned gb)
{
    return gb == 2 ? mc_le16(r) : mc_le16(r) | (uint32_t)r[2] << 16;
}

/* Where half-edge h's entry lies in a neighbour table (mc_pmesh_lod_neighbours) of hb-byte entries. */
#define MC_PMESH_NEIGHBOUR_AT(nbr, h, hb) ((nbr) + (3u * MC_HALF_FACE(h) + MC_HALF_EDGE_INDEX(h)) * (hb))

/* The level-of-detail state: level, face count and the ancestor map (in the caller's memory). */
typedef struct mc_pmesh_lod {
    const mc_pmesh *pm;
    uint32_t level;              /* vertices present: V0 .. V */
    uint32_t faces;              /* faces present: F(level) */
    void *anc;                   /* V entries, uint16_t when index_bytes is 2, else uint32_t */
    uint8_t *nbr;                /* null, or the level's neighbour table (mc_pmesh_lod_neighbours) */
} mc_pmesh_lod;

/* Bytes of ancestor map a state needs (the generator writes it for each bake as a define). */
#define MC_PMESH_LOD_BYTES(vertices, index_bytes) ((uint32_t)(vertices) * (uint32_t)(index_bytes))

/* Bytes of a neighbour table (mc_pmesh_lod_neighbours) for a part of F faces. */
#define MC_PMESH_NEIGHBOUR_BYTES(faces, half_bytes) (3u * (uint32_t)(faces) * (uint32_t)(half_bytes))

/* Starts at the base level: anc (MC_PMESH_LOD_BYTES, aligned for its entries) maps every vertex to
 * its root. Reads the base vertices' tree records only. No neighbour table. Work: V. */
void mc_pmesh_lod_init(mc_pmesh_lod *lod, const mc_pmesh *pm, void *anc);

/* Keeps the current level's neighbours in nbr (MC_PMESH_NEIGHBOUR_BYTES(pm->faces, pm->half_bytes)
 * bytes, the caller's; null drops the table): for each edge of each present face, the half-edge
 * across it at the level (mc_pmesh_lod_opposite's walk), laid out as the opposite array's records
 * (half_bytes wide, little-endian, all ones for none); all ones for every face not present. From
 * then on every level change keeps it so, and mc_pmesh_lod_opposite and the line drawings read it
 * instead of walking: at coarse levels most edges walk across removed faces, several steps each.
 * The table is a function of the level, as the ancestor map is (the same bytes however the level was
 * reached). Only once the opposite array is whole (a streamed mesh: stream.h). Work: a walk for each
 * edge of the level now; then a split or collapse adds walks for its faces' edges and for those of
 * the faces beside them, a few each. */
void mc_pmesh_lod_neighbours(mc_pmesh_lod *lod, uint8_t *nbr);

/* Refines or coarsens to level (clamped to V0 .. V); returns the level set. */
uint32_t mc_pmesh_lod_set(mc_pmesh_lod *lod, uint32_t level);

/* The finest level with at most max_faces faces (the base level when even it has more): a work
 * budget for the frame, in faces, that gives the same level on every machine. Moves one split at a
 * time from the current level, so the work is the change, as mc_pmesh_lod_set. Returns the level. */
uint32_t mc_pmesh_lod_fit(mc_pmesh_lod *lod, uint32_t max_faces);
/* mc_pmesh_lod_fit not above max_level (a streamed mesh: the splits that have come, stream.h); from
 * a current level above it, the finest within the budget at or below max_level. */
uint32_t mc_pmesh_lod_fit_to(mc_pmesh_lod *lod, uint32_t max_faces, uint32_t max_level);

/* The vertex present at the current level that vertex v (0 .. V-1) stands for. */
static inline uint32_t mc_pmesh_lod_vertex(const mc_pmesh_lod *lod, uint32_t v)
{
    return lod->pm->index_bytes == 2 ? ((const uint16_t *)lod->anc)[v] : ((const uint32_t *)lod->anc)[v];
}

/* The corners of face f (0 .. lod->faces-1) at the current level. Inline, and with the index width
 * tested once, not per byte: every drawing pass calls it for every face of the level. */
MC_ALWAYS_INLINE void mc_pmesh_lod_face(const mc_pmesh_lod *lod, uint32_t f, uint32_t corner[3])
{
    const mc_pmesh *pm = lod->pm;
    const uint8_t *r = mc_chunk_record(pm->corners, pm->record_shift, 3u * pm->index_bytes, f);
    if (pm->index_bytes == 2) {
        const uint16_t *anc = (const uint16_t *)lod->anc;
        corner[0] = anc[mc_le16(r)], corner[1] = anc[mc_le16(r + 2)], corner[2] = anc[mc_le16(r + 4)];
    } else {
        const uint32_t *anc = (const uint32_t *)lod->anc;
        corner[0] = anc[mc_le32(r)], corner[1] = anc[mc_le32(r + 4)], corner[2] = anc[mc_le32(r + 8)];
    }
}

/* 1 when the face whose corner record is r (index width ib) has the corners c at the current level
 * (their ancestors) that it has in the full mesh: each stored corner its own ancestor. Such a face
 * keeps what the full mesh gives it (its face_bits). For a pass that has mapped the corners already. */
MC_ALWAYS_INLINE int mc_pmesh_corners_as_full(const uint8_t *r, unsigned ib, const uint32_t c[3])
{
    if (ib == 2) return ((mc_le16(r) ^ c[0]) | (mc_le16(r + 2) ^ c[1]) | (mc_le16(r + 4) ^ c[2])) == 0;
    return ((mc_le32(r) ^ c[0]) | (mc_le32(r + 4) ^ c[1]) | (mc_le32(r + 8) ^ c[2])) == 0;
}

/* mc_pmesh_corners_as_full of face f (0 .. lod->faces-1) at the current level. */
MC_ALWAYS_INLINE int mc_pmesh_lod_face_as_full(const mc_pmesh_lod *lod, uint32_t f)
{
    const mc_pmesh *pm = lod->pm;
    uint32_t c[3];
    mc_pmesh_lod_face(lod, f, c);
    return mc_pmesh_corners_as_full(mc_chunk_record(pm->corners, pm->record_shift, 3u * pm->index_bytes, f),
                                    pm->index_bytes, c);
}

/* mc_pmesh_lod_opposite's walk across removed faces from o, the stored opposite of a half-edge, whose
 * face is not present (out of line: most edges of a level need none). */
uint32_t mc_pmesh_lod_opposite_walk(const mc_pmesh_lod *lod, uint32_t o);

/* The half-edge across a half-edge of a present face at the current level, from o, the opposite the
 * arrays store for it (MC_NO_HALF_EDGE for a border): o itself when its face is present, else the
 * walk. For passes that read the stored opposites in order. */
MC_ALWAYS_INLINE uint32_t mc_pmesh_lod_across(const mc_pmesh_lod *lod, uint32_t o)
{
    if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) < lod->faces) return o;
    return mc_pmesh_lod_opposite_walk(lod, o);
}

/* The half-edge across half-edge h (MC_HALF_EDGE(f, k), f < lod->faces) at the current level, or
 * MC_NO_HALF_EDGE where edge k of face f is a border there. Work: the faces removed across that edge
 * between the current level and the full mesh, at most; usually none or one; none with a neighbour
 * table. Inline: the stored opposite (or the table's entry), when its face is present. */
MC_ALWAYS_INLINE uint32_t mc_pmesh_lod_opposite(const mc_pmesh_lod *lod, uint32_t h)
{
    const mc_pmesh *pm = lod->pm;
    const unsigned hb = pm->half_bytes;
    const uint8_t *r = lod->nbr ? MC_PMESH_NEIGHBOUR_AT(lod->nbr, h, hb)
                                : mc_chunk_record(pm->opposite, pm->record_shift, 3u * hb, MC_HALF_FACE(h)) +
                                      MC_HALF_EDGE_INDEX(h) * hb;
    return mc_pmesh_lod_across(lod, mc_pmesh_half(r, hb));
}

/* Edge i (0 .. E-1) of the edge order: a half-edge of the full mesh (its face may be missing at the
 * current level). */
uint32_t mc_pmesh_edge(const mc_pmesh *pm, uint32_t i);

/* The vertex split s (0 .. V-V0-1) brings back. */
uint32_t mc_pmesh_split_vertex(const mc_pmesh *pm, uint32_t s);

/* The faces split s adds, 1 or 2, from split_faces bits chunked 2^shift to a chunk. */
MC_ALWAYS_INLINE uint32_t mc_pmesh_split_faces_in(const mc_chunk *bits, unsigned shift, uint32_t s)
{
    const uint32_t i = s & ((UINT32_C(1) << shift) - 1u);
    return 1u + ((bits[s >> shift].data[i >> 3] >> (i & 7u)) & 1u);
}

/* The faces split s (0 .. V-V0-1) adds: 1 or 2 (its split_faces bit). */
MC_ALWAYS_INLINE uint32_t mc_pmesh_split_faces(const mc_pmesh *pm, uint32_t s)
{
    return mc_pmesh_split_faces_in(pm->split_faces, pm->record_shift, s);
}

/* The vertices of root v's subtree, v .. v + n - 1 (its descendants follow it in depth-first order):
 * the roots are 0 and each root plus its n. n is at least 1 and at most V - v whatever the arrays
 * hold. */
uint32_t mc_pmesh_root_span(const mc_pmesh *pm, uint32_t v);

/* The position a positions record at r holds: unit-cube coordinates in Q16 (q - 32768), -32768 ..
 * 32767. */
MC_ALWAYS_INLINE void mc_pmesh_position_at(const uint8_t *r, int32_t xyz[3])
{
    xyz[0] = (int32_t)mc_le16(r) - 32768;
    xyz[1] = (int32_t)mc_le16(r + 2) - 32768;
    xyz[2] = (int32_t)mc_le16(r + 4) - 32768;
}

/* Vertex v's position (mc_pmesh_position_at of its record). */
void mc_pmesh_position(const mc_pmesh *pm, uint32_t v, int32_t xyz[3]);

/* The half-edge across half-edge h in the full mesh (the opposite array's entry; MC_NO_HALF_EDGE
 * for a border), whether or not h's face is present at a level: mc_pmesh_lod_across of it is the
 * level's neighbour, found by the walk. */
uint32_t mc_pmesh_opposite(const mc_pmesh *pm, uint32_t h);

#endif
