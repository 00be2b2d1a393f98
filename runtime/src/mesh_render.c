/* Flat-shaded progressive meshes: see modelc/mesh_render.h.
 *
 * Per face: its corners (the level's ancestors of the stored ones), their projections (from the
 * frame's vertex cache, or projected here), then a test as cheap as raster.c's first ones (a back
 * face when culling, no pixel centre in the bounding box): only a face that may cover a pixel has its
 * shade (the stored one when the face is as in the full mesh) and goes to the rasterizer. A face with a corner the projection flags goes to
 * clipped_face instead (xform.h's clipping). */
#include "modelc/mesh_render.h"
#include "xform_ortho.h"

unsigned mc_mesh_shade(const int32_t p0[3], const int32_t p1[3], const int32_t p2[3])
{
    return mc_mesh_shade_of(p0, p1, p2);
}

/* Vertex v's position, as mc_pmesh_position (inlined: the loop below needs it per face) */
MC_ALWAYS_INLINE void position(const mc_pmesh *pm, uint32_t v, int32_t p[3])
{
    mc_pmesh_position_at(mc_chunk_record(pm->positions, pm->record_shift, 6u, v), p);
}

uint32_t mc_mesh_face(const mc_pmesh_lod *lod, const mc_xform *x, uint32_t f, int32_t p[3][3], mc_raster_vertex v[3])
{
    uint32_t c[3], out = 0;
    mc_pmesh_lod_face(lod, f, c);
    for (int k = 0; k < 3; k++) {
        mc_xvertex xv;
        mc_pmesh_position(lod->pm, c[k], p[k]);
        mc_xform_vertex(x, p[k], &xv);
        out |= xv.flags;
        v[k].x = xv.x, v[k].y = xv.y, v[k].z = xv.z;
    }
    return out;
}

/* floor(v / 16) + 2^22 for |v| < 2^26, shifting nothing negative: two compare as their floor(v / 16) */
MC_ALWAYS_INLINE uint32_t cell16(int32_t v) { return (uint32_t)(v + ((int32_t)1 << 26)) >> 4; }

/* 0 when mc_raster_triangle would certainly draw nothing (raster.c's first tests): no pixel centre
 * c = 16 i + 8 in the bounding box as the top-left rule counts them, xmin <= c < xmax and
 * ymin <= c < ymax, i.e. all corners with the same floor((x - 9) / 16), or all with the same
 * floor((y - 9) / 16); when culling (cull: MC_RASTER_CULL_BACK or 0), a back face or zero area.
 * Faces off the target are left to the rasterizer (few, and its own test finds them). The corners
 * come from mc_xform_vertex, inside its band: |x|, |y| <= 2^21. */
MC_ALWAYS_INLINE int may_cover(const mc_raster_vertex v[3], unsigned cull)
{
    const uint32_t cx0 = cell16(v[0].x - 9), cx1 = cell16(v[1].x - 9), cx2 = cell16(v[2].x - 9);
    const uint32_t cy0 = cell16(v[0].y - 9), cy1 = cell16(v[1].y - 9), cy2 = cell16(v[2].y - 9);
    if (((cx0 ^ cx1) | (cx0 ^ cx2)) == 0 || ((cy0 ^ cy1) | (cy0 ^ cy2)) == 0) return 0;
    if (!cull) return 1;
    const int64_t area = (int64_t)(v[1].x - v[0].x) * (v[2].y - v[0].y) - (int64_t)(v[2].x - v[0].x) * (v[1].y - v[0].y);
    return area < 0;
}

unsigned mc_mesh_clip_face(const mc_xform *x, const int32_t p[3][3], mc_raster_vertex v[MC_XFORM_CLIP_MAX])
{
    int32_t q[3][3];
    mc_xvertex xv[MC_XFORM_CLIP_MAX];
    for (int k = 0; k < 3; k++) mc_xform_view(x, p[k], q[k]);
    const unsigned n = mc_xform_clip_triangle(x, (const int32_t(*)[3])q, xv);
    for (unsigned i = 0; i < n; i++) v[i].x = xv[i].x, v[i].y = xv[i].y, v[i].z = xv[i].z;
    return n;
}

int mc_mesh_face_front(const mc_xform *x, const int32_t p[3][3])
{
    int32_t q[3][3];
    for (int k = 0; k < 3; k++) mc_xform_view(x, p[k], q[k]);
    return mc_xform_front(x, (const int32_t(*)[3])q);
}

/* A face with a corner flagged by the projection: culled by its plane (mc_xform_front), not by its
 * cut polygon's area, else clipped and drawn as a fan with no culling; counted in st. Apart from the
 * loop below (noinline: the common path keeps its registers). */
#if defined(__GNUC__) || defined(__clang__)
__attribute__((noinline))
#endif
static void clipped_face(const mc_pmesh *pm, const mc_xform *x, const uint32_t c[3], unsigned flags, const mc_target *t,
                         mc_mesh_stats *st)
{
    int32_t p[3][3], q[3][3];
    for (int k = 0; k < 3; k++) position(pm, c[k], p[k]), mc_xform_view(x, p[k], q[k]);
    if ((flags & MC_MESH_CULL_BACK) && !mc_xform_front(x, (const int32_t(*)[3])q)) return;
    mc_xvertex xv[MC_XFORM_CLIP_MAX];
    const unsigned n = mc_xform_clip_triangle(x, (const int32_t(*)[3])q, xv);
    if (n == 0) { st->clipped_away++; return; }
    st->clipped++;
    const unsigned color = (flags & MC_MESH_DRAW_PAPER) ? MC_MESH_PAPER : mc_mesh_shade(p[0], p[1], p[2]);
    uint32_t covered = 0;
    for (unsigned i = 1; i + 1 < n; i++) {
        mc_raster_vertex v[3];
        v[0].x = xv[0].x, v[0].y = xv[0].y, v[0].z = xv[0].z;
        v[1].x = xv[i].x, v[1].y = xv[i].y, v[1].z = xv[i].z;
        v[2].x = xv[i + 1].x, v[2].y = xv[i + 1].y, v[2].z = xv[i + 1].z;
        covered += mc_raster_triangle(t, v, (uint8_t)color, 0u);
    }
    st->drawn += covered > 0;
    st->pixels += covered;
}

/* The loop of project_run over vertices v0 .. v0 + n - 1 (position records from r): wide, the 4-byte
 * index width; perspective, the view's. With MC_MESH_SELECT both are constants where called, so that
 * each case is a loop of its own (the orthographic one keeps the position in registers); a firmware
 * keeps one loop (flash), the tests the same every vertex. */
MC_ALWAYS_INLINE uint32_t project_loop(const mc_pmesh_lod *lod, const mc_xform *x, const mc_xform_ortho *o,
                                       mc_xvertex *cache, uint32_t v0, uint32_t n, const uint8_t *r, int wide,
                                       int perspective)
{
    const uint16_t *anc16 = (const uint16_t *)lod->anc;
    const uint32_t *anc32 = (const uint32_t *)lod->anc;
    uint32_t flags = 0;
    for (uint32_t v = v0; v < v0 + n; v++, r += 6) {
        if ((wide ? anc32[v] : anc16[v]) != v) continue;
        if (!perspective && UINTPTR_MAX > 0xFFFFFFFFu) {   /* a 64-bit core reads the position as the values it multiplies */
            mc_xform_ortho_xyz(o, (int64_t)mc_le16(r) - 32768, (int64_t)mc_le16(r + 2) - 32768, (int64_t)mc_le16(r + 4) - 32768,
                               &cache[v]);
        } else {
            int32_t p[3];
            mc_pmesh_position_at(r, p);
            if (perspective) mc_xform_vertex(x, p, &cache[v]);
            else mc_xform_ortho_point(o, p, &cache[v]);
        }
        flags |= cache[v].flags;
    }
    return flags;
}

/* Projects the vertices v0 .. v0 + n - 1 present at the level (their own ancestors) into cache,
 * their position records starting at r; in the usual (orthographic) view with the projection
 * inline (xform_ortho.h), its constants in registers. Returns their flags, or-ed. */
static uint32_t project_run(const mc_pmesh_lod *lod, const mc_xform *x, mc_xvertex *cache, uint32_t v0, uint32_t n,
                            const uint8_t *r)
{
    const int wide = lod->pm->index_bytes != 2, perspective = x->perspective;
    mc_xform_ortho o;
    mc_xform_ortho_init(&o, x);
#if MC_MESH_SELECT
    if (perspective) return project_loop(lod, x, &o, cache, v0, n, r, wide, 1);
    return wide ? project_loop(lod, x, &o, cache, v0, n, r, 1, 0) : project_loop(lod, x, &o, cache, v0, n, r, 0, 0);
#else
    return project_loop(lod, x, &o, cache, v0, n, r, wide, perspective);
#endif
}

/* Projects vertex v into cache[v]; returns its flags. */
static uint32_t project_one(const mc_pmesh *pm, const mc_xform *x, const mc_xform_ortho *o, mc_xvertex *cache, uint32_t v)
{
    int32_t p[3];
    mc_pmesh_position_at(mc_chunk_record(pm->positions, pm->record_shift, 6u, v), p);
    if (x->perspective) mc_xform_vertex(x, p, &cache[v]);
    else mc_xform_ortho_point(o, p, &cache[v]);
    return cache[v].flags;
}

/* Projects every vertex present at the level into cache[v]. At a fine level the positions are read
 * in order, the absent ones skipped; at a coarse one (under a third of the vertices present) only
 * the present ones are visited, the roots by their subtrees and then the vertex of each split made,
 * so that the work follows the level, not the full mesh. The same entries either way. Returns their
 * flags, or-ed. */
static uint32_t project_level(const mc_pmesh_lod *lod, const mc_xform *x, mc_xvertex *cache)
{
    const mc_pmesh *pm = lod->pm;
    const unsigned shift = pm->record_shift;
    const uint32_t chunk = UINT32_C(1) << shift;
    uint32_t flags = 0;
    if (lod->level < pm->vertices / 3u) {
        mc_xform_ortho o;
        mc_xform_ortho_init(&o, x);
        for (uint32_t v = 0; v < pm->vertices; v += mc_pmesh_root_span(pm, v)) flags |= project_one(pm, x, &o, cache, v);
        for (uint32_t s = 0; s < lod->level - pm->base_vertices; s++)
            flags |= project_one(pm, x, &o, cache, mc_pmesh_split_vertex(pm, s));
        return flags;
    }
    for (uint32_t v0 = 0; v0 < pm->vertices; v0 += chunk) {
        const uint32_t n = pm->vertices - v0 < chunk ? pm->vertices - v0 : chunk;
        flags |= project_run(lod, x, cache, v0, n, pm->positions[v0 >> shift].data);
    }
    return flags;
}

int mc_mesh_render(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t,
                   mc_xvertex *cache, mc_mesh_stats *stats)
{
    mc_mesh_stats st;   /* field by field: an aggregate initialiser becomes a memset call at -O0 */
    st.faces = st.drawn = st.skipped = st.pixels = st.clipped = st.clipped_away = 0;
    if (!lod || !lod->pm || !view || !t || !t->color || !t->depth) return MC_ERR_ARG;
    if (t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    const mc_pmesh *pm = lod->pm;
    mc_xform x;
    mc_xform_init(&x, view, t->width, t->height);
    const unsigned rflags = (flags & MC_MESH_CULL_BACK) ? MC_RASTER_CULL_BACK : 0u;
    const int paper = (flags & MC_MESH_DRAW_PAPER) != 0;
    if (cache) project_level(lod, &x, cache);
    const unsigned ib = pm->index_bytes, shift = pm->record_shift;
    const uint32_t faces = lod->faces, chunk = UINT32_C(1) << shift;
    st.faces = faces;
    /* the faces chunk by chunk, each a run of 2^shift records (the last maybe fewer) */
    for (uint32_t f0 = 0; f0 < faces; f0 += chunk) {
        const uint8_t *r = pm->corners[f0 >> shift].data;
        const uint8_t *fb = pm->face_bits ? pm->face_bits[f0 >> shift].data : 0;
        const uint32_t end = faces - f0 < chunk ? faces - f0 : chunk;
        for (uint32_t i = 0; i < end; i++, r += 3u * ib) {
            uint32_t c[3];
            if (ib == 2) {
                const uint16_t *anc = (const uint16_t *)lod->anc;
                c[0] = anc[mc_le16(r)], c[1] = anc[mc_le16(r + 2)], c[2] = anc[mc_le16(r + 4)];
            } else {
                const uint32_t *anc = (const uint32_t *)lod->anc;
                c[0] = anc[mc_le32(r)], c[1] = anc[mc_le32(r + 4)], c[2] = anc[mc_le32(r + 8)];
            }
            int32_t p[3][3];
            mc_raster_vertex v[3];
            uint32_t out = 0;
            if (cache) {
                const mc_xvertex *a = &cache[c[0]], *b = &cache[c[1]], *d = &cache[c[2]];
                out = a->flags | b->flags | d->flags;
                v[0].x = a->x, v[0].y = a->y, v[0].z = a->z;
                v[1].x = b->x, v[1].y = b->y, v[1].z = b->z;
                v[2].x = d->x, v[2].y = d->y, v[2].z = d->z;
            } else {
                for (int k = 0; k < 3; k++) {
                    mc_xvertex xv;
                    position(pm, c[k], p[k]);
                    mc_xform_vertex(&x, p[k], &xv);
                    out |= xv.flags;
                    v[k].x = xv.x, v[k].y = xv.y, v[k].z = xv.z;
                }
            }
            if (out) { clipped_face(pm, &x, c, flags, t, &st); continue; }
            if (!may_cover(v, rflags)) continue;
            unsigned color;
            if (paper) color = MC_MESH_PAPER;
            else if (fb && mc_pmesh_corners_as_full(r, ib, c)) color = MC_FACE_BITS_SHADE(fb[i]);
            else {
                if (cache) position(pm, c[0], p[0]), position(pm, c[1], p[1]), position(pm, c[2], p[2]);
                color = mc_mesh_shade(p[0], p[1], p[2]);
            }
            const uint32_t covered = mc_raster_triangle(t, v, (uint8_t)color, rflags);
            st.drawn += covered > 0;
            st.pixels += covered;
        }
    }
    if (stats) *stats = st;
    return MC_OK;
}

uint32_t mc_mesh_project(const mc_pmesh_lod *lod, const mc_xform *x, mc_xvertex *cache)
{
    return project_level(lod, x, cache);
}
