/* NAME-track: the tracker front end. Follows a baked edge model (modelc --as edges) through a
 * sequence of grey camera frames with the runtime's particle filter (particles.h) and writes one
 * pose a frame.
 *
 *   NAME-track --frames 'DIR/image%04d.pgm' --camera FILE.xml|px,py,u0,v0 --init FILE.pos|tx,ty,tz,tux,tuy,tuz
 *              [--orientation FILE] [--particles N] [--out FILE.csv] [--overlay DIR] [--fixed-out FILE] [options]
 *
 * Each frame: read (PGM), shrunk by an integer factor to fit the bake's --screen (a box average;
 * the camera's intrinsics scaled to match; --shrunk K: frames shrunk K times already), its edges
 * found and spread into masks (imgedge.h), then one step of the filter: the pipeline and settings
 * of ../common/track_frame.h, which the firmware tracker (../fw/track_main.c) runs too. Poses are
 * written in ViSP's convention (metres, theta-u radians, object to camera), with the estimate's
 * confidence and score and the time of each stage, as CSV to --out (written whole at the end: a
 * failure leaves no partial file) or standard output.
 * --overlay writes a PNG a frame: the frame dimmed, its edge pixels grey, and the model's visible
 * lines at the estimate coloured by orientation (matched ones bright), two pixels wide. --fixed-out
 * writes the estimate's integer fields a frame, the lines the firmware tracker prints
 * (track_frame.h MC_TRACK_POSE_LINE), so that the two compare as text. An output path that is not a
 * regular file (/dev/null, a pipe) is written directly.
 *
 * Errors: one line "NAME-track: ..." and exit status 1 (bad data) or 2 (bad usage). All memory is
 * static: the bake's (mc_app_model, sized by --screen and --particles) and this file's frame
 * buffers; the program makes no heap call. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <modelc/app.h>

#include "../common/track_frame.h"
#include "../host/image.h"
#include "../host/timing.h"
#include "track_input.h"

#define MAX_PIXELS ((size_t)MC_PGM_MAX_SIDE * MC_PGM_MAX_SIDE)

static uint8_t raw[MAX_PIXELS];           /* a frame as read */
static uint8_t codes[MAX_PIXELS];         /* --overlay: the frame's edge pixels before spreading */
static uint8_t grey[MAX_PIXELS];          /* --overlay: the frame as tracked */
static uint8_t rgb[3 * MAX_PIXELS];       /* --overlay: the picture */
static char prog[64] = "track";

static int fail(int status, const char *fmt, const char *a, const char *b)
{
    fprintf(stderr, "%s: ", prog);
    fprintf(stderr, fmt, a, b);
    fputc('\n', stderr);
    return status;
}

typedef struct options {
    const char *frames, *camera, *init, *orientation, *out, *overlay, *fixed_out;
    long first, count, scale, shrunk;
    mc_track_settings s;   /* the filter's and the edges' settings (track_frame.h) */
} options;

static const char usage[] =
    "usage: %s --frames PATTERN --camera FILE.xml|px,py,u0,v0 --init FILE.pos|tx,ty,tz,tux,tuy,tuz [options]\n"
    "  --frames PATTERN     frame files, a printf pattern with one integer conversion, e.g. 'dir/image%%04d.pgm'\n"
    "  --first K            the first frame's number (default 0)\n"
    "  --count N            frames to track (default: until the next file is missing)\n"
    "  --camera C           ViSP tracker settings XML (its <camera>), or px,py,u0,v0 in pixels\n"
    "  --init P             the first frame's pose: ViSP .pos file, or tx,ty,tz (m),tux,tuy,tuz (rad)\n"
    "  --orientation FILE   3-DOF mode: one rotation vector (tux tuy tuz) a frame, as from an IMU\n"
    "  --particles N        particles (default 100, at most the bake's --particles)\n"
    "  --fresh F            of them, placed at random each frame to find a lost object (default N/3)\n"
    "  --layers L           weighings a frame, 1..4: each further one draws all N again from the last\n"
    "                       weights with steps halved and, after the first, --fine-radius (default 3)\n"
    "  --scale K            shrink frames K times (default: the least that fits the bake's --screen)\n"
    "  --shrunk K           the frames were shrunk K times already (a K x K box average, as --scale does): the\n"
    "                       camera is scaled by K, the frames tracked as they are\n"
    "  --threshold T        image edge gradient magnitude, 1..1442 (default 30)\n"
    "  --radius R           pixels an image edge may lie from a model line, 0..8 (default 2)\n"
    "  --fine-radius R      the same for the layers after the first, below --radius (default 1)\n"
    "  --tolerance B        orientation bins of 22.5 degrees a match may be off, 0..3 (default 1)\n"
    "  --step-t MM          translation step a frame (default 5)\n"
    "  --step-r DEG         rotation step a frame (default 2)\n"
    "  --fresh-r DEG        fresh particles turned from the estimate by steps of this, 0..28 (default 15; 0: any\n"
    "                       orientation)\n"
    "  --search MM          fresh particles within this many mm of the first pose, each axis (default 60)\n"
    "  --detect K           of the fresh ones, K placed where the image's edges fit their orientation best,\n"
    "                       searched within --detect-reach pixels of the estimate, in frames after one whose\n"
    "                       confidence is below --detect-below (default 16; 0: none)\n"
    "  --detect-below C     0..1.01 (default 0.9; above 1: every frame)\n"
    "  --detect-reach PX    0..1024 (default 64)\n"
    "  --detect-stride PX   the search's coarse grid, 1..16 (default 3), then refined to the pixel\n"
    "  --sharpness S        weight halving every 1/S of matched/visible lost, 1..64 (default 32)\n"
    "  --recall K           in the layers after the first, weight halving every 1/K of matched pixels short\n"
    "                       of the best particle's, 0..64 (default 4; 0: off)\n"
    "  --min-visible N      fewer visible line pixels weigh 0 (default 20)\n"
    "  --near M, --far M    the camera's depth range in metres (default 0.02, 20)\n"
    "  --seed S             the random stream (default 1)\n"
    "  --out FILE           the poses as CSV (default: standard output)\n"
    "  --overlay DIR        a PNG a frame, DIR/frameNNNN.png\n"
    "  --fixed-out FILE     the estimate's integer fields, a line a frame: \"pose K q0 q1 q2 q3 t0 t1 t2 visible\n"
    "                       matched confidence\" (Q30, um, Q16), as the firmware tracker prints them\n";

static int number(const char *opt, const char *text, double lo, double hi, double *v)
{
    char *end;
    errno = 0;
    *v = strtod(text, &end);
    if (end == text || *end || errno || !(*v >= lo && *v <= hi)) {
        char range[96];
        snprintf(range, sizeof range, "%s: expected a number in %g..%g", text, lo, hi);
        return fail(2, "%s %s", opt, range);
    }
    return 0;
}

static int integer(const char *opt, const char *text, long lo, long hi, long *v)
{
    double d;
    int rc = number(opt, text, (double)lo, (double)hi, &d);
    if (rc) return rc;
    if (d != floor(d)) return fail(2, "%s %s: expected a whole number", opt, text);
    *v = (long)d;
    return 0;
}

/* The pattern must hold exactly one integer conversion (%d, %04d, %5u ...) and no other '%'
 * but "%%": it is handed to snprintf with the frame number. */
static int check_pattern(const char *p)
{
    int conversions = 0;
    for (const char *c = p; *c; c++) {
        if (*c != '%') continue;
        if (c[1] == '%') { c++; continue; }
        c++;
        while (*c == '0') c++;
        while (*c >= '0' && *c <= '9') c++;
        if (*c != 'd' && *c != 'u') return -1;
        conversions++;
    }
    return conversions == 1 ? 0 : -1;
}

static int frame_path(const options *o, long k, char *path, size_t n)
{
    const int len = snprintf(path, n, o->frames, (int)k);
    return len < 0 || (size_t)len >= n ? -1 : 0;
}

static int exists(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (f) fclose(f);
    return f != NULL;
}

static int parse(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->count = -1;
    mc_track_settings *s = &o->s;
    mc_track_settings_default(s);
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        long l;
        int rc = 0;
        if (!strcmp(a, "--help") || !strcmp(a, "-h")) {
            printf(usage, prog);
            exit(0);
        }
        if (!v) return fail(2, "%s needs a value (see %s --help)", a, prog);
        i++;
        if (!strcmp(a, "--frames")) o->frames = v;
        else if (!strcmp(a, "--camera")) o->camera = v;
        else if (!strcmp(a, "--init")) o->init = v;
        else if (!strcmp(a, "--orientation")) o->orientation = v, s->dof = 3;
        else if (!strcmp(a, "--out")) o->out = v;
        else if (!strcmp(a, "--overlay")) o->overlay = v;
        else if (!strcmp(a, "--fixed-out")) o->fixed_out = v;
        else if (!strcmp(a, "--first")) rc = integer(a, v, 0, 100000000, &o->first);
        else if (!strcmp(a, "--count")) rc = integer(a, v, 1, 100000000, &o->count);
        else if (!strcmp(a, "--particles")) rc = integer(a, v, 1, 65535, &s->particles);
        else if (!strcmp(a, "--fresh")) rc = integer(a, v, 0, 65534, &s->fresh);
        else if (!strcmp(a, "--layers")) rc = integer(a, v, 1, 4, &s->layers);
        else if (!strcmp(a, "--scale")) rc = integer(a, v, 1, 64, &o->scale);
        else if (!strcmp(a, "--shrunk")) rc = integer(a, v, 1, 64, &o->shrunk);
        else if (!strcmp(a, "--threshold")) rc = integer(a, v, 1, MC_IMGEDGE_THRESHOLD_MAX, &s->threshold);
        else if (!strcmp(a, "--radius")) rc = integer(a, v, 0, 8, &s->radius);
        else if (!strcmp(a, "--fine-radius")) rc = integer(a, v, 0, 7, &s->fine_radius);
        else if (!strcmp(a, "--tolerance")) rc = integer(a, v, 0, 3, &s->tolerance);
        else if (!strcmp(a, "--sharpness")) rc = integer(a, v, 1, 64, &s->sharpness);
        else if (!strcmp(a, "--recall")) rc = integer(a, v, 0, 64, &s->recall);
        else if (!strcmp(a, "--detect")) rc = integer(a, v, 0, 65535, &s->detect);
        else if (!strcmp(a, "--detect-below")) rc = number(a, v, 0, 1.01, &s->detect_below);
        else if (!strcmp(a, "--detect-reach")) rc = integer(a, v, 0, 1024, &s->detect_reach);
        else if (!strcmp(a, "--detect-stride")) rc = integer(a, v, 1, 16, &s->detect_stride);
        else if (!strcmp(a, "--min-visible")) rc = integer(a, v, 0, 100000000, &s->min_visible);
        else if (!strcmp(a, "--seed")) rc = integer(a, v, 0, 2000000000, &l), s->seed = (unsigned long)l;
        else if (!strcmp(a, "--step-t")) rc = number(a, v, 0, 1000, &s->step_t_mm);
        else if (!strcmp(a, "--step-r")) rc = number(a, v, 0, 45, &s->step_r_deg);
        else if (!strcmp(a, "--fresh-r")) rc = number(a, v, 0, 28, &s->fresh_r_deg);
        else if (!strcmp(a, "--search")) rc = number(a, v, 0, 10000, &s->search_mm);
        else if (!strcmp(a, "--near")) rc = number(a, v, 1e-5, 100, &s->near_m);
        else if (!strcmp(a, "--far")) rc = number(a, v, 1e-4, 268, &s->far_m);
        else return fail(2, "unknown option %s (see %s --help)", a, prog);
        if (rc) return rc;
    }
    if (!o->frames || !o->camera || !o->init) return fail(2, "%s%s", "--frames, --camera and --init are required (see --help)", "");
    if (check_pattern(o->frames)) return fail(2, "--frames %s: expected one integer conversion such as %%04d%s", o->frames, "");
    if (s->fresh < 0) s->fresh = s->particles / 3;
    if (s->fresh >= s->particles) return fail(2, "--fresh must be below --particles%s%s", "", "");
    if (!(s->near_m < s->far_m)) return fail(2, "--near must be below --far%s%s", "", "");
    if (o->scale && o->shrunk) return fail(2, "--scale and --shrunk exclude each other%s%s", "", "");
    return 0;
}

/* the colour of orientation bin b: a hue wheel around the half circle */
static void bin_colour(unsigned b, int bright, uint8_t c[3])
{
    static const uint8_t hue[8][3] = {{255, 40, 40},  {255, 160, 0}, {230, 230, 0}, {60, 220, 60},
                                      {0, 220, 220},  {40, 120, 255}, {150, 60, 255}, {255, 40, 200}};
    for (int k = 0; k < 3; k++) c[k] = bright ? hue[b & 7][k] : (uint8_t)(hue[b & 7][k] / 2);
}

static int write_overlay(const options *o, long k, const uint8_t *frame, unsigned w, unsigned h, const mc_sdepth *sd,
                         const uint8_t *color)
{
    for (size_t i = 0; i < (size_t)w * h; i++) {
        uint8_t *p = rgb + 3 * i;
        const uint8_t g = (uint8_t)(frame[i] / 3);
        p[0] = p[1] = p[2] = codes[i] ? 150 : g;
    }
    /* the model's line pixels, each also over its right and lower neighbours (where those are not
     * line pixels themselves), so that one-pixel lines show on a picture of the whole frame */
    for (unsigned y = 0; y < h; y++)
        for (unsigned x = 0; x < w; x++) {
            if (!mc_sdepth_in_use(sd, x, y)) continue;
            uint8_t c[3];
            bin_colour((unsigned)color[(size_t)y * w + x] - 1u, mc_sdepth_is_matched(sd, x, y), c);
            for (unsigned d = 0; d < 3; d++) {
                const unsigned u = x + (d == 1), v = y + (d == 2);
                if (u >= w || v >= h || (d && mc_sdepth_in_use(sd, u, v))) continue;
                uint8_t *p = rgb + 3 * ((size_t)v * w + u);
                p[0] = c[0], p[1] = c[1], p[2] = c[2];
            }
        }
    char path[4096];
    if (snprintf(path, sizeof path, "%s/frame%04ld.png", o->overlay, k) >= (int)sizeof path)
        return fail(1, "--overlay %s: path too long%s", o->overlay, "");
    if (mc_host_write_png(path, rgb, (int)w, (int)h)) return fail(1, "%s: cannot write%s", path, "");
    return 0;
}

/* An output file written whole or not at all: into PATH.tmp, renamed over PATH at the end. A path
 * that exists and is not a regular file (/dev/null, a pipe, a terminal) is written directly: renaming
 * over it would replace the device with a file. */
typedef struct outfile {
    FILE *f;
    const char *path;
    char tmp[4200];
    int direct;
} outfile;

static int out_open(outfile *o, const char *path)
{
    struct stat st;
    o->path = path;
    o->direct = stat(path, &st) == 0 && !S_ISREG(st.st_mode);
    snprintf(o->tmp, sizeof o->tmp, "%s.tmp", path);
    o->f = fopen(o->direct ? path : o->tmp, "w");
    return o->f ? 0 : -1;
}

/* Closes o (not opened: nothing to do); with keep, puts what it wrote in place, else removes it.
 * Returns -1 when keeping failed. */
static int out_close(outfile *o, int keep)
{
    if (!o->f) return 0;
    const int failed = fclose(o->f) != 0;
    o->f = NULL;
    if (o->direct) return keep && failed ? -1 : 0;
    if (!keep || failed) {
        remove(o->tmp);
        return keep ? -1 : 0;
    }
    return rename(o->tmp, o->path) ? -1 : 0;
}

int main(int argc, char **argv)
{
    const mc_app *app = &mc_app_model;
    snprintf(prog, sizeof prog, "%s-track", app->model->name);
    options o;
    int rc = parse(argc, argv, &o);
    if (rc) return rc;
    if (!app->model->edges || !app->edges_frame)
        return fail(1, "model %s has no edge part: bake it with modelc --as edges%s", app->model->name, "");
    if ((unsigned long)o.s.particles > app->max_particles) {
        char n[32];
        snprintf(n, sizeof n, "%lu", (unsigned long)app->max_particles);
        return fail(2, "--particles: at most %s, the bake's --particles%s", n, "");
    }
    char err[512], path[4096];

    /* the first frame sets the size; the rest must match it */
    if (frame_path(&o, o.first, path, sizeof path)) return fail(2, "--frames %s: path too long%s", o.frames, "");
    uint16_t fw, fh;
    if (mc_pgm_read(path, NULL, 0, &fw, &fh, err, sizeof err)) return fail(1, "%s%s", err, "");
    /* K: how many times this program shrinks the frames; the camera's frames were shrunk K times
     * in all, by it or (--shrunk) before */
    long K = o.shrunk ? 1 : o.scale;
    if (!K)
        for (K = 1; fw / K > app->max_width || fh / K > app->max_height; K++) continue;
    const unsigned long camera_k = (unsigned long)(o.shrunk ? o.shrunk : K);
    const unsigned w = fw / (unsigned)K, h = fh / (unsigned)K;
    if (w > app->max_width || h > app->max_height || w < 3 || h < 3) {
        char s[96];
        snprintf(s, sizeof s, "%ux%u shrunk %ld times is %ux%u; the bake holds %ux%u", fw, fh, K, w, h,
                 app->max_width, app->max_height);
        return fail(2, "%s: %s", o.shrunk ? "--shrunk" : "--scale", s);
    }

    mc_track_intrinsics in;
    const size_t cl = strlen(o.camera);
    if (cl > 4 && !strcmp(o.camera + cl - 4, ".xml") ? mc_track_camera_read_xml(o.camera, &in, err, sizeof err)
                                                    : mc_track_camera_parse(o.camera, &in, err, sizeof err))
        return fail(1, "%s%s", err, "");
    /* the intrinsics scaled to the shrunk frame, in Q16 (track_frame.h) */
    mc_camera cam;
    if (mc_track_camera_fixed(&cam, in.px, in.py, in.u0, in.v0, camera_k, (uint16_t)w, (uint16_t)h, o.s.near_m,
                              o.s.far_m) != MC_OK)
        return fail(1, "--camera %s: not a usable camera%s", o.camera, "");

    double pose0[6];
    const size_t il = strlen(o.init);
    if (il > 4 && !strcmp(o.init + il - 4, ".pos") ? mc_track_pose_read(o.init, pose0, err, sizeof err)
                                                  : mc_track_pose_parse(o.init, pose0, err, sizeof err))
        return fail(1, "%s%s", err, "");
    int32_t q[4], t[3];
    mc_track_pose_to_fixed(pose0, q, t);

    mc_track_orient_reader orient;
    if (o.orientation && mc_track_orient_open(&orient, o.orientation, err, sizeof err)) return fail(1, "%s%s", err, "");

    /* the depth buffer, the scoring view and the filter (track_frame.h) */
    static mc_track_state tr;
    const int started = mc_track_start(&tr, app, &cam, &o.s, q, t);
    if (started == MC_TRACK_START_SDEPTH) return fail(1, "cannot set up the depth buffer%s%s", "", "");
    if (started != MC_TRACK_START_OK) return fail(2, "the filter's settings are out of range (see --help)%s%s", "", "");
    const mc_filter *f = &tr.f;

    outfile csv = {0}, fx = {0};
    FILE *out = stdout, *fixed = NULL;
    if (o.out) {
        if (out_open(&csv, o.out)) return fail(1, "%s: cannot write: %s", o.out, strerror(errno));
        out = csv.f;
    }
    if (o.fixed_out) {
        if (out_open(&fx, o.fixed_out)) {
            const int e = errno;
            out_close(&csv, 0);
            return fail(1, "%s: cannot write: %s", o.fixed_out, strerror(e));
        }
        fixed = fx.f;
    }
    fprintf(out, "frame,tx,ty,tz,tux,tuy,tuz,confidence,visible,matched,edges_ms,filter_ms\n");
    long done = 0;
    for (long k = o.first; o.count < 0 || done < o.count; k++, done++) {
        if (frame_path(&o, k, path, sizeof path)) { rc = fail(2, "--frames %s: path too long%s", o.frames, ""); break; }
        if (o.count < 0 && done > 0 && !exists(path)) break;
        uint16_t gw, gh;
        if (mc_pgm_read(path, raw, sizeof raw, &gw, &gh, err, sizeof err)) { rc = fail(1, "%s%s", err, ""); break; }
        if (gw != fw || gh != fh) { rc = fail(1, "%s: not the size of the first frame%s", path, ""); break; }
        int32_t oq[4];
        if (o.orientation) {
            const int got = mc_track_orient_next(&orient, oq, NULL, err, sizeof err);
            if (got < 0) { rc = fail(1, "%s%s", err, ""); break; }
            if (got == 0) { rc = fail(1, "%s: no orientation for frame %s", o.orientation, path); break; }
        }
        const double t0 = mc_host_now_ms();
        mc_track_edges(&tr, raw, fw, (unsigned)K, o.overlay ? codes : NULL, o.overlay ? grey : NULL);
        const double t1 = mc_host_now_ms();
        if (mc_filter_step(&tr.f, &tr.view, o.orientation ? oq : NULL) != MC_OK) { rc = fail(1, "%s: the filter failed%s", path, ""); break; }
        const double t2 = mc_host_now_ms();
        double p[6];
        mc_track_pose_from_fixed(f->estimate.q, f->estimate.t, p);
        fprintf(out, "%ld,%.6f,%.6f,%.6f,%.6f,%.6f,%.6f,%.4f,%lu,%lu,%.3f,%.3f\n", k, p[0], p[1], p[2], p[3], p[4], p[5],
                f->confidence / 65536.0, (unsigned long)f->estimate.visible, (unsigned long)f->estimate.matched, t1 - t0,
                t2 - t1);
        if (fixed) fprintf(fixed, MC_TRACK_POSE_LINE, MC_TRACK_POSE_ARGS(k, f));
        if (o.overlay) {
            mc_pose pose;
            mc_track_score sc;
            if (mc_pose_set(&pose, f->estimate.q, f->estimate.t) != MC_OK || mc_track_score_pose(&tr.view, &pose, &sc) != MC_OK ||
                (rc = write_overlay(&o, k, grey, w, h, &tr.sd, app->color)))
                break;
        }
    }
    if (o.orientation) mc_track_orient_close(&orient);
    /* each file written whole or not at all: both kept, or neither */
    if (rc) {
        out_close(&fx, 0), out_close(&csv, 0);
        return rc;
    }
    if (out_close(&fx, 1)) {
        out_close(&csv, 0);
        return fail(1, "%s: cannot write: %s", o.fixed_out, strerror(errno));
    }
    if (out_close(&csv, 1)) return fail(1, "%s: cannot write: %s", o.out, strerror(errno));
    return rc;
}
