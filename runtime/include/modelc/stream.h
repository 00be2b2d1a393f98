/* Streamed bakes: a bake as one binary stream, coarse first, and its reader.
 *
 * Promise: mc_stream_feed takes a stream in pieces of any size (bytes as they arrive from a file, a
 * pipe, a socket, a fetch or a UART) into the caller's buffer, checks every complete record as it
 * lands, and mc_stream_octree then describes the deepest level d whose records 0..d are all complete
 * and checked: an mc_octree of depth d that the point renderer draws exactly as it draws the baked
 * octree at depth d (the same masks, colours, palette and cones, so the same pixels). Everything the
 * renderer relies on is checked before a level counts, with a CRC-32 on each record besides: node
 * counts against the masks above, no empty mask, colour indices within the palette, each cone's
 * subtree counts against the masks below it (they come with the level three below theirs).
 * A version-2 stream then carries the bake's progressive mesh (pmesh.h), base mesh first, then its
 * splits in order: mc_stream_pmesh describes it as soon as the base has come, and every level from
 * the base to mc_stream_mesh_level is the baked mesh's level, vertex for vertex and face for face
 * (so the shaded style draws the same pixels as the bake at that --lod); the line styles also need
 * the adjacency, which comes last, and with it the reader works out the face bits the bake stores
 * (mesh_face.h mc_mesh_face_bits: the same bytes), so the whole mesh draws as the bake does. The
 * mesh's records are checked for what the level of detail and the renderers index with (every
 * index in range, a split's vertex new and inside its parent's subtree, the parent already present,
 * its first face starting at the vertex and the parent, face counts, opposites that pair up), so a forged stream can draw wrong but never out of bounds.
 * A stream that turns out truncated, corrupted, of another version or larger than the buffer stops
 * the reader with an error (sticky, with the byte offset where it was found); what was drawable
 * before stays drawable, so a front end keeps its last good frame. No heap: the caller owns the
 * buffer (sized at bake time: budget.json "stream", MC_NAME_STREAM_BYTES: the stream, and for a
 * mesh its arrays, MC_STREAM_MESH_BYTES, after it) and the mc_stream. Freestanding; work
 * proportional to the bytes fed.
 *
 * A version-3 stream is a version-2 stream whose splits come packed (kind 8 instead of 6, about a
 * third of the bytes) and whose adjacency is the edge order alone (kind 9 instead of 7): the reader
 * decodes the splits into the same arrays, keeping the level's mesh in the buffer while it does
 * (MC_STREAM_PACKED_BYTES more), finds the opposites from the full mesh it built and writes them
 * and the edge order over that state; every level, and the adjacency, are the same as version 2's.
 *
 * The format, versions 1, 2 and 3 (all integers little-endian):
 *   header, 20 bytes:  "mcs" 0x1A | u16 version (1, 2 or 3) | u8 depth D (1..MC_MAX_DEPTH) |
 *                      u8 flags (version 1: 0; versions 2 and 3: 1, a mesh part follows the octree) |
 *                      u16 palette entries P (1..256) | u16 0 | u32 total bytes of the stream |
 *                      u32 CRC-32 of the 16 bytes before it
 *   then records:      u8 kind | u8 level | u16 0 | u32 payload bytes n | n bytes | u32 CRC-32 of the
 *                      8 + n bytes before it
 *     kind 1, palette: P RGB triplets; first, and once
 *     kind 2, level l: levels 0, 1, ..., D in order: u32 nodes N | N child masks (l < D) |
 *                      N palette indices (l >= 1 and P > 1) | the 7-byte normal cones of level l-3's
 *                      nodes (octree.h), the first depth that culls with them, for l-3 >= 1 where the
 *                      bake has cones (told apart by n)
 *   version 2 only, after the palette, in this order among themselves but interleaved with the
 *   levels (level 0; ib, hb: the index and half-edge widths):
 *     kind 4, mesh:    u32 V, V0, F, F0, E | u8 ib (2: V <= 65535, else 4) | u8 hb (2: 4 F + 3 <
 *                      65535, else 4) | u8 closed (0, 1) | u8 0 | i16 crease cosine (Q14) |
 *                      u16 palette entries Pm (1..256) | Pm RGB triplets (mesh_render.h)
 *     kind 5, base:    per base vertex, in index order: u[ib] index (the first 0, each next the
 *                      one before plus its subtree size) | 6-byte position | u[ib] subtree size
 *                      (the sizes add up to V); then F0 faces of 3 u[ib] corners
 *     kind 6, splits:  u32 first split (the splits before it all read) | u32 count k >= 1 | per
 *                      split: u[ib] vertex | u8 faces it adds (1, 2) | 6-byte position |
 *                      u[ib] parent | u[ib] subtree size | its faces' 3 u[ib] corners each;
 *                      until all V - V0 splits and F faces have come
 *     kind 7, adjacency: F records of 3 u[hb] opposites, then E u[hb] half-edges: the edge order
 *   version 3 only, kinds 8 and 9 in place of kinds 6 and 7:
 *     kind 8, packed splits: u32 first split | u32 count k >= 1 | u8 order g (0..16) | bits, most
 *                      significant first in each byte, the last byte's unused bits zero. Per split,
 *                      with the level before it (the base and the splits before it) known:
 *                      parent p: width(V) bits (a vertex present at the level); the split vertex is
 *                      then p's next child in depth-first order, p + 1 plus the subtree sizes of p's
 *                      children split before; subtree size: Exp-Golomb order 0 of size - 1; faces it
 *                      adds: 1 bit (0: one, 1: two); per face: 1 bit (0: its corners at the split's
 *                      level are v, p, x; 1: p, v, x), x's rank among p's neighbours at the level
 *                      before (the distinct vertices sharing a face with p, in index order):
 *                      width(their number) bits, then each corner's full-mesh vertex as its offset in
 *                      the subtree of its vertex at the split's level: width(that size) bits; the
 *                      position, each axis: Exp-Golomb order g of the zigzag (0, -1, 1, -2: 0, 1, 2,
 *                      3) of its difference to the rounded mean (sum + n / 2) / n of the split
 *                      vertex's n neighbours after the split. width(n): the bits of an offset below
 *                      n, 0 for n <= 1. Exp-Golomb order g of u: u + 2^g has b + 1 bits; b - g zeros,
 *                      then those b + 1 bits.
 *     kind 9, packed adjacency (in place of kind 7, after the last split): the edge order, each
 *                      half-edge 4 f + k as 3 f + k in width(3 F) bits, most significant first, the
 *                      last byte's unused bits zero. The opposites are not sent: each half-edge's is
 *                      the half-edge of the full mesh that runs back between the same two vertices
 *                      (none: a border), which the generator checks holds before it packs.
 *   kind 3, end:       no payload; last, and the stream's total is where it ends
 * The mesh records hold pmesh.h's arrays in split order: the base and each batch of splits bring
 * their vertices' position and subtree size (placed at their indices in the buffer's mesh arrays)
 * and their faces (appended); a split's parent is checked as it comes and not kept, since the
 * arrays imply it (pmesh.h). A prefix that holds the header, the palette and the levels 0..d is a
 * drawable octree of depth d: each level costs about four times the one above it, so the first
 * picture comes after a small part of the bytes. The generator (--emit stream, gen/emit_stream.cpp;
 * version 2 for bakes --as both) puts the mesh header and base right after the palette and then
 * merges the levels with the batches of splits, each next record from the part that has had fewer
 * bytes so far, so both parts' pictures refine from the first bytes; the adjacency comes last.
 */
#ifndef MODELC_STREAM_H
#define MODELC_STREAM_H

#include <stdint.h>
#include "config.h"
#include "octree.h"
#include "pmesh.h"

#define MC_STREAM_VERSION 3   /* the newest this reader takes (it takes 1 and 2 too) */
#define MC_STREAM_HEADER_BYTES 20
#define MC_STREAM_RECORD_BYTES 12   /* a record's own bytes around its payload */

/* A version-2 stream's mesh arrays in the buffer, after the stream's bytes (rounded up to 4):
 * positions, tree records, splits and corners of a mesh of V vertices (V0 in the base), F faces,
 * index width ib, the face bits (pmesh.h), worked out once the adjacency has come, and the splits'
 * face-count bits. The adjacency is read where it lies in the stream. */
#define MC_STREAM_MESH_BYTES(V, V0, F, ib) \
    (6u * (uint32_t)(V) + (ib) * (uint32_t)(V) + (ib) * ((uint32_t)(V) - (uint32_t)(V0)) + \
     3u * (ib) * (uint32_t)(F) + (uint32_t)(F) + ((uint32_t)(V) - (uint32_t)(V0) + 7u) / 8u)

/* What a version-3 stream's reader needs in the buffer after the mesh arrays to decode packed
 * splits: per corner of the F faces its vertex at the decoded level and the next corner of that
 * vertex; per vertex of V its first corner, its next child's index and a mark (4 bytes each, from a
 * multiple of 4). The opposites and the edge order are then written over the first two. */
#define MC_STREAM_PACKED_BYTES(V, F) (24u * (uint32_t)(F) + 12u * (uint32_t)(V) + 4u)

enum {
    MC_STREAM_OK = 0,
    MC_STREAM_ERR_MAGIC = -1,      /* not a modelc stream */
    MC_STREAM_ERR_VERSION = -2,    /* a version this reader does not know */
    MC_STREAM_ERR_HEADER = -3,     /* a header field out of range */
    MC_STREAM_ERR_SIZE = -4,       /* larger than the buffer */
    MC_STREAM_ERR_CRC = -5,        /* a header or record whose CRC-32 does not match */
    MC_STREAM_ERR_RECORD = -6,     /* a record of the wrong kind, order or length */
    MC_STREAM_ERR_NODES = -7,      /* a level's node count not what the masks above it say */
    MC_STREAM_ERR_VALUE = -8,      /* an empty mask or a colour outside the palette */
    MC_STREAM_ERR_CONE = -9,       /* a cone's subtree counts not what the masks below it say */
    MC_STREAM_ERR_TRAILING = -10,  /* bytes after the end record */
    MC_STREAM_ERR_TRUNCATED = -11, /* the input ended before the end record (mc_stream_end) */
    MC_STREAM_ERR_ARG = -12,       /* a NULL pointer */
    MC_STREAM_ERR_MESH = -13       /* a mesh record whose indices or counts do not fit the mesh */
};

typedef struct mc_stream {
    uint8_t *buf;                  /* the caller's buffer: the stream's bytes as they came */
    uint32_t cap, len;             /* its size, the bytes in it */
    uint32_t at;                   /* the first byte not yet checked */
    uint32_t total;                /* the header's total (0 until the header is read) */
    int error;                     /* MC_STREAM_OK or the first error (sticky) */
    uint32_t error_at;             /* the byte offset where it was found */
    int ended;                     /* the end record was read */
    unsigned levels_read;          /* complete, checked levels: 0..levels_read-1 */
    uint8_t depth;                 /* D of the header */
    uint16_t palette_size;
    /* where each level's arrays lie in buf (offsets, 0 = none), and its node count */
    uint32_t nodes[MC_MAX_DEPTH + 1];
    uint32_t masks_at[MC_MAX_DEPTH + 1], colors_at[MC_MAX_DEPTH + 1], cones_at[MC_MAX_DEPTH + 1];
    uint32_t palette_at;
    /* the descriptor of the drawable prefix, rebuilt whenever a level completes */
    mc_octree octree;
    mc_octree_level level[MC_MAX_DEPTH + 1];
    mc_chunk chunks[MC_MAX_DEPTH + 1][3][2];   /* per level: masks, colours, cones; one chunk each */
    /* the mesh part (version 2): its descriptor, once its header has come; one chunk per array */
    uint8_t version, has_mesh;
    uint8_t mesh_state;            /* 0 none yet, 1 header, 2 base, 3 adjacency (complete) */
    uint32_t splits_read, faces_read;
    mc_pmesh pmesh;
    mc_chunk mesh_chunks[8][2];    /* positions, tree, splits, corners, opposite, edge order, face bits,
                                      split faces */
    /* a version-3 stream's decoder (stream_packed.c), in the buffer after the mesh arrays: per
     * corner its vertex at the decoded level and the next corner of that vertex; per vertex its
     * first corner, its next child, a mark; the last mark given */
    uint32_t *pk_level, *pk_next, *pk_head, *pk_slot, *pk_stamp;
    uint32_t pk_now;
} mc_stream;

/* Starts reading a stream into buf (cap bytes). */
void mc_stream_init(mc_stream *s, uint8_t *buf, uint32_t cap);

/* Appends n bytes and checks every record they complete. Returns MC_STREAM_OK or the error that
 * stopped the stream (then and on every later call; the drawable prefix is kept). */
int mc_stream_feed(mc_stream *s, const uint8_t *data, uint32_t n);

/* The input has ended: MC_STREAM_OK when the stream was complete, else its error
 * (MC_STREAM_ERR_TRUNCATED when nothing else was wrong). */
int mc_stream_end(mc_stream *s);

/* The deepest drawable level (0: nothing drawable yet) and its octree (NULL then). The octree stays
 * valid while s and its buffer live; feeding more may deepen it. */
unsigned mc_stream_depth(const mc_stream *s);
const mc_octree *mc_stream_octree(const mc_stream *s);

/* A version-2 stream's mesh part: NULL before its base has come. Its levels from the base to
 * mc_stream_mesh_level are drawable (mc_pmesh_lod_init, then mc_pmesh_lod_set up to that level: the
 * descriptor's vertices is the full mesh's, so a front end clamps); its opposite, edge_order and
 * face_bits are NULL until the adjacency has come, and the line styles need the first two. Valid
 * while s and its buffer live; feeding more raises the level. */
const mc_pmesh *mc_stream_pmesh(const mc_stream *s);
uint32_t mc_stream_mesh_level(const mc_stream *s);

/* A short name of an MC_STREAM_* code ("ok", "crc", ...). */
const char *mc_stream_error_name(int error);

/* CRC-32 (ISO-HDLC, as zlib's crc32) of n bytes, continuing from crc (0 to start). */
uint32_t mc_stream_crc32(uint32_t crc, const uint8_t *p, uint32_t n);

#endif
