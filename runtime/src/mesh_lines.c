/* Line drawings of a progressive mesh: see modelc/mesh_lines.h. */
#include "modelc/mesh_lines.h"

static uint64_t mag(int64_t v) { return v < 0 ? 0u - (uint64_t)v : (uint64_t)v; }

/* The normal of the face with corners p, its components shifted right together until each fits 15
 * bits (signs kept); all zero for a face with no area. */
static void normal15(const int32_t p[3][3], int64_t n[3])
{
    int64_t a[3], b[3];
    for (int i = 0; i < 3; i++) a[i] = (int64_t)p[1][i] - p[0][i], b[i] = (int64_t)p[2][i] - p[0][i];
    n[0] = a[1] * b[2] - a[2] * b[1];   /* components below 2^35 (mesh_render.c) */
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    const uint64_t m = mag(n[0]) | mag(n[1]) | mag(n[2]);
    int s = 0;
    while ((m >> s) >= ((uint64_t)1 << 15)) s++;
    for (int i = 0; i < 3; i++) n[i] = n[i] / ((int64_t)1 << s);
}

int mc_mesh_crease(const int32_t a[3][3], const int32_t b[3][3], int32_t crease_cos)
{
    int64_t n[3], m[3];
    normal15(a, n);
    normal15(b, m);
    const int64_t d = n[0] * m[0] + n[1] * m[1] + n[2] * m[2];   /* |d| < 3 * 2^30 */
    const uint64_t ln = (uint64_t)(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    const uint64_t lm = (uint64_t)(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]);
    if (ln == 0 || lm == 0) return 0;
    /* cos = d / sqrt(ln lm) < c = crease_cos / 2^14; squared: d^2 against c^2 ln lm / 2^28, with
     * ln lm < 9 * 2^60 and (ln lm >> 28) c^2 < 9 * 2^60: no overflow */
    const uint64_t d2 = (uint64_t)(d * d), rhs = ((ln * lm) >> 28) * (uint64_t)((int64_t)crease_cos * crease_cos);
    if (crease_cos >= 0) return d < 0 || d2 < rhs;
    return d < 0 && d2 > rhs;
}

/* Twice the signed screen area of a projected face, in (1/16 pixel)^2; below 0: front-facing. */
static int64_t area2(const mc_raster_vertex v[3])
{
    return (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y);
}

int mc_mesh_front(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f)
{
    int32_t p[3][3];
    mc_raster_vertex v[3];
    return !mc_mesh_face(lod, x, f, p, v) && area2(v) < 0;
}

void mc_mesh_facing(const mc_pmesh_lod *lod, const mc_xform *x, uint8_t *facing)
{
    for (uint32_t i = 0; i < MC_MESH_FACING_BYTES(lod->faces); i++) facing[i] = 0;
    for (uint32_t f = 0; f < lod->faces; f++)
        if (mc_mesh_front(lod, x, f)) facing[f >> 3] |= (uint8_t)(1u << (f & 7u));
}

static int front(const uint8_t *facing, uint32_t f) { return (facing[f >> 3] >> (f & 7u)) & 1u; }

static void face_positions(const mc_pmesh_lod *lod, uint32_t f, int32_t p[3][3])
{
    uint32_t c[3];
    mc_pmesh_lod_face(lod, f, c);
    for (int k = 0; k < 3; k++) mc_pmesh_position(lod->pm, c[k], p[k]);
}

unsigned mc_mesh_edge_kind(const mc_pmesh_lod *lod, const uint8_t *facing, uint32_t h, uint32_t o)
{
    if (o == MC_NO_HALF_EDGE) return MC_EDGE_BORDER;
    const uint32_t f = MC_HALF_FACE(h), g = MC_HALF_FACE(o);
    if (front(facing, f) != front(facing, g)) return MC_EDGE_SILHOUETTE;
    int32_t a[3][3], b[3][3];
    face_positions(lod, f, a);
    face_positions(lod, g, b);
    /* (C99 converts int32_t (*)[3] to its const form only by a cast) */
    return mc_mesh_crease((const int32_t(*)[3])a, (const int32_t(*)[3])b, lod->pm->crease_cos) ? MC_EDGE_CREASE
                                                                                              : MC_EDGE_PLAIN;
}

/* One pixel's worth of the face's steepest depth slope, in depth units (0 for a face seen edge-on,
 * which covers no pixel to hide a line with). */
static uint64_t slope_offset(const mc_raster_vertex v[3])
{
    const int64_t a = area2(v);
    if (a == 0) return 0;
    const int64_t z1 = (int64_t)v[1].z - v[0].z, z2 = (int64_t)v[2].z - v[0].z;
    /* dz/dx, dz/dy per 1/16 pixel: numerators below 2^16 * 2^22 each */
    const uint64_t gx = mag(z1 * (v[2].y - v[0].y) - z2 * (v[1].y - v[0].y));
    const uint64_t gy = mag((int64_t)(v[1].x - v[0].x) * z2 - (int64_t)(v[2].x - v[0].x) * z1);
    const uint64_t g = gx > gy ? gx : gy;
    return (g << MC_XFORM_SUBPIXEL_BITS) / mag(a) + 1u;
}

/* The corners of face f as projected for this frame: from the cache when there is one (its entries
 * for present vertices are this frame's, mesh_lines.h), else projected now. Returns their flags. */
static uint32_t corners(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xvertex *cache, uint32_t f,
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

/* The memory's parts (mesh_lines.h MC_MESH_LINES_BYTES): the level the crease bits are for, plus
 * one (0: none yet); the facing bits; four bits a face, bit k set when edge k is a crease. */
static uint32_t *crease_tag(uint8_t *mem) { return (uint32_t *)(void *)mem; }
static uint8_t *facing_of(uint8_t *mem) { return mem + 4; }
static uint8_t *creases_of(uint8_t *mem, uint32_t faces) { return mem + 4 + MC_MESH_FACING_BYTES(faces); }

static void set_crease(uint8_t *cr, uint32_t h)
{
    const uint32_t f = MC_HALF_FACE(h);
    cr[f >> 1] |= (uint8_t)((1u << MC_HALF_EDGE_INDEX(h)) << ((f & 1u) * 4u));
}

static int is_crease(const uint8_t *cr, uint32_t h)
{
    const uint32_t f = MC_HALF_FACE(h);
    return (cr[f >> 1] >> ((f & 1u) * 4u + MC_HALF_EDGE_INDEX(h))) & 1u;
}

/* The crease bits of the level (a function of the level alone: recomputed only when it changed). */
static void update_creases(const mc_pmesh_lod *lod, uint8_t *mem)
{
    const mc_pmesh *pm = lod->pm;
    if (*crease_tag(mem) == lod->level + 1u) return;
    uint8_t *cr = creases_of(mem, pm->faces);
    for (uint32_t i = 0; i < (pm->faces + 1u) / 2u; i++) cr[i] = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        int32_t a[3][3];
        face_positions(lod, f, a);
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
            if (o == MC_NO_HALF_EDGE || MC_HALF_FACE(o) < f) continue;
            int32_t b[3][3];
            face_positions(lod, MC_HALF_FACE(o), b);
            if (mc_mesh_crease((const int32_t(*)[3])a, (const int32_t(*)[3])b, pm->crease_cos))
                set_crease(cr, h), set_crease(cr, o);
        }
    }
    *crease_tag(mem) = lod->level + 1u;
}

int mc_mesh_lines(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t, uint8_t *mem,
                  const mc_xvertex *cache, mc_lines_stats *stats)
{
    mc_lines_stats st;   /* field by field: an aggregate initialiser becomes a memset call at -O0 */
    st.edges = st.silhouettes = st.creases = st.borders = st.skipped = st.pixels = 0;
    if (!lod || !lod->pm || !view || !t || !t->color || !t->depth || !mem) return MC_ERR_ARG;
    if (t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    mc_xform x;
    mc_xform_init(&x, view, t->width, t->height);
    uint8_t *facing = facing_of(mem);
    const uint8_t *cr = creases_of(mem, lod->pm->faces);
    update_creases(lod, mem);
    for (uint32_t i = 0; i < MC_MESH_FACING_BYTES(lod->faces); i++) facing[i] = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        mc_raster_vertex v[3];
        if (!corners(lod, &x, cache, f, v) && area2(v) < 0) facing[f >> 3] |= (uint8_t)(1u << (f & 7u));
    }
    for (uint32_t f = 0; f < lod->faces; f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;   /* the earlier face's */
            const unsigned kind = o == MC_NO_HALF_EDGE                            ? MC_EDGE_BORDER
                                  : front(facing, f) != front(facing, MC_HALF_FACE(o)) ? MC_EDGE_SILHOUETTE
                                  : is_crease(cr, h)                                  ? MC_EDGE_CREASE
                                                                                      : MC_EDGE_PLAIN;
            st.edges++;
            st.silhouettes += kind == MC_EDGE_SILHOUETTE;
            st.creases += kind == MC_EDGE_CREASE;
            st.borders += kind == MC_EDGE_BORDER;
            if (!(kind & flags)) continue;
            mc_raster_vertex v[3], w[3];
            if (corners(lod, &x, cache, f, v)) { st.skipped++; continue; }   /* (a flagged endpoint flags its face) */
            uint64_t off = slope_offset(v);
            if (o != MC_NO_HALF_EDGE && corners(lod, &x, cache, MC_HALF_FACE(o), w) == 0) {
                const uint64_t og = slope_offset(w);
                if (og > off) off = og;
            }
            off += 2u;
            mc_line_style style;
            style.depth_offset = (uint16_t)(off > MC_LINE_DEPTH_MAX ? MC_LINE_DEPTH_MAX : off);
            style.flags = (uint8_t)(MC_LINE_WRITE_DEPTH | ((flags & MC_LINES_NO_HIDING) ? MC_LINE_NO_DEPTH_TEST : 0u));
            const mc_raster_vertex *a = &v[k], *b = &v[(k + 1) % 3];
            /* 1/16 pixel to the pixel that holds the point (pixel i spans [i, i + 1)) */
            mc_line_vertex la, lb;
            la.x = a->x >> MC_XFORM_SUBPIXEL_BITS, la.y = a->y >> MC_XFORM_SUBPIXEL_BITS, la.z = a->z;
            lb.x = b->x >> MC_XFORM_SUBPIXEL_BITS, lb.y = b->y >> MC_XFORM_SUBPIXEL_BITS, lb.z = b->z;
            const unsigned color = kind == MC_EDGE_SILHOUETTE ? MC_LINES_SILHOUETTE_COLOR
                                   : kind == MC_EDGE_CREASE   ? MC_LINES_CREASE_COLOR
                                                              : MC_LINES_BORDER_COLOR;
            st.pixels += mc_line(t, la, lb, (uint8_t)color, &style);
        }
    if (stats) *stats = st;
    return MC_OK;
}

int mc_mesh_lines_sparse(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, mc_sdepth *sd, uint8_t *mem,
                         mc_xvertex *cache, mc_lines_stats *stats)
{
    mc_lines_stats st;
    st.edges = st.silhouettes = st.creases = st.borders = st.skipped = st.pixels = 0;
    if (!lod || !lod->pm || !view || !sd || !mem) return MC_ERR_ARG;
    if (sd->width > MC_TARGET_MAX || sd->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    mc_xform x;
    mc_xform_init(&x, view, sd->width, sd->height);
    if (cache) mc_mesh_project(lod, &x, cache);
    uint8_t *facing = facing_of(mem);
    const uint8_t *cr = creases_of(mem, lod->pm->faces);
    update_creases(lod, mem);
    for (uint32_t i = 0; i < MC_MESH_FACING_BYTES(lod->faces); i++) facing[i] = 0;
    for (uint32_t f = 0; f < lod->faces; f++) {
        mc_raster_vertex v[3];
        if (!corners(lod, &x, cache, f, v) && area2(v) < 0) facing[f >> 3] |= (uint8_t)(1u << (f & 7u));
    }
    /* the lines first: their pixels become the buffer's entries, the nearest kept */
    for (uint32_t f = 0; f < lod->faces; f++)
        for (uint32_t k = 0; k < 3; k++) {
            const uint32_t h = MC_HALF_EDGE(f, k), o = mc_pmesh_lod_opposite(lod, h);
            if (o != MC_NO_HALF_EDGE && MC_HALF_FACE(o) < f) continue;
            const unsigned kind = o == MC_NO_HALF_EDGE                            ? MC_EDGE_BORDER
                                  : front(facing, f) != front(facing, MC_HALF_FACE(o)) ? MC_EDGE_SILHOUETTE
                                  : is_crease(cr, h)                                  ? MC_EDGE_CREASE
                                                                                      : MC_EDGE_PLAIN;
            st.edges++;
            st.silhouettes += kind == MC_EDGE_SILHOUETTE;
            st.creases += kind == MC_EDGE_CREASE;
            st.borders += kind == MC_EDGE_BORDER;
            if (!(kind & flags)) continue;
            mc_raster_vertex v[3], w[3];
            if (corners(lod, &x, cache, f, v)) { st.skipped++; continue; }
            uint64_t off = slope_offset(v);
            if (o != MC_NO_HALF_EDGE && corners(lod, &x, cache, MC_HALF_FACE(o), w) == 0) {
                const uint64_t og = slope_offset(w);
                if (og > off) off = og;
            }
            off += 2u;
            const mc_raster_vertex *a = &v[k], *b = &v[(k + 1) % 3];
            mc_line_vertex la, lb;
            la.x = a->x >> MC_XFORM_SUBPIXEL_BITS, la.y = a->y >> MC_XFORM_SUBPIXEL_BITS, la.z = a->z;
            lb.x = b->x >> MC_XFORM_SUBPIXEL_BITS, lb.y = b->y >> MC_XFORM_SUBPIXEL_BITS, lb.z = b->z;
            const unsigned color = kind == MC_EDGE_SILHOUETTE ? MC_LINES_SILHOUETTE_COLOR
                                   : kind == MC_EDGE_CREASE   ? MC_LINES_CREASE_COLOR
                                                              : MC_LINES_BORDER_COLOR;
            st.pixels += mc_line_sdepth(sd, la, lb, (uint8_t)color,
                                        (uint16_t)(off > MC_LINE_DEPTH_MAX ? MC_LINE_DEPTH_MAX : off));
        }
    /* then the faces mc_mesh_render would draw empty the entries they hide; a face whose box holds
     * no entry costs its corners and its box */
    if (!(flags & MC_LINES_NO_HIDING)) {
        const int cull = lod->pm->closed;
        for (uint32_t f = 0; f < lod->faces; f++) {
            if (cull && !front(facing, f)) continue;
            mc_raster_vertex v[3];
            if (corners(lod, &x, cache, f, v)) continue;
            mc_raster_triangle_hide(sd, v, cull ? MC_RASTER_CULL_BACK : 0u);
        }
    }
    if (stats) *stats = st;
    return MC_OK;
}
