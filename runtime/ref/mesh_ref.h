/* Double-precision reference renderer of the ORIGINAL model (not the octree), for tests and
 * benchmarks only: never linked into a viewer or firmware. It uses malloc and doubles.
 *
 * Input: the file `modelc MODEL --dump-reference FILE` writes (gen/reference.cpp): the model's
 * triangles or points with every position mapped into the unit cube [-1/2, 1/2]^3 by the same grid the
 * octree is built on, so that the octree's cell centres and the reference agree on where the model is.
 * Layout (little-endian, as the host that wrote it):
 *   char magic[8] "MCREF01\n"; uint32 kind (0 mesh, 1 points); uint32 shade (1: colour each pixel
 *   from the frontal light of the interpolated normal, 0: from the rgb values); uint32 nverts, ntris;
 *   double side, origin[3] (the model-frame grid, informational); double radius (points: splat radius
 *   in cube sides); nverts x {double pos[3], normal[3], rgb[3] (0..255)}; ntris x uint32[3].
 *
 * Rendering follows modelc/xform.h exactly as runtime/ref/ref.c does (the same clamped view, the same
 * angles, pixel i covering [i, i+1), depth 1 - z in cube sides, smaller nearer):
 *   - meshes: every triangle, two-sided, z-buffered; a pixel is covered when its centre (x + 1/2,
 *     y + 1/2) lies in a triangle (edges shared by two triangles cover a centre once). Its colour is
 *     the generator's shading at that surface point (gen/voxel.cpp): the barycentric blend of the
 *     vertex normals lit by the fixed frontal light 0.15 + 0.85 |n.z| / |n| in the model frame (so
 *     the light turns with the model, as in the baked colours), or the blend of the vertex colours;
 *     rounded to bytes as the generator does, then mapped to the nearest entry of `palette` (squared
 *     RGB distance, first wins, as gen/octree.cpp maps node colours) when a palette is given.
 *     Perspective: barycentrics are corrected for the projection; triangles with a vertex nearer than
 *     the near plane (1/64 cube side before the eye) are skipped.
 *   - point sets: each point a disc of the dump's radius (at least half a pixel), its colour as given.
 */
#ifndef MODELC_MESH_REF_H
#define MODELC_MESH_REF_H

#include <stddef.h>
#include <stdint.h>
#include <modelc/xform.h>

typedef struct mc_mesh_ref {
    int is_points;
    int shade;
    uint32_t nverts, ntris;
    double side, origin[3], radius;
    double *pos, *normal, *rgb;   /* 3 * nverts each */
    uint32_t *tris;               /* 3 * ntris */
} mc_mesh_ref;

/* Loads FILE; returns 0, or -1 with a one-line reason in err. */
int mc_mesh_ref_load(const char *path, mc_mesh_ref *m, char *err, size_t errlen);
void mc_mesh_ref_free(mc_mesh_ref *m);

/* The image of the reference: out_rgb (3 * width * height bytes; background 0, 0, 0) and
 * out_covered (width * height bytes, 1 where the model is); out_index (may be NULL) receives the
 * palette index per covered pixel (0 elsewhere) when a palette is given. palette may be NULL (true
 * colour). Returns the number of covered pixels, or -1 when out of memory. */
long mc_mesh_ref_render(const mc_mesh_ref *m, const mc_view *view, unsigned width, unsigned height,
                        const uint8_t *palette, unsigned palette_size, uint8_t *out_rgb,
                        uint8_t *out_covered, uint8_t *out_index);

#endif
