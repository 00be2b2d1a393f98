/* Synthetic camera sequences with exact ground truth for the tracker's tests and benchmarks, rendered
 * in double precision independently of the runtime: the baked edge model's faces (its positions,
 * read through edges.h; nothing of the runtime's projection or rasterization), flat shaded by a
 * light, over a cluttered background, with noise, blur, a passing occluder and a sudden jump of
 * the object's pose. Linked with a bake (the .c files in build/NAME/) for its mc_model_NAME; never part of a
 * tracker.
 *
 *   synth NAME --out DIR [--frames N] [--size WxH] [--camera px,py,u0,v0] [--start tx,ty,tz,tux,tuy,tuz]
 *         [--seed S] [--clutter N] [--noise SIGMA] [--blur 0|1] [--occlude FIRST:LAST] [--jump K]
 *         [--jump-turn ax,ay,az] [--jump-move dx,dy,dz] [--speed F]
 *
 * Writes DIR/image%04d.pgm (P5, 8-bit), DIR/truth.csv (frame,tx,ty,tz,tux,tuy,tuz: the pose of each
 * frame, ViSP's convention: metres, theta-u radians, object to camera), DIR/init.pos (frame 0's pose
 * as a ViSP .pos file) and DIR/orientation.txt (each frame's true rotation vector, for the 3-DOF
 * mode). Each pixel is the mean of a 4 x 4 grid of samples (ViSP's convention: pixel (i, j) spans
 * u in [i - 1/2, i + 1/2)); a sample sees the nearest face whose projection holds it.
 *
 * Motion: the translation drifts along a slow Lissajous path (about 1.5 mm a frame at --speed 1)
 * and the object turns about a slowly tilting axis (about 0.6 degrees a frame); at frame --jump the
 * pose jumps and carries on from there: turned by --jump-turn (a rotation vector in degrees, camera
 * axes: x right, y down, z ahead; default 15,20,0, 25 degrees) and moved by --jump-move (mm, camera
 * axes; default 40,-25,30).
 */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <modelc/model.h>

#ifndef SYNTH_MODEL
#error "compile with -DSYNTH_MODEL=mc_model_NAME"
#endif
extern const mc_model SYNTH_MODEL;

#define PI 3.14159265358979323846
#define SS 4   /* samples per pixel side */

typedef struct { double r[3][3], t[3]; } pose_d;

static uint64_t rng_state = 0x853c49e6748fea9bULL;
static double uniform(void)   /* [0, 1) */
{
    rng_state = rng_state * 6364136223846793005ULL + 1442695040888963407ULL;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}
static double gauss(void)
{
    const double u = uniform() + 1e-12, v = uniform();
    return sqrt(-2 * log(u)) * cos(2 * PI * v);
}

static void rot_from_tu(const double tu[3], double r[3][3])
{
    const double th = sqrt(tu[0] * tu[0] + tu[1] * tu[1] + tu[2] * tu[2]);
    double u[3] = {1, 0, 0};
    if (th > 1e-15)
        for (int k = 0; k < 3; k++) u[k] = tu[k] / th;
    const double c = cos(th), s = sin(th), C = 1 - c;
    r[0][0] = c + u[0] * u[0] * C, r[0][1] = u[0] * u[1] * C - u[2] * s, r[0][2] = u[0] * u[2] * C + u[1] * s;
    r[1][0] = u[1] * u[0] * C + u[2] * s, r[1][1] = c + u[1] * u[1] * C, r[1][2] = u[1] * u[2] * C - u[0] * s;
    r[2][0] = u[2] * u[0] * C - u[1] * s, r[2][1] = u[2] * u[1] * C + u[0] * s, r[2][2] = c + u[2] * u[2] * C;
}

static void tu_from_rot(const double r[3][3], double tu[3])
{
    const double c = (r[0][0] + r[1][1] + r[2][2] - 1) / 2;
    const double th = acos(c > 1 ? 1 : c < -1 ? -1 : c);
    double v[3] = {r[2][1] - r[1][2], r[0][2] - r[2][0], r[1][0] - r[0][1]};
    const double s = sin(th);
    if (th < 1e-12) {
        tu[0] = v[0] / 2, tu[1] = v[1] / 2, tu[2] = v[2] / 2;
        return;
    }
    if (PI - th < 1e-6) {   /* near pi: from the diagonal */
        double u[3];
        for (int k = 0; k < 3; k++) u[k] = sqrt(fmax(0, (r[k][k] + 1) / 2));
        if (r[0][1] < 0) u[1] = -u[1];
        if (r[0][2] < 0) u[2] = -u[2];
        for (int k = 0; k < 3; k++) tu[k] = u[k] * th;
        return;
    }
    for (int k = 0; k < 3; k++) tu[k] = v[k] * th / (2 * s);
}

static void matmul(const double a[3][3], const double b[3][3], double c[3][3])
{
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++) c[i][j] = a[i][0] * b[0][j] + a[i][1] * b[1][j] + a[i][2] * b[2][j];
}

/* the pose of frame k; from frame jump (when > 0) turned by jump_turn (degrees) and moved by
 * jump_move (mm) */
static void truth(int k, const double start[6], double speed, int jump, const double jump_turn[3],
                  const double jump_move[3], pose_d *p)
{
    const double s = speed * k;
    double tu[3];
    /* the turn: angle along a tilting axis, composed after the start rotation */
    double ax[3] = {0.48 + 0.2 * sin(0.01 * s), 0.8, 0.36 + 0.2 * cos(0.013 * s)};
    const double n = sqrt(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    const double ang = 0.0105 * s;
    for (int j = 0; j < 3; j++) tu[j] = ax[j] / n * ang;
    double r0[3][3], r1[3][3];
    rot_from_tu(start + 3, r0);
    rot_from_tu(tu, r1);
    matmul(r0, r1, p->r);
    p->t[0] = start[0] + 0.04 * sin(0.021 * s), p->t[1] = start[1] + 0.03 * sin(0.017 * s + 0.5);
    p->t[2] = start[2] + 0.05 * sin(0.013 * s);
    if (jump > 0 && k >= jump) {
        double j[3][3], r[3][3], jtu[3];
        for (int a = 0; a < 3; a++) jtu[a] = jump_turn[a] * PI / 180;
        rot_from_tu(jtu, j);
        matmul(j, p->r, r);
        memcpy(p->r, r, sizeof r);
        for (int a = 0; a < 3; a++) p->t[a] += jump_move[a] / 1000;
    }
}

typedef struct { double x, y, z; } v3;

int main(int argc, char **argv)
{
    const char *out = NULL;
    int frames = 60, W = 320, H = 240, clutter = 40, blur = 1, occ0 = -1, occ1 = -1, jump = -1;
    double cam[4] = {547.7367575 / 2, 542.0744058 / 2, (338.7036994 + 0.5) / 2 - 0.5, (234.5083345 + 0.5) / 2 - 0.5};
    double start[6] = {0.02, 0.01, 0.45, 2.1, 1.15, -0.45}, noise = 3, speed = 1;
    double jump_turn[3] = {15, 20, 0}, jump_move[3] = {40, -25, 30};   /* degrees, mm */
    unsigned long seed = 1;
    for (int i = 1; i + 1 < argc; i += 2) {
        const char *a = argv[i], *v = argv[i + 1];
        if (!strcmp(a, "--out")) out = v;
        else if (!strcmp(a, "--frames")) frames = atoi(v);
        else if (!strcmp(a, "--size")) sscanf(v, "%dx%d", &W, &H);
        else if (!strcmp(a, "--camera")) sscanf(v, "%lf,%lf,%lf,%lf", cam, cam + 1, cam + 2, cam + 3);
        else if (!strcmp(a, "--start")) sscanf(v, "%lf,%lf,%lf,%lf,%lf,%lf", start, start + 1, start + 2, start + 3, start + 4, start + 5);
        else if (!strcmp(a, "--seed")) seed = strtoul(v, NULL, 10);
        else if (!strcmp(a, "--clutter")) clutter = atoi(v);
        else if (!strcmp(a, "--noise")) noise = atof(v);
        else if (!strcmp(a, "--blur")) blur = atoi(v);
        else if (!strcmp(a, "--occlude")) sscanf(v, "%d:%d", &occ0, &occ1);
        else if (!strcmp(a, "--jump")) jump = atoi(v);
        else if (!strcmp(a, "--jump-turn")) {
            if (sscanf(v, "%lf,%lf,%lf", jump_turn, jump_turn + 1, jump_turn + 2) != 3) return 2;
        } else if (!strcmp(a, "--jump-move")) {
            if (sscanf(v, "%lf,%lf,%lf", jump_move, jump_move + 1, jump_move + 2) != 3) return 2;
        } else if (!strcmp(a, "--speed")) speed = atof(v);
        else {
            fprintf(stderr, "synth: unknown option %s\n", a);
            return 2;
        }
    }
    if (!out || frames < 1 || W < 8 || H < 8 || W > 4096 || H > 4096) {
        fprintf(stderr, "synth: usage: synth --out DIR [--frames N] [--size WxH] ...\n");
        return 2;
    }
    rng_state ^= seed * 0x9E3779B97F4A7C15ULL;
    const mc_edges *e = SYNTH_MODEL.edges;
    const uint32_t nv = e->vertices, nf = e->faces;
    v3 *pos = malloc(nv * sizeof *pos), *cp = malloc(nv * sizeof *cp);
    uint8_t *bg = malloc((size_t)W * H), *img = malloc((size_t)W * H);
    double *acc = malloc((size_t)W * H * sizeof *acc), *zb = malloc((size_t)W * H * SS * SS * sizeof *zb);
    float *shade = malloc((size_t)W * H * SS * SS * sizeof *shade);
    double *fshade = malloc(nf * sizeof *fshade);
    if (!pos || !cp || !bg || !img || !acc || !zb || !shade || !fshade) return 1;
    for (uint32_t v = 0; v < nv; v++) {
        int32_t p[3];
        mc_edges_position(e, v, p);
        pos[v].x = p[0] * 1e-6, pos[v].y = p[1] * 1e-6, pos[v].z = p[2] * 1e-6;
    }
    /* the background: a grey floor with clutter (rectangles turned at random, thin bars), fixed */
    for (size_t i = 0; i < (size_t)W * H; i++) bg[i] = (uint8_t)(95 + (i / W) * 40 / H);
    for (int c = 0; c < clutter; c++) {
        const double cx = uniform() * W, cy = uniform() * H, a = uniform() * PI;
        const double hw = (c % 3 == 0 ? 1 + uniform() * 2 : 4 + uniform() * 30) * W / 320.0, hh = (3 + uniform() * 25) * W / 320.0;
        const uint8_t g = (uint8_t)(20 + uniform() * 215);
        const double ca = cos(a), sa = sin(a);
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                const double dx = x - cx, dy = y - cy, u = dx * ca + dy * sa, v = -dx * sa + dy * ca;
                if (fabs(u) <= hw && fabs(v) <= hh) bg[(size_t)y * W + x] = g;
            }
    }
    char path[4096];
    snprintf(path, sizeof path, "%s/truth.csv", out);
    FILE *tf = fopen(path, "w");
    snprintf(path, sizeof path, "%s/orientation.txt", out);
    FILE *of = fopen(path, "w");
    if (!tf || !of) {
        fprintf(stderr, "synth: cannot write in %s\n", out);
        return 1;
    }
    fprintf(tf, "frame,tx,ty,tz,tux,tuy,tuz\n");
    const double light[3] = {-0.35, -0.55, -0.76};   /* towards the light, camera space */
    for (int k = 0; k < frames; k++) {
        pose_d p;
        truth(k, start, speed, jump, jump_turn, jump_move, &p);
        double tu[3];
        tu_from_rot(p.r, tu);
        fprintf(tf, "%d,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f\n", k, p.t[0], p.t[1], p.t[2], tu[0], tu[1], tu[2]);
        fprintf(of, "%.12f %.12f %.12f\n", tu[0], tu[1], tu[2]);
        if (k == 0) {
            snprintf(path, sizeof path, "%s/init.pos", out);
            FILE *pf = fopen(path, "w");
            if (!pf) return 1;
            fprintf(pf, "%.12f\n%.12f\n%.12f\n%.12f\n%.12f\n%.12f\n", p.t[0], p.t[1], p.t[2], tu[0], tu[1], tu[2]);
            fclose(pf);
        }
        for (uint32_t v = 0; v < nv; v++) {
            const double *r0 = p.r[0], *r1 = p.r[1], *r2 = p.r[2];
            cp[v].x = r0[0] * pos[v].x + r0[1] * pos[v].y + r0[2] * pos[v].z + p.t[0];
            cp[v].y = r1[0] * pos[v].x + r1[1] * pos[v].y + r1[2] * pos[v].z + p.t[1];
            cp[v].z = r2[0] * pos[v].x + r2[1] * pos[v].y + r2[2] * pos[v].z + p.t[2];
        }
        const size_t S = (size_t)W * SS, N = S * H * SS;
        for (size_t i = 0; i < N; i++) zb[i] = INFINITY, shade[i] = -1;
        for (uint32_t f = 0; f < nf; f++) {
            uint32_t c[3];
            mc_edges_face(e, f, c);
            const v3 a = cp[c[0]], b = cp[c[1]], d = cp[c[2]];
            if (a.z <= 1e-3 || b.z <= 1e-3 || d.z <= 1e-3) continue;   /* the scenes keep the object in front */
            const double ux = b.x - a.x, uy = b.y - a.y, uz = b.z - a.z, vx = d.x - a.x, vy = d.y - a.y, vz = d.z - a.z;
            double n[3] = {uy * vz - uz * vy, uz * vx - ux * vz, ux * vy - uy * vx};
            const double nl = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
            const double lam = fabs(n[0] * light[0] + n[1] * light[1] + n[2] * light[2]) / nl;
            const float g = (float)(40 + 190 * lam + 12 * ((f / 2) % 3));
            /* projected corners in samples: pixel i's samples at u = i - 1/2 + (s + 1/2) / SS */
            double X[3], Y[3], iz[3];
            const v3 *q[3] = {&a, &b, &d};
            for (int j = 0; j < 3; j++) {
                const double u = cam[2] + cam[0] * q[j]->x / q[j]->z, v = cam[3] + cam[1] * q[j]->y / q[j]->z;
                X[j] = (u + 0.5) * SS - 0.5, Y[j] = (v + 0.5) * SS - 0.5, iz[j] = 1 / q[j]->z;
            }
            const double area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
            if (fabs(area) < 1e-12) continue;
            const int x0 = (int)fmax(0, ceil(fmin(X[0], fmin(X[1], X[2])))), x1 = (int)fmin(S - 1.0, floor(fmax(X[0], fmax(X[1], X[2]))));
            const int y0 = (int)fmax(0, ceil(fmin(Y[0], fmin(Y[1], Y[2])))), y1 = (int)fmin(H * SS - 1.0, floor(fmax(Y[0], fmax(Y[1], Y[2]))));
            for (int y = y0; y <= y1; y++)
                for (int x = x0; x <= x1; x++) {
                    const double w0 = ((X[1] - x) * (Y[2] - y) - (X[2] - x) * (Y[1] - y)) / area;
                    const double w1 = ((X[2] - x) * (Y[0] - y) - (X[0] - x) * (Y[2] - y)) / area;
                    const double w2 = 1 - w0 - w1;
                    if (w0 < 0 || w1 < 0 || w2 < 0) continue;
                    const double z = 1 / (w0 * iz[0] + w1 * iz[1] + w2 * iz[2]);
                    const size_t at = (size_t)y * S + x;
                    if (z < zb[at]) zb[at] = z, shade[at] = g;
                }
        }
        /* occluder: a dark bar sweeping across the frame between its frames */
        const int occ = occ0 >= 0 && k >= occ0 && k <= occ1;
        const double ox = occ ? (double)(k - occ0) / (occ1 - occ0 + 1) * W * 1.2 - 0.1 * W : 0;
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double s = 0;
                for (int j = 0; j < SS; j++)
                    for (int i = 0; i < SS; i++) {
                        const float g = shade[(size_t)(y * SS + j) * S + x * SS + i];
                        s += g >= 0 ? g : bg[(size_t)y * W + x];
                    }
                s /= SS * SS;
                if (occ && x >= ox && x < ox + 0.12 * W) s = 35 + 10 * ((y / 8) % 2);
                acc[(size_t)y * W + x] = s;
            }
        for (int y = 0; y < H; y++)
            for (int x = 0; x < W; x++) {
                double s = acc[(size_t)y * W + x];
                if (blur && x > 0 && y > 0 && x + 1 < W && y + 1 < H) {   /* 1-2-1 binomial, 3 x 3 */
                    s = 0;
                    for (int j = -1; j <= 1; j++)
                        for (int i = -1; i <= 1; i++) s += acc[(size_t)(y + j) * W + x + i] * (2 - abs(i)) * (2 - abs(j));
                    s /= 16;
                }
                s += noise * gauss();
                img[(size_t)y * W + x] = (uint8_t)(s < 0 ? 0 : s > 255 ? 255 : lround(s));
            }
        snprintf(path, sizeof path, "%s/image%04d.pgm", out, k);
        FILE *f = fopen(path, "wb");
        if (!f || fprintf(f, "P5\n%d %d\n255\n", W, H) < 0 || fwrite(img, 1, (size_t)W * H, f) != (size_t)W * H || fclose(f)) {
            fprintf(stderr, "synth: cannot write %s\n", path);
            return 1;
        }
    }
    fclose(tf), fclose(of);
    free(pos), free(cp), free(bg), free(img), free(acc), free(zb), free(shade), free(fshade);
    return 0;
}
