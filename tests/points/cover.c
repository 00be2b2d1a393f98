/* How much of a model's silhouette a baked point set leaves showing background or the model's far
 * side, against the double-precision reference of a mesh of the same surface (tests/points/suite.sh).
 *
 *   cover MESH_DUMP SET_DUMP [fill] YAW:PITCH...
 *
 * Linked with one bake (its NAME_app.c: mc_app_model) and the runtime as the viewers have it.
 * MESH_DUMP is `modelc MESH --dump-reference` of the surface (runtime/ref/mesh_ref.h), SET_DUMP the
 * same of the point set that was baked: the mesh's positions are mapped from its grid cube into the
 * point set's (both dumps carry theirs), so the two line up whatever the point set's bounding box.
 *
 * Each view (degrees; zoom 1, orthographic, 320x240: the cube spans 240 pixels, a depth-8 leaf 0.94
 * of a pixel) is drawn by mc_octree_render at the octree's depth with the default splat, then, with
 * `fill`, finished by mc_finish's default (what the viewer shows). Inside the reference's silhouette
 * (mc_mesh_ref_render's coverage) a pixel is
 *   - background: nothing drawn on it;
 *   - far side: drawn, but more than FAR_CELLS leaf sides behind the reference's front surface there
 *     (the mesh's own z-buffer, below; the runtime's depth read in cube sides through the scale that
 *     modelc/depth.h promises and octree_render.c sets: the bounding sphere's diameter over the fewest
 *     halvings that bring it under MC_DEPTH_SPAN units).
 * Prints one line per view and the total: "view Y:P inside N background B far F share S outside O"
 * and "total inside N background B far F share S worst W outside O" (shares in per cent, worst = the
 * largest view share, outside = drawn pixels outside the silhouette). A dense bake of the mesh itself
 * scores a few tenths of a per cent, from the lattice gaps of turned views (the suite checks it, so
 * a wrong depth scale would show there first). With COVER_PPM=PREFIX set, each view is also written
 * to PREFIX-YAW-PITCH.ppm: the frame, background inside the silhouette red, far side blue.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/modelc.h>
#include <modelc/app.h>
#include <modelc/depth.h>
#include "mesh_ref.h"
#include "ref.h"

#define W 320
#define H 240
/* "clearly behind": a leaf centre lies within half a cell diagonal of the surface it samples, and a
 * splat or a leaf near the silhouette may stand for a steeper part of the surface than the pixel
 * centre's; the far side of the catalogue's shapes lies tens of cells behind */
#define FAR_CELLS 4.0

static uint8_t color[W * H], rgb[3 * W * H], cov[W * H];
static uint16_t depth[W * H];
static double zref[W * H];

/* The reference's front surface: depth 1 - z (cube sides, smaller nearer) at each pixel centre,
 * orthographic, as mesh_ref.c projects. */
static void front_depth(const mc_mesh_ref *m, const double *pos, const mc_view *view)
{
    mc_view v = mc_view_clamp(view, W, H);
    double r[3][3];
    mc_ref_rotation(&v, r);
    const double scale = v.zoom / 65536.0 * (W < H ? W : H), cx = W / 2.0 + v.tx, cy = H / 2.0 + v.ty;
    for (int i = 0; i < W * H; i++) zref[i] = HUGE_VAL;
    for (uint32_t t = 0; t < m->ntris; t++) {
        double sx[3], sy[3], sz[3];
        for (int k = 0; k < 3; k++) {
            const double *p = pos + 3 * m->tris[3 * t + k];
            double q[3];
            for (int a = 0; a < 3; a++) q[a] = r[a][0] * p[0] + r[a][1] * p[1] + r[a][2] * p[2];
            sx[k] = cx + scale * q[0], sy[k] = cy - scale * q[1], sz[k] = 1.0 - q[2];
        }
        double area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0]);
        if (!(fabs(area) > 0)) continue;
        long x0 = (long)ceil(fmin(sx[0], fmin(sx[1], sx[2])) - 0.5), x1 = (long)floor(fmax(sx[0], fmax(sx[1], sx[2])) - 0.5);
        long y0 = (long)ceil(fmin(sy[0], fmin(sy[1], sy[2])) - 0.5), y1 = (long)floor(fmax(sy[0], fmax(sy[1], sy[2])) - 0.5);
        if (x0 < 0) x0 = 0;
        if (y0 < 0) y0 = 0;
        if (x1 > W - 1) x1 = W - 1;
        if (y1 > H - 1) y1 = H - 1;
        for (long y = y0; y <= y1; y++)
            for (long x = x0; x <= x1; x++) {
                double px = x + 0.5, py = y + 0.5, l[3];
                for (int k = 0; k < 3; k++) {
                    int a = (k + 1) % 3, b = (k + 2) % 3;
                    l[k] = ((sx[b] - sx[a]) * (py - sy[a]) - (sy[b] - sy[a]) * (px - sx[a])) / area;
                }
                if (l[0] < 0 || l[1] < 0 || l[2] < 0) continue;
                double z = l[0] * sz[0] + l[1] * sz[1] + l[2] * sz[2];
                if (z < zref[y * W + x]) zref[y * W + x] = z;
            }
    }
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: cover MESH_DUMP SET_DUMP [fill] YAW:PITCH...\n");
        return 2;
    }
    mc_mesh_ref m, s;
    char err[256];
    if (mc_mesh_ref_load(argv[1], &m, err, sizeof err) != 0 || mc_mesh_ref_load(argv[2], &s, err, sizeof err) != 0) {
        fprintf(stderr, "cover: %s\n", err);
        return 2;
    }
    if (m.is_points) {
        fprintf(stderr, "cover: %s is a point set, not a mesh\n", argv[1]);
        return 2;
    }
    /* the mesh's unit-cube positions moved into the point set's unit cube, through the model frame */
    for (uint32_t i = 0; i < 3 * m.nverts; i++) {
        const int a = (int)(i % 3);
        const double model = (m.pos[i] + 0.5) * m.side + m.origin[a];
        m.pos[i] = (model - s.origin[a]) / s.side - 0.5;
    }
    const mc_octree *o = mc_app_model.model->octree;
    if (!o) {
        fprintf(stderr, "cover: the bake has no octree\n");
        return 2;
    }
    int fill = 0, first = 3;
    if (strcmp(argv[3], "fill") == 0) fill = 1, first = 4;
    const mc_target t = {color, depth, W, H};
    long all_in = 0, all_bg = 0, all_far = 0, all_out = 0;
    double worst = 0;
    for (int a = first; a < argc; a++) {
        double yaw, pitch;
        if (sscanf(argv[a], "%lf:%lf", &yaw, &pitch) != 2) {
            fprintf(stderr, "cover: %s: expected YAW:PITCH in degrees\n", argv[a]);
            return 2;
        }
        mc_view v = mc_view_default();
        v.yaw = (int32_t)lround(yaw / 360.0 * MC_ANGLE_FULL);
        v.pitch = (int32_t)lround(pitch / 360.0 * MC_ANGLE_FULL);
        mc_clear(&t);
        if (mc_octree_render(o, &v, o->depth, NULL, &t, NULL, NULL, NULL) != MC_OK) {
            fprintf(stderr, "cover: mc_octree_render failed\n");
            return 2;
        }
        if (fill) mc_finish(&t, MC_FILL_DEFAULT);
        if (mc_mesh_ref_render(&m, &v, W, H, NULL, 0, rgb, cov, NULL) < 0) return 2;
        front_depth(&m, m.pos, &v);
        /* the renderer's depth scale for this view: radius and shift as octree_render.c sets them */
        const mc_view cv = mc_view_clamp(&v, W, H);
        const int64_t scale = (int64_t)cv.zoom * (W < H ? W : H);                  /* Q16 pixels per side */
        const int64_t radius = mc_mul_shift64(scale, 929887697, 30 + 16 - MC_FRAC_BITS) + 2 * MC_MAX_DEPTH;
        int zshift = 0;
        while (((uint32_t)(2 * radius) >> zshift) >= MC_DEPTH_SPAN) zshift++;
        const double zroot = (double)((radius >> zshift) + MC_MAX_DEPTH);
        const double units = scale / 65536.0 * ldexp(1.0, MC_FRAC_BITS - zshift);   /* per cube side */
        const double far = FAR_CELLS / (double)(1u << o->depth);                    /* cube sides */
        long in = 0, bg = 0, behind = 0, outside = 0;
        for (int i = 0; i < W * H; i++) {
            if (!cov[i]) {
                outside += depth[i] != MC_DEPTH_EMPTY;
                continue;
            }
            in++;
            if (depth[i] == MC_DEPTH_EMPTY) { bg++; continue; }
            if (depth[i] == MC_DEPTH_FILLED || !(zref[i] < HUGE_VAL)) continue;   /* filled: no depth */
            /* the drawn leaf's 1 - z: the root sits at zroot, z towards the viewer lowers the depth */
            const double d = 1.0 - (zroot - depth[i]) / units;
            if (d > zref[i] + far) behind++;
        }
        const char *ppm = getenv("COVER_PPM");   /* for looking: one picture per view */
        if (ppm) {
            char path[512];
            snprintf(path, sizeof path, "%s-%g-%g.ppm", ppm, yaw, pitch);
            FILE *f = fopen(path, "wb");
            if (f) {
                fprintf(f, "P6 %d %d 255\n", W, H);
                for (int i = 0; i < W * H; i++) {
                    uint8_t c[3] = {0, 0, 0};
                    if (depth[i] != MC_DEPTH_EMPTY && depth[i] != MC_DEPTH_FILLED) {
                        const double d = 1.0 - (zroot - depth[i]) / units;
                        const uint8_t *p = o->palette + 3 * color[i];
                        c[0] = p[0], c[1] = p[1], c[2] = p[2];
                        if (cov[i] && zref[i] < HUGE_VAL && d > zref[i] + far) c[0] = 0, c[1] = 0, c[2] = 255;
                    } else if (cov[i] && depth[i] == MC_DEPTH_EMPTY) {
                        c[0] = 255;
                    }
                    fwrite(c, 1, 3, f);
                }
                fclose(f);
            }
        }
        const double share = in ? 100.0 * (bg + behind) / in : 100.0;
        printf("view %g:%g inside %ld background %ld far %ld share %.3f outside %ld\n", yaw, pitch, in, bg, behind, share,
               outside);
        if (share > worst) worst = share;
        all_in += in, all_bg += bg, all_far += behind, all_out += outside;
    }
    printf("total inside %ld background %ld far %ld share %.3f worst %.3f outside %ld\n", all_in, all_bg, all_far,
           all_in ? 100.0 * (all_bg + all_far) / all_in : 100.0, worst, all_out);
    mc_mesh_ref_free(&m);
    mc_mesh_ref_free(&s);
    return 0;
}
