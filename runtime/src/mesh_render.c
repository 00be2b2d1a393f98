/* Flat-shaded progressive meshes: see modelc/mesh_render.h. */
#include "modelc/mesh_render.h"

/* ((2j - 1) / 62)^2 in Q30, j = 1 .. 31: |n.z| / |n| at least (j - 1/2) / 31 means shade j or more */
static const uint32_t shade_limit[MC_MESH_SHADES - 1] = {
    279329, 2513964, 6983232, 13687136, 22625673, 33798845, 47206651, 62849092, 80726167, 100837877,
    123184221, 147765199, 174580812, 203631059, 234915940, 268435456, 304189606, 342178391, 382401810,
    424859863, 469552551, 516479873, 565641830, 617038421, 670669646, 726535506, 784636000, 844971128,
    907540891, 972345289, 1039384320,
};

static uint64_t mag(int64_t v) { return v < 0 ? 0u - (uint64_t)v : (uint64_t)v; }

unsigned mc_mesh_shade(const int32_t p0[3], const int32_t p1[3], const int32_t p2[3])
{
    int64_t a[3], b[3], n[3];
    for (int i = 0; i < 3; i++) a[i] = (int64_t)p1[i] - p0[i], b[i] = (int64_t)p2[i] - p0[i];
    n[0] = a[1] * b[2] - a[2] * b[1];   /* |a|, |b| < 2^17 a component: |n| < 2^35 */
    n[1] = a[2] * b[0] - a[0] * b[2];
    n[2] = a[0] * b[1] - a[1] * b[0];
    uint64_t m = mag(n[0]) | mag(n[1]) | mag(n[2]);
    if (m == 0) return MC_MESH_SHADES / 2;
    int s = 0;
    while ((m >> s) >= ((uint64_t)1 << 15)) s++;
    /* components below 2^15 after the shift: squares below 2^30, so the products below stay in 64 bits */
    int64_t x = n[0] / ((int64_t)1 << s), y = n[1] / ((int64_t)1 << s), z = n[2] / ((int64_t)1 << s);
    uint64_t len2 = (uint64_t)(x * x + y * y + z * z), z2 = (uint64_t)(z * z) << 30;
    if (len2 == 0) return MC_MESH_SHADES / 2;
    unsigned lo = 0, hi = MC_MESH_SHADES - 1;   /* the number of limits z2 / len2 reaches */
    while (lo < hi) {
        unsigned mid = (lo + hi + 1) / 2;
        if (z2 >= (uint64_t)shade_limit[mid - 1] * len2) lo = mid;
        else hi = mid - 1;
    }
    return lo;
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

int mc_mesh_render(const mc_pmesh_lod *lod, const mc_view *view, unsigned flags, const mc_target *t,
                   mc_mesh_stats *stats)
{
    mc_mesh_stats st;   /* field by field: an aggregate initialiser becomes a memset call at -O0 */
    st.faces = st.drawn = st.skipped = st.pixels = 0;
    if (!lod || !lod->pm || !view || !t || !t->color || !t->depth) return MC_ERR_ARG;
    if (t->width > MC_TARGET_MAX || t->height > MC_TARGET_MAX) return MC_ERR_SIZE;
    mc_xform x;
    mc_xform_init(&x, view, t->width, t->height);
    const unsigned rflags = (flags & MC_MESH_CULL_BACK) ? MC_RASTER_CULL_BACK : 0u;
    st.faces = lod->faces;
    for (uint32_t f = 0; f < lod->faces; f++) {
        int32_t p[3][3];
        mc_raster_vertex v[3];
        if (mc_mesh_face(lod, &x, f, p, v)) { st.skipped++; continue; }
        const unsigned color = (flags & MC_MESH_DRAW_PAPER) ? MC_MESH_PAPER : mc_mesh_shade(p[0], p[1], p[2]);
        uint32_t covered = mc_raster_triangle(t, v, (uint8_t)color, rflags);
        st.drawn += covered > 0;
        st.pixels += covered;
    }
    if (stats) *stats = st;
    return MC_OK;
}
