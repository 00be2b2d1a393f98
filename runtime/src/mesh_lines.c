/* Line drawings of a progressive mesh: see modelc/mesh_lines.h.
 * Long because it is one drawing's passes (every face's facing, every edge's kind and line, and the
 * sparse way's face pass) over the same inline readers of a face's corners, facing and crease bits,
 * each pass made once per index width and corner mode from one body (constants where called): apart,
 * those readers would move to a header that every part includes, and the passes' specialisations
 * would no longer be read side by side. */
#include "modelc/mesh_lines.h"
#include "modelc/bits.h"   /* mc_ctz */
#include "mesh_creases.h"

/* Twice the signed screen area of a projected face, in (1/16 pixel)^2; below 0: front-facing. */
MC_ALWAYS_INLINE int64_t area2(const mc_raster_vertex v[3])
{
    return (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y);
}

int mc_mesh_front(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f)
{
    int32_t p[3][3];
    mc_raster_vertex v[3];
    if (mc_mesh_face(lod, x, f, p, v)) return mc_mesh_face_front(x, (const int32_t(*)[3])p);
    return area2(v) < 0;
}

void mc_mesh_facing(const mc_pmesh_lod *lod, const mc_xform *x, uint8_t *facing)
{
    for (uint32_t i = 0; i < MC_MESH_FACING_BYTES(lod->faces); i++) facing[i] = 0;
    for (uint32_t f = 0; f < lod->faces; f++)
        if (mc_mesh_front(lod, x, f)) facing[f >> 3] |= (uint8_t)(1u << (f & 7u));
}

MC_ALWAYS_INLINE uint32_t front(const uint8_t *facing, uint32_t f) { return (facing[f >> 3] >> (f & 7u)) & 1u; }

unsigned mc_mesh_edge_kind(const mc_pmesh_lod *lod, const uint8_t *facing, uint32_t h, uint32_t o)
{
    if (o == MC_NO_HALF_EDGE) return MC_EDGE_BORDER;
    const uint32_t f = MC_HALF_FACE(h), g = MC_HALF_FACE(o);
    if (front(facing, f) != front(facing, g)) return MC_EDGE_SILHOUETTE;
    int32_t a[3][3], b[3][3];
    mc_mesh_face_positions(lod, f, a);
    mc_mesh_face_positions(lod, g, b);
    /* (C99 converts int32_t (*)[3] to its const form only by a cast) */
    return mc_mesh_crease((const int32_t(*)[3])a, (const int32_t(*)[3])b, lod->pm->crease_cos) ? MC_EDGE_CREASE
                                                                                              : MC_EDGE_PLAIN;
}

/* The corners of face f as projected for this frame: from the cache when there is one (its entries
 * for present vertices are this frame's, mesh_lines.h), else projected now. Returns their flags. */
MC_ALWAYS_INLINE uint32_t corners(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, uint32_t f,
                                  mc_raster_vertex v[3])
{
    if (!cache) {
        int32_t p[3][3];
        return mc_mesh_face(lod, x, f, p, v);
    }
    uint32_t c[3], out = 0;
    mc_pmesh_lod_face(lod, f, c);
    for (int k = 0; k < 3; k++) {
        const mc_xvertex *e = &cache[c[k]];
        v[k].x = e->x, v[k].y = e->y, v[k].z = e->z;
        out |= e->flags;
    }
    return out;
}

/* Whether face f, a face with a flagged corner, is front-facing: the plane test (mesh_lines.h). */
static int face_front(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f)
{
    int32_t p[3][3];
    mc_mesh_face_positions(lod, f, p);
    return mc_mesh_face_front(x, (const int32_t(*)[3])p);
}

/* mc_raster_slope of face f, a face with a flagged corner: of the largest triangle of its clipped
 * polygon's fan (0 when nothing is left), as the face's plane has one slope on the screen wherever
 * it is cut. (Apart, and the clipping's buffers with it: only such a face needs them on the stack.) */
static MC_NOINLINE uint64_t clipped_slope(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f)
{
    int32_t p[3][3], q[3][3];
    mc_xvertex poly[MC_XFORM_CLIP_MAX];
    mc_raster_vertex tri[3];
    mc_mesh_face_positions(lod, f, p);
    for (int k = 0; k < 3; k++) mc_xform_view(x, p[k], q[k]);
    const unsigned n = mc_xform_clip_triangle(x, (const int32_t(*)[3])q, poly);
    uint64_t best = 0;
    unsigned at = 0;
    for (unsigned i = 1; i + 1 < n; i++) {
        const int64_t a = (int64_t)(poly[i].x - poly[0].x) * (poly[i + 1].y - poly[0].y) -
                          (int64_t)(poly[i + 1].x - poly[0].x) * (poly[i].y - poly[0].y);
        if (mc_mag64(a) > best) best = mc_mag64(a), at = i;
    }
    if (best == 0) return 0;
    const mc_xvertex *c[3] = {&poly[0], &poly[at], &poly[at + 1]};
    for (int k = 0; k < 3; k++) tri[k].x = c[k]->x, tri[k].y = c[k]->y, tri[k].z = c[k]->z;
    return mc_raster_slope(tri);
}

/* The depth offset slope of face f whose corners' flags are `flags` and projections v. */
static uint64_t face_slope(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f, uint32_t flags, const mc_raster_vertex v[3])
{
    return flags ? clipped_slope(lod, x, f) : mc_raster_slope(v);
}

/* Apart (noinline), as clipped_slope: only an edge with a flagged corner on its face needs it. */
MC_NOINLINE int mc_mesh_edge_ends(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t h, mc_raster_vertex ends[2])
{
    int32_t p[3][3], q[2][3];
    mc_xvertex e[2];
    const uint32_t f = MC_HALF_FACE(h), k = MC_HALF_EDGE_INDEX(h);
    mc_mesh_face_positions(lod, f, p);
    for (int i = 0; i < 2; i++) mc_xform_view(x, p[(k + (uint32_t)i) % 3], q[i]), mc_xform_project(x, q[i], &e[i]);
    const int flagged = (e[0].flags | e[1].flags) != 0;
    if (flagged && !mc_xform_clip_segment(x, q[0], q[1], e)) return 2;
    for (int i = 0; i < 2; i++) ends[i].x = e[i].x, ends[i].y = e[i].y, ends[i].z = e[i].z;
    return flagged;
}

/* How the passes over every face read a face's corners from the cache (a constant where called, so
 * that each pass has a loop for each): through the ancestor map; as stored (the full level, where
 * every vertex is its own ancestor); as stored with no corner flagged (the full level, and the frame's
 * projection flagged no vertex: no face needs its plane test or its clipping). With MC_MESH_SELECT
 * only: a firmware keeps one loop of each pass (flash). */
enum { CORNERS_MAPPED, CORNERS_STORED, CORNERS_PLAIN };

/* run(args..., ib, mode) with the part's index width ib (2 or 4) and the corner mode as constants:
 * a pass's loop over a run of faces, written once, made for each of the six. */
#define BY_CORNERS(ib, mode, run, ...)                                              \
    do {                                                                            \
        if ((ib) == 2) {                                                            \
            if ((mode) == CORNERS_PLAIN) run(__VA_ARGS__, 2, CORNERS_PLAIN);        \
            else if ((mode) == CORNERS_STORED) run(__VA_ARGS__, 2, CORNERS_STORED); \
            else run(__VA_ARGS__, 2, CORNERS_MAPPED);                               \
        } else {                                                                    \
            if ((mode) == CORNERS_PLAIN) run(__VA_ARGS__, 4, CORNERS_PLAIN);        \
            else if ((mode) == CORNERS_STORED) run(__VA_ARGS__, 4, CORNERS_STORED); \
            else run(__VA_ARGS__, 4, CORNERS_MAPPED);                               \
        }                                                                           \
    } while (0)

/* The corner mode of a frame at lod's level; unflagged: no vertex of the level is flagged (known
 * from the projection). */
static unsigned corner_mode(const mc_pmesh_lod *lod, int unflagged)
{
    if (!MC_MESH_SELECT || lod->level != lod->pm->vertices) return CORNERS_MAPPED;
    return unflagged ? CORNERS_PLAIN : CORNERS_STORED;
}

/* The cache entries of the corners of the face whose corner record is r (ib: the index width; mode:
 * the corner mode; constants where called), each corner standing for its ancestor present at the
 * level. */
MC_ALWAYS_INLINE void record_corners(const mc_pmesh_lod *lod, const mc_xvertex *cache, const uint8_t *r, unsigned ib,
                                     unsigned mode, const mc_xvertex **a, const mc_xvertex **b, const mc_xvertex **c)
{
    if (mode != CORNERS_MAPPED && ib == 2) {
        *a = &cache[mc_le16(r)], *b = &cache[mc_le16(r + 2)], *c = &cache[mc_le16(r + 4)];
    } else if (mode != CORNERS_MAPPED) {
        *a = &cache[mc_le32(r)], *b = &cache[mc_le32(r + 4)], *c = &cache[mc_le32(r + 8)];
    } else if (ib == 2) {
        const uint16_t *anc = (const uint16_t *)lod->anc;
        *a = &cache[anc[mc_le16(r)]], *b = &cache[anc[mc_le16(r + 2)]], *c = &cache[anc[mc_le16(r + 4)]];
    } else {
        const uint32_t *anc = (const uint32_t *)lod->anc;
        *a = &cache[anc[mc_le32(r)]], *b = &cache[anc[mc_le32(r + 4)]], *c = &cache[anc[mc_le32(r + 8)]];
    }
}

/* Whether face f, whose corner record is r, is front-facing (ib, mode: as record_corners). */
MC_ALWAYS_INLINE uint32_t facing_one(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, uint32_t f,
                                     const uint8_t *r, unsigned ib, unsigned mode)
{
    const mc_xvertex *a, *b, *c;
    record_corners(lod, cache, r, ib, mode, &a, &b, &c);
    if (mode != CORNERS_PLAIN && (a->flags | b->flags | c->flags)) return (uint32_t)face_front(lod, x, f);
    return (uint32_t)mc_mesh_front_of(a, b, c);
}

/* The facing bits of faces f0 .. f0 + n - 1, whose corner records start at r, from the cache; *acc
 * holds the bits of the byte being filled, stored as each byte is complete. ib is the part's index
 * width and mode the corner mode (record_corners; constants where called, BY_CORNERS). */
MC_ALWAYS_INLINE void facing_run(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, uint8_t *facing,
                                 uint32_t f0, uint32_t n, const uint8_t *r, uint32_t *acc, unsigned ib, unsigned mode)
{
    uint32_t bits = *acc, i = 0;
#if MC_MESH_SELECT
    /* whole bytes where the run starts on one (every run but maybe a short part's): each bit shifted
     * in from the top, the byte stored once */
    if ((f0 & 7u) == 0)
        for (; i + 8u <= n; i += 8u) {
            uint32_t byte = 0;
            for (uint32_t k = 0; k < 8u; k++, r += 3u * ib) byte = byte >> 1 | facing_one(lod, x, cache, f0 + i + k, r, ib, mode) << 7;
            facing[(f0 + i) >> 3] = (uint8_t)byte;
        }
#endif
    for (; i < n; i++, r += 3u * ib) {
        const uint32_t f = f0 + i;
        bits |= facing_one(lod, x, cache, f, r, ib, mode) << (f & 7u);
        if ((f & 7u) == 7u) facing[f >> 3] = (uint8_t)bits, bits = 0;
    }
    *acc = bits;
}

/* Sets the level's facing bits (mc_mesh_facing's; the corners from the cache when there is one, read
 * in order, a run of records a chunk; unflagged: no vertex of the level is flagged). */
static void set_facing(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, int unflagged, uint8_t *facing)
{
    const mc_pmesh *pm = lod->pm;
    if (!cache) {
        for (uint32_t i = 0; i < MC_MESH_FACING_BYTES(lod->faces); i++) facing[i] = 0;
        for (uint32_t f = 0; f < lod->faces; f++) {
            mc_raster_vertex v[3];
            if (corners(lod, x, 0, f, v) ? face_front(lod, x, f) : area2(v) < 0)
                facing[f >> 3] |= (uint8_t)(1u << (f & 7u));
        }
        return;
    }
    const unsigned shift = pm->record_shift;
    const uint32_t chunk = UINT32_C(1) << shift;
    const unsigned mode = corner_mode(lod, unflagged);
    uint32_t acc = 0;
    for (uint32_t f0 = 0; f0 < lod->faces; f0 += chunk) {
        const uint32_t n = lod->faces - f0 < chunk ? lod->faces - f0 : chunk;
        const uint8_t *r = pm->corners[f0 >> shift].data;
        BY_CORNERS(pm->index_bytes, mode, facing_run, lod, x, cache, facing, f0, n, r, &acc);
    }
    if (lod->faces & 7u) facing[lod->faces >> 3] = (uint8_t)acc;
}

static unsigned kind_color(unsigned kind)
{
    return kind == MC_EDGE_SILHOUETTE ? MC_LINES_SILHOUETTE_COLOR
           : kind == MC_EDGE_CREASE   ? MC_LINES_CREASE_COLOR
                                      : MC_LINES_BORDER_COLOR;
}

/* The line of half-edge h (opposite o) as both ways draw it: the pixels holding its ends (clipped
 * where one is flagged, mc_mesh_edge_ends) in la, lb, and its depth offset. Returns 0 when nothing of
 * it is left; counts its clipping in st. */
static int edge_line(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, uint32_t h, uint32_t o,
                     mc_lines_stats *st, mc_line_vertex *la, mc_line_vertex *lb, uint16_t *offset)
{
    const uint32_t f = MC_HALF_FACE(h), k = MC_HALF_EDGE_INDEX(h);
    mc_raster_vertex v[3], w[3], ends[2];
    const uint32_t fl = corners(lod, x, cache, f, v);
    ends[0] = v[k], ends[1] = v[(k + 1) % 3];
    if (fl) {   /* a face with a flagged corner: a flagged end clips the segment */
        const int clipped = mc_mesh_edge_ends(lod, x, h, ends);
        if (clipped == 2) { st->clipped_away++; return 0; }
        st->clipped += (uint32_t)clipped;
    }
    uint64_t off = face_slope(lod, x, f, fl, v);
    if (o != MC_NO_HALF_EDGE) {
        const uint32_t g = MC_HALF_FACE(o), gl = corners(lod, x, cache, g, w);
        const uint64_t og = face_slope(lod, x, g, gl, w);
        if (og > off) off = og;
    }
    off += 2u;
    *offset = (uint16_t)(off > MC_LINE_DEPTH_MAX ? MC_LINE_DEPTH_MAX : off);
    /* 1/16 pixel to the pixel that holds the point (pixel i spans [i, i + 1)) */
    la->x = ends[0].x >> MC_XFORM_SUBPIXEL_BITS, la->y = ends[0].y >> MC_XFORM_SUBPIXEL_BITS, la->z = ends[0].z;
    lb->x = ends[1].x >> MC_XFORM_SUBPIXEL_BITS, lb->y = ends[1].y >> MC_XFORM_SUBPIXEL_BITS, lb->z = ends[1].z;
    return 1;
}

/* The counts of an edge pass, kept in locals (a pixel store could alias *st). */
typedef struct edge_counts {
    uint32_t sil, crease, border;
} edge_counts;

/* The line of half-edge h (opposite o) of kind `kind`, drawn into t with mc_line's depth test (sd
 * null) or offered to sd (t null). Apart (noinline): few edges are lines, and each of the edge pass's
 * copies (two sinks, two record widths, three edges a face) would otherwise carry it. */
static MC_NOINLINE void draw_edge(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, mc_line_style *style,
                               const mc_target *t, mc_sdepth *sd, mc_lines_stats *st, uint32_t h, uint32_t o, unsigned kind)
{
    mc_line_vertex la, lb;
    if (!edge_line(lod, x, cache, h, o, st, &la, &lb, &style->depth_offset)) return;
    st->pixels += sd ? mc_line_sdepth(sd, la, lb, (uint8_t)kind_color(kind), style->depth_offset)
                     : mc_line(t, la, lb, (uint8_t)kind_color(kind), style);
}

#if MC_MESH_SELECT
/* The facing bits of the 32 faces from face f on (bit i: face f + i), of a level of `faces` faces
 * (bits past its last face are whatever the array holds). */
MC_ALWAYS_INLINE uint32_t facing_window(const uint8_t *facing, uint32_t f, uint32_t faces)
{
    const uint32_t b = f >> 3, nb = MC_MESH_FACING_BYTES(faces);
    uint64_t w = 0;
    if (b + 5u <= nb) {   /* (all five bytes within the level's: every window but the last few) */
        w = (uint64_t)facing[b] | (uint64_t)facing[b + 1] << 8 | (uint64_t)facing[b + 2] << 16 |
            (uint64_t)facing[b + 3] << 24 | (uint64_t)facing[b + 4] << 32;
    } else {
        for (uint32_t k = 0; k < 5u; k++)
            if (b + k < nb) w |= (uint64_t)facing[b + k] << (8u * k);
    }
    return (uint32_t)(w >> (f & 7u));
}
#endif

/* Edge k of face f in the edge pass, o its opposite as read (all ones for a border), fr and fc the
 * face's facing bit and crease bits. Each edge is found once: a border by its only face, a crease by
 * the face with the lower number at the level, a silhouette by that face too when drawn into a
 * target (mesh_lines.h: the order mesh_qi.h lists lines in) and by its front face when offered to a
 * sparse buffer; drawn when of a kind in flags (from either face the same pixels: line.h draws a->b
 * as b->a, the offset takes both faces' slopes, and both faces' clipped polygons cut the edge at the
 * same points). walk and k are constants where called (walk: o is a stored opposite, whose face may
 * be missing at the level). */
MC_ALWAYS_INLINE void edge_one(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, const uint8_t *facing,
                               unsigned flags, mc_line_style *style, const mc_target *t, mc_sdepth *sd, mc_lines_stats *st,
                               edge_counts *c, uint32_t f, uint32_t k, uint32_t o, uint32_t fr, uint32_t fc, int walk)
{
    if (walk) o = mc_pmesh_lod_across(lod, o);
    const uint32_t h = MC_HALF_EDGE(f, k);
    if (o == MC_NO_HALF_EDGE) {
        c->border++;
        if (flags & MC_EDGE_BORDER) draw_edge(lod, x, cache, style, t, sd, st, h, o, MC_EDGE_BORDER);
        return;
    }
    const uint32_t g = MC_HALF_FACE(o);
    if (front(facing, g) != fr) {   /* a silhouette: its front face's (sparse), its lower face's */
        if (sd ? !fr : g < f) return;
        c->sil++;
        if (flags & MC_EDGE_SILHOUETTE) draw_edge(lod, x, cache, style, t, sd, st, h, o, MC_EDGE_SILHOUETTE);
    } else if ((fc >> k) & 1u && g > f) {
        c->crease++;
        if (flags & MC_EDGE_CREASE) draw_edge(lod, x, cache, style, t, sd, st, h, o, MC_EDGE_CREASE);
    }
}

/* Face f's three edges in the edge pass, its opposite records at r (hb bytes each). */
MC_ALWAYS_INLINE void edge_face(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, const uint8_t *facing,
                                unsigned flags, mc_line_style *style, const mc_target *t, mc_sdepth *sd, mc_lines_stats *st,
                                edge_counts *c, uint32_t f, uint32_t fr, uint32_t fc, const uint8_t *r, unsigned hb, int walk)
{
#if MC_MESH_SELECT   /* a straight run of three (a loop's branches would come back) */
    edge_one(lod, x, cache, facing, flags, style, t, sd, st, c, f, 0, mc_pmesh_half(r, hb), fr, fc, walk);
    edge_one(lod, x, cache, facing, flags, style, t, sd, st, c, f, 1, mc_pmesh_half(r + hb, hb), fr, fc, walk);
    edge_one(lod, x, cache, facing, flags, style, t, sd, st, c, f, 2, mc_pmesh_half(r + 2u * hb, hb), fr, fc, walk);
#else                /* a loop: a firmware's flash */
    for (uint32_t k = 0; k < 3u; k++)
        edge_one(lod, x, cache, facing, flags, style, t, sd, st, c, f, k, mc_pmesh_half(r + k * hb, hb), fr, fc, walk);
#endif
}

/* Whether the faces across the three edges whose opposites are at q (hb bytes each) all face as fr
 * says (1 front, 0 back): then a face so facing with no crease edge offers no line, in a closed part
 * at a level whose opposites need no walk. Most faces are such: three reads and one test instead of
 * three edge tests. Asked of closed parts only, which have no border (pmesh.h closed: the generator
 * and a stream's reader make sure), so every opposite is a face's. */
MC_ALWAYS_INLINE int quiet_face(const uint8_t *facing, const uint8_t *q, unsigned hb, uint32_t fr)
{
    const uint32_t o0 = mc_pmesh_half(q, hb), o1 = mc_pmesh_half(q + hb, hb), o2 = mc_pmesh_half(q + 2u * hb, hb);
    const uint32_t a = front(facing, MC_HALF_FACE(o0)), b = front(facing, MC_HALF_FACE(o1)), c = front(facing, MC_HALF_FACE(o2));
    return fr ? (a & b & c) != 0 : (a | b | c) == 0;
}

#if MC_MESH_SELECT
/* Bit i set when face f + i (i < n <= 32) has a crease edge. */
MC_ALWAYS_INLINE uint32_t crease_window(const uint8_t *cr, uint32_t f, uint32_t n)
{
    uint32_t m = 0;
    for (uint32_t i = 0; i < n; i++) m |= (uint32_t)(mc_lines_face_creases(cr, f + i) != 0) << i;
    return m;
}
#endif

/* The edge pass over faces f0 .. f0 + n - 1, whose opposite records start at r (hb: the index width,
 * 2 or 4, and walk: constants where called; any_crease: whether the level has a crease). Offered to
 * a sparse buffer, a face finds an edge only when it is front-facing (a silhouette's), has a crease
 * edge, or may have a border (the part is not closed): in a closed part the back faces without a
 * crease, about half, are passed over, and so are the front faces without a crease whose three
 * neighbours face front (quiet_face), where no opposite walks; with MC_MESH_SELECT the faces to visit
 * are taken 32 at a time from their bits (whether a face is one is a coin toss to a predictor). Drawn
 * into a target, every face is visited, but with MC_MESH_SELECT (a firmware keeps the flash) where no
 * opposite walks in a closed part, a face without a crease whose neighbours face as it does. */
MC_ALWAYS_INLINE void edge_run(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, const uint8_t *facing,
                               const uint8_t *cr, unsigned flags, mc_line_style *style, const mc_target *t, mc_sdepth *sd,
                               mc_lines_stats *st, uint32_t f0, uint32_t n, const uint8_t *r, unsigned hb, int walk,
                               int any_crease)
{
    edge_counts c;   /* zeroed field by field: clang -O0 clears an aggregate initializer with memset */
    c.sil = c.crease = c.border = 0;
    const int skip = sd && lod->pm->closed;   /* (sd: a constant where called) */
    /* a closed part whose every opposite read is the level's (none walks: the full level, or a
     * neighbour table): a sparse buffer's front faces and a target's faces may be quiet */
    const int quiet = lod->pm->closed && (lod->nbr || lod->faces >= lod->pm->faces);
#if MC_MESH_SELECT
    for (uint32_t i0 = 0; i0 < n; i0 += 32u) {
        const uint32_t m = n - i0 < 32u ? n - i0 : 32u;
        uint32_t bits = m == 32u ? 0xFFFFFFFFu : (UINT32_C(1) << m) - 1u;
        if (skip) bits &= facing_window(facing, f0 + i0, lod->faces) | (any_crease ? crease_window(cr, f0 + i0, m) : 0u);
        while (bits) {
            /* (a level without a crease has no crease bit set: none is read) */
            const uint32_t i = i0 + mc_ctz(bits), f = f0 + i, fc = any_crease ? mc_lines_face_creases(cr, f) : 0u;
            const uint8_t *q = r + i * 3u * hb;
            bits &= bits - 1u;
            /* (a sparse buffer's face without a crease faces front) */
            if (quiet && fc == 0 && quiet_face(facing, q, hb, sd ? 1u : front(facing, f))) continue;
            edge_face(lod, x, cache, facing, flags, style, t, sd, st, &c, f, front(facing, f), fc, q, hb, walk);
        }
    }
#else
    (void)any_crease;   /* (a face's crease bits are at hand) */
    for (uint32_t f = f0; f < f0 + n; f++, r += 3u * hb) {
        const uint32_t fr = front(facing, f), fc = mc_lines_face_creases(cr, f);
        if (skip && !fc && (!fr || (quiet && quiet_face(facing, r, hb, 1u)))) continue;
        edge_face(lod, x, cache, facing, flags, style, t, sd, st, &c, f, fr, fc, r, hb, walk);
    }
#endif
    st->silhouettes += c.sil, st->creases += c.crease, st->borders += c.border;
}

/* Both ways' edge pass: the level's crease and facing bits in mem, then every edge of a kind in
 * flags drawn as its line, into t with mc_line's depth test (sd null) or offered to sd (t null);
 * counts into st; unflagged: no vertex of the level is flagged in the cache. A constant sink makes
 * one function of it for each way. */
MC_ALWAYS_INLINE void draw_edges(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, int unflagged,
                                 uint8_t *mem, unsigned flags, const mc_target *t, mc_sdepth *sd, mc_lines_stats *st)
{
    uint8_t *facing = mc_lines_facing(mem);
    const uint8_t *cr = mc_lines_creases(mem, lod->pm->faces);
    mc_mesh_creases_update(lod, mem);
    set_facing(lod, x, cache, unflagged, facing);
    mc_line_style style;
    style.flags = (uint8_t)(MC_LINE_WRITE_DEPTH | ((flags & MC_LINES_NO_HIDING) ? MC_LINE_NO_DEPTH_TEST : 0u));
    style.depth_offset = 0;
    const mc_pmesh *pm = lod->pm;
    const unsigned shift = pm->record_shift;
    const uint32_t chunk = UINT32_C(1) << shift;
    /* the stored opposites read in order, a run of records a chunk (or the level's own, when the
     * state keeps a neighbour table: the same records, none of them needing a walk); at the full
     * level no stored opposite needs one either. A firmware keeps one copy of the pass (flash). */
    const int walk = MC_MESH_SELECT ? !lod->nbr && lod->faces < pm->faces : 1;
    const int any_crease = mc_lines_any_crease(mem);
    for (uint32_t f0 = 0; f0 < lod->faces; f0 += chunk) {
        const uint32_t n = lod->faces - f0 < chunk ? lod->faces - f0 : chunk;
        const uint8_t *r = lod->nbr ? MC_PMESH_NEIGHBOUR_AT(lod->nbr, MC_HALF_EDGE(f0, 0), pm->half_bytes)
                                    : pm->opposite[f0 >> shift].data;
        if (!walk) {
            if (pm->half_bytes == 2) edge_run(lod, x, cache, facing, cr, flags, &style, t, sd, st, f0, n, r, 2, 0, any_crease);
            else edge_run(lod, x, cache, facing, cr, flags, &style, t, sd, st, f0, n, r, 4, 0, any_crease);
        } else {
            if (pm->half_bytes == 2) edge_run(lod, x, cache, facing, cr, flags, &style, t, sd, st, f0, n, r, 2, 1, any_crease);
            else edge_run(lod, x, cache, facing, cr, flags, &style, t, sd, st, f0, n, r, 4, 1, any_crease);
        }
    }
    /* every edge once: a border has one half-edge at the level, any other edge two */
    st->edges = (3u * lod->faces + st->borders) / 2u;
}

/* mc_lines_stats all zero (field by field: an aggregate initialiser becomes a memset call at -O0) */
static void stats_zero(mc_lines_stats *st)
{
    st->edges = st->silhouettes = st->creases = st->borders = st->skipped = st->pixels = st->clipped = 0;
    st->clipped_away = 0;
}

int mc_mesh_lines(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t, uint8_t *mem,
                  const mc_xvertex *cache, mc_lines_stats *stats)
{
    mc_lines_stats st;
    stats_zero(&st);
    if (!lod || !lod->pm || !view || !t || !t->color || !t->depth || !mem) return MC_ERR_ARG;
    if (t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    mc_xform x;
    mc_xform_init(&x, view, t->width, t->height);
    draw_edges(lod, &x, cache, 0, mem, flags, t, 0, &st);
    if (stats) *stats = st;
    return MC_OK;
}

/* Empties the entries of sd that face f, a face with a flagged corner, hides: the triangles of its
 * clipped polygon's fan, as mc_mesh_render draws them (not culled). Apart, as clipped_slope. */
static MC_NOINLINE void hide_clipped(mc_sdepth *sd, const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f)
{
    int32_t p[3][3];
    mc_raster_vertex poly[MC_XFORM_CLIP_MAX];
    mc_mesh_face_positions(lod, f, p);
    const unsigned n = mc_mesh_clip_face(x, (const int32_t(*)[3])p, poly);
    for (unsigned i = 1; i + 1 < n; i++) {
        mc_raster_vertex tri[3];
        tri[0] = poly[0], tri[1] = poly[i], tri[2] = poly[i + 1];
        mc_raster_triangle_hide(sd, tri, 0u);
    }
}

/* an unflagged vertex lies within the band, which lies within the rasterizer's limit */
typedef char mc_band_within_raster_limit[((int64_t)MC_XFORM_BAND << MC_XFORM_SUBPIXEL_BITS) <= MC_RASTER_COORD_LIMIT ? 1 : -1];

/* Empties the entries of sd that the face with projected corners a, b, c (none flagged) hides, culled
 * when cull; a face whose box holds no pixel centre or no entry is rejected here, inline, before its
 * corners are copied. With MC_MESH_SELECT, for a box of at most two rows within one 32-pixel block (a
 * face of a dense mesh is a pixel or two across) both tests are taken as values, the rows' words read
 * at indices clamped to the frame (which an empty box may leave), and only the answer branches. */
MC_ALWAYS_INLINE void hide_face(mc_sdepth *sd, const mc_xvertex *a, const mc_xvertex *b, const mc_xvertex *c, int cull)
{
#if MC_MESH_SELECT
    mc_raster_box box;   /* (the corners are unflagged: inside the band, so inside the rasterizer's limit) */
    const int ok = mc_raster_centre_run_inside(a->y, b->y, c->y, sd->height, &box.j0, &box.j1) &
                   mc_raster_centre_run_inside(a->x, b->x, c->x, sd->width, &box.i0, &box.i1);
    const uint32_t i0 = (uint32_t)box.i0, i1 = (uint32_t)box.i1, j0 = (uint32_t)box.j0;   /* i0, j0 >= 0 */
    int hit;
    if (box.j1 - box.j0 > 1 || (i0 >> 5) != (i1 >> 5)) {   /* (i1 < 0 lands here too) */
        hit = ok && mc_sdepth_any(sd, i0, i1, j0, (uint32_t)box.j1);
    } else {
        const uint32_t jc = j0 < sd->height - 1u ? j0 : sd->height - 1u, jr = jc + (box.j1 > box.j0);
        const uint32_t ic = i0 < sd->width - 1u ? i0 : sd->width - 1u;
        const uint32_t *u = sd->used + (ic >> 5);
        const uint32_t words = u[jc * sd->blocks] | u[jr * sd->blocks];
        const uint32_t mask = (0xFFFFFFFFu >> (i0 & 31u)) & (0xFFFFFFFFu << (31u - (i1 & 31u)));
        hit = ok & ((words & mask) != 0);
    }
    if (!hit) return;
#endif
    mc_raster_vertex v[3];
    v[0].x = a->x, v[0].y = a->y, v[0].z = a->z;
    v[1].x = b->x, v[1].y = b->y, v[1].z = b->z;
    v[2].x = c->x, v[2].y = c->y, v[2].z = c->z;
#if !MC_MESH_SELECT
    mc_raster_box box;
    if (!mc_raster_centres(v, sd->width, sd->height, &box) ||
        !mc_sdepth_any(sd, (uint32_t)box.i0, (uint32_t)box.i1, (uint32_t)box.j0, (uint32_t)box.j1))
        return;
#endif
    mc_raster_triangle_hide_box(sd, v, cull ? MC_RASTER_CULL_BACK : 0u, &box);   /* (the box as it takes it) */
}

/* Face f of the face pass, its corner record at q (ib, mode: as record_corners, constants where called). */
MC_ALWAYS_INLINE void hide_one(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, mc_sdepth *sd, int cull,
                               uint32_t f, const uint8_t *q, unsigned ib, unsigned mode)
{
    const mc_xvertex *a, *b, *c;
    record_corners(lod, cache, q, ib, mode, &a, &b, &c);
    if (mode != CORNERS_PLAIN && (a->flags | b->flags | c->flags)) {
        hide_clipped(sd, lod, x, f);
        return;
    }
    hide_face(sd, a, b, c, cull);
}

/* The face pass over faces f0 .. f0 + n - 1, whose corner records start at r, their corners from the
 * cache (ib: the index width, mode: the corner mode; constants where called). Culling, with
 * MC_MESH_SELECT, the front faces are taken 32 at a time from their facing bits, lowest first,
 * instead of a branch on each face's. */
MC_ALWAYS_INLINE void hide_run(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, mc_sdepth *sd,
                               const uint8_t *facing, int cull, uint32_t f0, uint32_t n, const uint8_t *r, unsigned ib,
                               unsigned mode)
{
#if MC_MESH_SELECT
    for (uint32_t i0 = 0; i0 < n; i0 += 32u) {
        const uint32_t m = n - i0 < 32u ? n - i0 : 32u;
        uint32_t bits = m == 32u ? 0xFFFFFFFFu : (UINT32_C(1) << m) - 1u;
        if (cull) bits &= facing_window(facing, f0 + i0, lod->faces);
        while (bits) {
            const uint32_t i = i0 + mc_ctz(bits);
            bits &= bits - 1u;
            hide_one(lod, x, cache, sd, cull, f0 + i, r + i * 3u * ib, ib, mode);
        }
    }
#else
    for (uint32_t i = 0; i < n; i++, r += 3u * ib)
        if (!cull || front(facing, f0 + i)) hide_one(lod, x, cache, sd, cull, f0 + i, r, ib, mode);
#endif
}

/* Whether face group g of the full level may hide an entry of sd in orthographic view x (pmesh.h
 * groups): its box of points bounds where its faces lie and their least depth (mc_xform_box_bound),
 * and a face empties only entries of its pixels at least as far as that depth (raster.h). A box
 * the view cannot bound is visited. */
static int group_may_hide(const mc_pmesh *pm, const mc_xform *x, const mc_sdepth *sd, uint32_t g)
{
    const uint8_t *r = mc_chunk_record(pm->groups, pm->record_shift, 12u, g);
    int32_t lo[3], hi[3];
    mc_pmesh_position_at(r, lo), mc_pmesh_position_at(r + 6, hi);
    mc_xform_box b;
    if (!mc_xform_box_bound(x, lo, hi, &b)) return 1;
    int32_t i0, i1, j0, j1;
    if (!mc_raster_centre_run_of(b.x0, b.x1, sd->width, &i0, &i1) || !mc_raster_centre_run_of(b.y0, b.y1, sd->height, &j0, &j1))
        return 0;   /* no pixel centre of the frame: its faces cover none */
    return mc_sdepth_any_from(sd, (uint32_t)i0, (uint32_t)i1, (uint32_t)j0, (uint32_t)j1, mc_raster_least_depth(b.z0, b.z0, b.z0));
}

/* The face pass by groups at the full level (ib, mode: as record_corners, constants where called):
 * a group that may hide an entry has its faces passed as hide_run passes them, in the group's order
 * (which faces empty an entry does not depend on the order); the others are passed over whole. */
MC_ALWAYS_INLINE void hide_groups(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, mc_sdepth *sd,
                                  const uint8_t *facing, int cull, unsigned ib, unsigned mode)
{
    const mc_pmesh *pm = lod->pm;
    const uint32_t size = pm->group_size, faces = pm->faces;
    const unsigned shift = pm->record_shift, gb = pm->group_bytes;
    for (uint32_t g = 0, first = 0; first < faces; g++, first += size) {
        if (!group_may_hide(pm, x, sd, g)) continue;
        const uint32_t n = faces - first < size ? faces - first : size;
        const uint8_t *r = mc_chunk_record(pm->group_faces, shift, gb, first);   /* (a group lies in one chunk) */
        for (uint32_t k = 0; k < n; k++, r += gb) {
            const uint32_t f = mc_pmesh_group_face(r, gb);
            if (cull && !front(facing, f)) continue;
            hide_one(lod, x, cache, sd, cull, f, mc_chunk_record(pm->corners, shift, 3u * ib, f), ib, mode);
        }
    }
}

void mc_mesh_lines_level(const mc_pmesh_lod *lod, uint8_t *mem)
{
    if (lod && lod->pm && lod->pm->opposite && mem) mc_mesh_creases_update(lod, mem);
}

/* The face pass: every face mc_mesh_render would draw (a closed part's front faces) empties the
 * entries of sd it hides (a face with a flagged corner culled by its plane, then as its clipped fan);
 * a face whose box holds no entry costs its corners and its box. With face groups (pmesh.h), at the
 * full level of an orthographic view, a group that cannot hide an entry costs its box instead.
 * Apart on x86-64 (MC_MESH_SELECT: noinline, called once a frame) so that a profile tells it from
 * the edge pass (tests/bench/mesh.sh); a firmware inlines it (0.1 % fewer instructions a line pixel
 * on the Cortex-M4 than apart). */
#if MC_MESH_SELECT
#define FACE_PASS MC_NOINLINE
#else
#define FACE_PASS
#endif
static FACE_PASS void face_pass(const mc_pmesh_lod *lod, const mc_xform *x, mc_sdepth *sd, const uint8_t *facing,
                                const mc_xvertex *cache, int unflagged)
{
    const mc_pmesh *pm = lod->pm;
    const int cull = pm->closed;
    if (!cache) {
        for (uint32_t f = 0; f < lod->faces; f++) {
            if (cull && !front(facing, f)) continue;
            int32_t p[3][3];
            mc_xvertex v[3];
            mc_mesh_face_positions(lod, f, p);
            for (int k = 0; k < 3; k++) mc_xform_vertex(x, p[k], &v[k]);
            if (v[0].flags | v[1].flags | v[2].flags) hide_clipped(sd, lod, x, f);
            else hide_face(sd, &v[0], &v[1], &v[2], cull);
        }
        return;
    }
    const unsigned shift = pm->record_shift;
    const uint32_t chunk = UINT32_C(1) << shift;
    const unsigned mode = corner_mode(lod, unflagged);
    if (pm->group_size && lod->faces == pm->faces && !x->perspective) {   /* (every corner its own ancestor) */
#if MC_MESH_SELECT
        BY_CORNERS(pm->index_bytes, mode, hide_groups, lod, x, cache, sd, facing, cull);
#else   /* one copy (a firmware's flash): the mapped corners, the index width as it comes */
        hide_groups(lod, x, cache, sd, facing, cull, pm->index_bytes, CORNERS_MAPPED);
#endif
        return;
    }
    for (uint32_t f0 = 0; f0 < lod->faces; f0 += chunk) {
        const uint32_t n = lod->faces - f0 < chunk ? lod->faces - f0 : chunk;
        const uint8_t *r = pm->corners[f0 >> shift].data;
        BY_CORNERS(pm->index_bytes, mode, hide_run, lod, x, cache, sd, facing, cull, f0, n, r);
    }
}

int mc_mesh_lines_sparse(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, mc_sdepth *sd, uint8_t *mem,
                         mc_xvertex *cache, mc_lines_stats *stats)
{
    mc_lines_stats st;
    stats_zero(&st);
    if (!lod || !lod->pm || !view || !sd || !mem) return MC_ERR_ARG;
    if (sd->width > MC_TARGET_MAX || sd->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    mc_xform x;
    mc_xform_init(&x, view, sd->width, sd->height);
    const int unflagged = cache && !mc_mesh_project(lod, &x, cache);
    /* the lines first: their pixels become the buffer's entries, the nearest kept; then the faces */
    draw_edges(lod, &x, cache, unflagged, mem, flags, 0, sd, &st);
    if (!(flags & MC_LINES_NO_HIDING) && sd->width && sd->height)   /* (an empty frame has nothing to hide) */
        face_pass(lod, &x, sd, mc_lines_facing(mem), cache, unflagged);
    if (stats) *stats = st;
    return MC_OK;
}
