/* Checks of the mesh reference renderer (runtime/ref/mesh_ref.c), run by tests/accuracy/suite.sh:
 *
 *   meshref_test BUNNY_REF_DUMP KITTEN_REF_DUMP
 *
 * Linked with the bunny00 bake at depth 8 (mc_octree_acc_bunny00), the kitten bake at depth 7
 * (mc_octree_acc_kitten) and the runtime. Prints TAP lines.
 *
 * Synthetic meshes with a known image (320x240, zoom 1: the unit cube spans 240 pixels, its centre
 * at pixel (160, 120); model +y up, +z towards the viewer):
 *   - a square [-1/4, 1/4]^2 at z = 0 facing the viewer covers exactly the 120 x 120 pixels whose
 *     centres lie in [100, 220] x [60, 180], all lit 255 (0.15 + 0.85 |n.z| with n = +z);
 *   - its two triangles, drawn one at a time, cover disjoint pixel sets whose union is the square
 *     (the diagonal runs through pixel centres: the shared-edge rule gives each to one triangle);
 *   - tilted by its normal (0, sin a, cos a): grey 255 (0.15 + 0.85 cos a) rounded, as the generator;
 *   - through a palette: the nearest entry;
 *   - a cube [-1/4, 1/4]^3 at yaw 45 degrees: its silhouette is 120 sqrt(2) x 120 pixels (coverage
 *     within one pixel of perimeter of that area), the -x face (grey 0.15 * 255 = 38) on the left, the
 *     +z face (255) on the right, since the baked light turns with the model;
 *   - the dump file format round trip (write, mc_mesh_ref_load, same image).
 * Against the octree (the runtime's fixed-point render of bunny00 at depth 8, default splat and fill):
 *   - PSNR >= PSNR_MIN at views frontal and yaw 30 degrees, zoom 1. PSNR_MIN is derived per view
 *     from the reference image: how far an octree image may honestly differ from it (see main);
 *   - the outlines agree within one pixel (the same normalisation), and do not when the octree is
 *     moved by two pixels;
 *   - discrimination: the reference of a view 10 degrees off scores below PSNR_MIN.
 * A point set (kitten, octree at depth 7, mc_octree_acc_kitten): the dump is a point set with a splat
 * radius, and every pixel the octree draws lies within 2 pixels of the splats' coverage.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/modelc.h>
#include "mesh_ref.h"

extern const mc_octree mc_octree_acc_bunny00, mc_octree_acc_kitten;

#define W 320
#define H 240
static uint8_t rgb[3 * W * H], cov[W * H], cov2[W * H], idx[W * H];
static int failures;

static void check(int ok, const char *name, const char *fmt, double a, double b)
{
    if (ok) printf("ok - %s\n", name);
    else {
        printf("not ok - %s: ", name);
        printf(fmt, a, b);
        printf("\n");
        failures++;
    }
}

static mc_mesh_ref mesh(double (*pos)[3], double (*nrm)[3], uint32_t nv, uint32_t (*tri)[3], uint32_t nt)
{
    mc_mesh_ref m;
    memset(&m, 0, sizeof m);
    m.shade = 1;
    m.nverts = nv;
    m.ntris = nt;
    m.pos = malloc(sizeof(double) * 3 * nv);
    m.normal = malloc(sizeof(double) * 3 * nv);
    m.rgb = calloc(3 * nv, sizeof(double));
    m.tris = malloc(sizeof(uint32_t) * 3 * (nt + 1));
    memcpy(m.pos, pos, sizeof(double) * 3 * nv);
    memcpy(m.normal, nrm, sizeof(double) * 3 * nv);
    memcpy(m.tris, tri, sizeof(uint32_t) * 3 * nt);
    return m;
}


static int square_exact(const uint8_t *c, const uint8_t *colour, int grey)
{
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int in = x >= 100 && x < 220 && y >= 60 && y < 180;
            if (c[y * W + x] != in) return 0;
            if (in && colour && colour[3 * (y * W + x)] != grey) return 0;
        }
    return 1;
}

static double psnr(const uint8_t *a, const uint8_t *b)
{
    double se = 0;
    for (int i = 0; i < 3 * W * H; i++) { double d = (double)a[i] - b[i]; se += d * d; }
    return se == 0 ? 99 : 10 * log10(255.0 * 255.0 / (se / (3.0 * W * H)));
}

static void octree_image(const mc_octree *s, const mc_view *v, uint8_t *out, uint8_t *c)
{
    static uint8_t col[W * H];
    static uint16_t dep[W * H];
    mc_target t = {col, dep, W, H};
    mc_clear(&t);
    mc_octree_render(s, v, s->depth, NULL, &t, NULL, NULL, NULL);
#ifdef MC_DEPTH_FILLED   /* the runtime has selectable fills (finish.h): its default */
    mc_finish(&t, MC_FILL_DEFAULT);
#else
    mc_finish_pixel_holes(&t);
#endif
    for (int i = 0; i < W * H; i++) {
        c[i] = dep[i] != MC_DEPTH_EMPTY;
        for (int k = 0; k < 3; k++) out[3 * i + k] = c[i] ? s->palette[3 * col[i] + k] : 0;
    }
}

/* pixels covered in a with no covered pixel of b within r pixels (a (2r+1)^2 square) */
static long far_from(const uint8_t *a, const uint8_t *b, int r)
{
    long n = 0;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            if (!a[y * W + x]) continue;
            int near = 0;
            for (int dy = -r; dy <= r && !near; dy++)
                for (int dx = -r; dx <= r && !near; dx++) {
                    int xx = x + dx, yy = y + dy;
                    near = xx >= 0 && yy >= 0 && xx < W && yy < H && b[yy * W + xx];
                }
            n += !near;
        }
    return n;
}

/* The least PSNR an octree image of the reference's view may honestly reach (see PSNR_MIN in main):
 * every pixel on either side of the outline wrong by the whole value of its covered neighbour, and
 * every other pixel wrong by the largest difference to a 4-neighbour of the reference. */
static double psnr_bound(const uint8_t *ref, const uint8_t *c)
{
    double se = 0;
    static const int d4[4][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}};
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            int i = y * W + x;
            double worst = 0;
            for (int k = 0; k < 4; k++) {
                int xx = x + d4[k][0], yy = y + d4[k][1];
                if (xx < 0 || yy < 0 || xx >= W || yy >= H) continue;
                int j = yy * W + xx;
                double e = 0;
                if (c[i] != c[j]) {   /* an outline: the covered one's whole value */
                    int v = c[i] ? i : j;
                    for (int a = 0; a < 3; a++) e += (double)ref[3 * v + a] * ref[3 * v + a];
                } else if (c[i]) {
                    for (int a = 0; a < 3; a++) e += ((double)ref[3 * i + a] - ref[3 * j + a]) * ((double)ref[3 * i + a] - ref[3 * j + a]);
                }
                if (e > worst) worst = e;
            }
            se += worst;
        }
    return se == 0 ? 99 : 10 * log10(255.0 * 255.0 / (se / (3.0 * W * H)));
}

static long count(const uint8_t *c) { long n = 0; for (int i = 0; i < W * H; i++) n += c[i]; return n; }

int main(int argc, char **argv)
{
    if (argc != 3) { fprintf(stderr, "usage: meshref_test BUNNY_REF_DUMP KITTEN_REF_DUMP\n"); return 2; }
    mc_view v = mc_view_default();
    char name[200];

    /* ---- the square ------------------------------------------------------------------------------ */
    double sq[4][3] = {{-0.25, -0.25, 0}, {0.25, -0.25, 0}, {0.25, 0.25, 0}, {-0.25, 0.25, 0}};
    double up[4][3] = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
    uint32_t st[2][3] = {{0, 1, 2}, {0, 2, 3}};
    mc_mesh_ref m = mesh(sq, up, 4, st, 2);
    long n = mc_mesh_ref_render(&m, &v, W, H, NULL, 0, rgb, cov, NULL);
    check(n == 120 * 120 && square_exact(cov, rgb, 255), "square: exactly the 120x120 pixels, grey 255",
          "%g covered, %g expected", (double)n, 14400);
    m.ntris = 1;
    long n1 = mc_mesh_ref_render(&m, &v, W, H, NULL, 0, rgb, cov2, NULL);
    memcpy(m.tris, st[1], sizeof st[1]);
    long n2 = mc_mesh_ref_render(&m, &v, W, H, NULL, 0, rgb, cov, NULL);
    int overlap = 0;
    for (int i = 0; i < W * H; i++) { overlap += cov[i] && cov2[i]; cov[i] |= cov2[i]; }
    check(n1 + n2 == 14400 && !overlap && square_exact(cov, NULL, 0),
          "square: the two triangles share the diagonal's pixels without overlap or gap",
          "%g + overlap %g", (double)(n1 + n2), overlap);
    memcpy(m.tris, st, sizeof st);
    m.ntris = 2;
    /* a tilted normal: the generator's light, rounded */
    const double a = 0.7;
    for (int k = 0; k < 4; k++) m.normal[3 * k + 1] = sin(a), m.normal[3 * k + 2] = cos(a);
    mc_mesh_ref_render(&m, &v, W, H, NULL, 0, rgb, cov, NULL);
    int grey = (int)lround(255 * (0.15 + 0.85 * cos(a)));
    check(square_exact(cov, rgb, grey), "square: frontal light of a tilted normal", "grey %g, expected %g",
          rgb[3 * (120 * W + 160)], grey);
    /* a palette: nearest entry, index reported */
    const uint8_t pal[9] = {0, 0, 0, 100, 100, 100, 250, 250, 250};
    for (int k = 0; k < 4; k++) m.normal[3 * k + 1] = 0, m.normal[3 * k + 2] = 1;
    mc_mesh_ref_render(&m, &v, W, H, pal, 3, rgb, cov, idx);
    check(square_exact(cov, rgb, 250) && idx[120 * W + 160] == 2, "square: mapped to the nearest palette entry",
          "grey %g, index %g", rgb[3 * (120 * W + 160)], idx[120 * W + 160]);
    /* off-centre placement: the same square moved by +1/8 cube side along x is 30 pixels to the right */
    for (int k = 0; k < 4; k++) m.pos[3 * k] += 0.125;
    n = mc_mesh_ref_render(&m, &v, W, H, NULL, 0, rgb, cov, NULL);
    check(n == 14400 && cov[60 * W + 130] && !cov[60 * W + 129] && cov[60 * W + 249] && !cov[60 * W + 250],
          "square: moved 1/8 cube side right, 30 pixels right", "%g covered %g", (double)n, 0);
    mc_mesh_ref_free(&m);

    /* ---- the cube at yaw 45 degrees ------------------------------------------------------------------ */
    double cp[24][3], cn[24][3];
    uint32_t ct[12][3];
    for (int f = 0; f < 6; f++) {   /* face f: axis f / 2, sign +- */
        int ax = f / 2, u = (ax + 1) % 3, w = (ax + 2) % 3;
        double s = f % 2 ? -0.25 : 0.25;
        const double c4[4][2] = {{-0.25, -0.25}, {0.25, -0.25}, {0.25, 0.25}, {-0.25, 0.25}};
        for (int k = 0; k < 4; k++) {
            double *p = cp[4 * f + k], *q = cn[4 * f + k];
            p[ax] = s, p[u] = c4[k][0], p[w] = c4[k][1];
            q[ax] = s > 0 ? 1 : -1, q[u] = 0, q[w] = 0;
        }
        uint32_t b = 4 * (uint32_t)f;
        ct[2 * f][0] = b, ct[2 * f][1] = b + 1, ct[2 * f][2] = b + 2;
        ct[2 * f + 1][0] = b, ct[2 * f + 1][1] = b + 2, ct[2 * f + 1][2] = b + 3;
    }
    m = mesh(cp, cn, 24, ct, 12);
    mc_view v45 = v;
    v45.yaw = MC_ANGLE_FULL / 8;
    n = mc_mesh_ref_render(&m, &v45, W, H, NULL, 0, rgb, cov, NULL);
    double area = 120 * sqrt(2.0) * 120, perim = 2 * (120 * sqrt(2.0) + 120);
    check(fabs(n - area) <= perim / 2, "cube at yaw 45: silhouette area 120 sqrt(2) x 120 pixels",
          "%g covered, %g expected", (double)n, area);
    int left = rgb[3 * (120 * W + 130)], right = rgb[3 * (120 * W + 190)];
    check(left == 38 && right == 255, "cube at yaw 45: -x face (grey 38) left, +z face (255) right",
          "left %g right %g", left, right);

    /* ---- dump file round trip --------------------------------------------------------------------- */
    const char *tmp = "build/tests/accuracy/cube.ref";
    FILE *f = fopen(tmp, "wb");
    if (f) {
        uint32_t hdr[4] = {0, 1, 24, 12};
        double g[5] = {1, 0, 0, 0, 0};
        fwrite("MCREF01\n", 1, 8, f);
        fwrite(hdr, 4, 4, f);
        fwrite(g, 8, 5, f);
        for (int i = 0; i < 24; i++) { double z3[3] = {0, 0, 0}; fwrite(cp[i], 8, 3, f); fwrite(cn[i], 8, 3, f); fwrite(z3, 8, 3, f); }
        fwrite(ct, 12, 12, f);
        fclose(f);
    }
    mc_mesh_ref lm;
    char err[300];
    int rc = mc_mesh_ref_load(tmp, &lm, err, sizeof err);
    long n3 = rc == 0 ? mc_mesh_ref_render(&lm, &v45, W, H, NULL, 0, rgb, cov2, NULL) : -1;
    check(rc == 0 && n3 == n && !memcmp(cov, cov2, sizeof cov), "dump file round trip: the same image",
          "load %g, covered %g", rc, (double)n3);
    if (rc == 0) mc_mesh_ref_free(&lm);
    mc_mesh_ref_free(&m);
    check(mc_mesh_ref_load("build/tests/accuracy/no-such.ref", &lm, err, sizeof err) == -1,
          "missing dump: an error, no crash", "%g %g", 0, 0);

    /* ---- against the octree of bunny00 ---------------------------------------------------------------
     * PSNR_MIN, derived per view from the reference image (psnr_bound). At depth 8 and zoom 1 a cell
     * is 240 / 256 = 0.94 pixels and the renderer draws one pixel per cell centre, which lies within
     * half a cell of the surface: so the octree's outline (and the edges where one part hides
     * another) may lie a pixel off the mesh's, and a pixel there may be wrong by the whole value of the
     * model against the background; elsewhere a cell's colour is the light at one point of its surface
     * up to a cell away from the pixel centre, so a pixel may be off by about the light's change from
     * one pixel to the next. psnr_bound charges every pixel the worst of these over its 4-neighbours:
     * a bound, not an estimate (the octree's PSNR is well above it). A render in the right place with
     * the right light cannot fall below it; a misplaced or mis-lit model does: the negative control,
     * the reference 10 degrees off (the same model, palette and light), must. */
    mc_mesh_ref b;
    if (mc_mesh_ref_load(argv[1], &b, err, sizeof err) != 0) {
        printf("not ok - bunny00 reference: %s\n", err);
        return 1;
    }
    const mc_octree *s = &mc_octree_acc_bunny00;
    static uint8_t oct[3 * W * H], ocov[W * H];
    const int yaws[2] = {0, 30};
    for (int i = 0; i < 2; i++) {
        mc_view vv = mc_view_default();
        vv.yaw = (int32_t)lround(yaws[i] / 360.0 * MC_ANGLE_FULL);
        mc_mesh_ref_render(&b, &vv, W, H, s->palette, s->palette_size, rgb, cov, NULL);
        octree_image(s, &vv, oct, ocov);
        double p = psnr(oct, rgb), PSNR_MIN = psnr_bound(rgb, cov);
        snprintf(name, sizeof name, "bunny00 depth 8, yaw %d, zoom 1: octree vs mesh reference PSNR >= %.2f dB "
                 "(derived bound)", yaws[i], PSNR_MIN);
        check(p >= PSNR_MIN, name, "%.2f dB < %.2f", p, PSNR_MIN);
        printf("# yaw %d: PSNR %.2f dB, bound %.2f dB\n", yaws[i], p, PSNR_MIN);
        /* the same normalisation: the outlines agree within a pixel (a cell is 0.94 pixels; its centre
         * lies within half a cell of the surface), allowing 0.1 % of the pixels for thin parts */
        long fo = far_from(ocov, cov, 1), fm = far_from(cov, ocov, 1), lim = count(cov) / 1000;
        snprintf(name, sizeof name, "bunny00 yaw %d: outlines within one pixel (all but %ld pixels)", yaws[i], lim);
        check(fo <= lim && fm <= lim, name, "%g octree and %g mesh pixels farther", (double)fo, (double)fm);
        printf("# farther than a pixel: %ld octree, %ld mesh pixels of %ld\n", fo, fm, count(cov));
        if (i == 0) {   /* discrimination: the octree moved by 2 pixels fails this check */
            mc_view moved = vv;
            moved.tx = 2;
            static uint8_t mrgb[3 * W * H], mcov[W * H];
            octree_image(s, &moved, mrgb, mcov);
            long a2 = far_from(mcov, cov, 1), b2 = far_from(cov, mcov, 1);
            check(a2 > lim || b2 > lim, "bunny00: the octree moved by 2 pixels fails the outline check",
                  "%g and %g pixels farther", (double)a2, (double)b2);
            printf("# moved 2 pixels: %ld octree, %ld mesh pixels farther\n", a2, b2);
        }
        if (i == 1) {
            mc_view off = vv;
            off.yaw += (int32_t)lround(10 / 360.0 * MC_ANGLE_FULL);
            mc_mesh_ref_render(&b, &off, W, H, s->palette, s->palette_size, rgb, cov, NULL);
            double q = psnr(oct, rgb);
            check(q < PSNR_MIN, "bunny00: the reference 10 degrees off scores below the bound",
                  "%.2f dB >= %.2f", q, PSNR_MIN);
            printf("# 10 degrees off: PSNR %.2f dB\n", q);
        }
    }
    mc_mesh_ref_free(&b);

    /* ---- a point set: kitten (5210 points with normals), its octree at depth 7 ---------------------
     * Each point is a disc of 3/4 of the mean spacing to its 6 nearest neighbours. A drawn cell's
     * centre lies within half a cell diagonal (0.94 * sqrt(3) = 1.6 pixels at depth 7) of a point, so
     * every pixel the octree draws is within 2 pixels of the reference's coverage (0.1 % allowed). */
    mc_mesh_ref k;
    if (mc_mesh_ref_load(argv[2], &k, err, sizeof err) != 0) {
        printf("not ok - kitten reference: %s\n", err);
        return 1;
    }
    check(k.is_points && k.nverts == 5210 && k.radius > 0 && k.radius < 0.05,
          "kitten: a point set of 5210 points with a splat radius", "%g points, radius %g", k.nverts, k.radius);
    const mc_octree *ks = &mc_octree_acc_kitten;
    mc_view kv = mc_view_default();
    kv.yaw = MC_ANGLE_FULL / 12;
    long kn = mc_mesh_ref_render(&k, &kv, W, H, ks->palette, ks->palette_size, rgb, cov, NULL);
    octree_image(ks, &kv, oct, ocov);
    long kf = far_from(ocov, cov, 2);
    check(kn > 10000 && kf <= count(ocov) / 1000, "kitten yaw 30: every octree pixel within 2 pixels of the splats",
          "%g covered, %g farther", (double)kn, (double)kf);
    printf("# kitten: %ld pixels covered by the splats, %ld by the octree, %ld of them farther than 2 pixels\n",
           kn, count(ocov), kf);
    mc_mesh_ref_free(&k);
    return failures ? 1 : 0;
}
