/* The host viewer: one binary per model (linked with the model's generated app binding).
 *
 *   NAME-view [--png FILE | --ppm FILE] [--yaw D --pitch D --roll D --zoom Z --depth N --size WxH
 *              --perspective --fill none|pixel|scanline --no-finish --splat 1|zoom]
 *   NAME-view --bench N [...]
 *   NAME-view --checksums [--ppm FILE | --png FILE] [--depth N --size WxH]
 *   NAME-view            interactive, when stdout is a terminal
 *
 * Reads no files: the model is compiled in. Host-only code (stdio, clocks, terminal) lives here,
 * outside the freestanding runtime. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include <modelc/app.h>
#include <modelc/modelc.h>

#include "image.h"
#include "term.h"
#include "timing.h"
#include "../common/frames.h"   /* the view list and frame checksum the firmware prints: --checksums */

static uint8_t rgb_buffer[4096 * 4096 * 3];

static void usage(FILE *f)
{
    fprintf(f,
            "usage: %s-view [options]\n"
            "  --png FILE      render one frame to a PNG file\n"
            "  --ppm FILE      render one frame to a binary PPM file\n"
            "  --bench N       render N frames of one full turn and print ms per frame (median)\n"
            "  --checksums     render the firmware's fixed view list (runtime/front/common/views.h) at the\n"
            "                  baked screen size and the model's depth (unless --size, --depth) and\n"
            "                  print the firmware's checksum line per frame; --ppm/--png then write\n"
            "                  the frame the firmware writes out\n"
            "  --yaw DEG       rotation about the vertical axis (default 0)\n"
            "  --pitch DEG     rotation about the horizontal axis (default 0)\n"
            "  --roll DEG      rotation about the view axis (default 0)\n"
            "  --zoom Z        1 = the model's bounding cube spans the shorter side (default 1)\n"
            "  --depth N       octree depth to draw, 1..%d (default %d)\n"
            "  --size WxH      frame size, at most %ux%u (default 320x240)\n"
            "  --perspective   perspective projection, eye 2 cube sides away (default orthographic)\n"
            "  --fill MODE     hole filling after rendering: none, pixel (one-pixel holes) or scanline\n"
            "                  (the paper's neighbourhood criterion, hole types 1-4; default %s)\n"
            "  --no-finish     the same as --fill none\n"
            "  --splat MODE    pixels per leaf: 1 (one pixel, the paper's) or zoom (a square that grows\n"
            "                  with the leaf's size on screen; default %s)\n"
            "  --help          this text\n"
            "With no output option and stdout a terminal, runs interactively: arrow keys rotate, + and -\n"
            "zoom, q quits.\n",
            mc_app_model.model->name, mc_app_model.model->octree->depth, mc_app_model.model->octree->depth,
            mc_app_model.max_width, mc_app_model.max_height,
            MC_FILL_DEFAULT_MODE == 2 ? "scanline" : MC_FILL_DEFAULT_MODE == 1 ? "pixel" : "none",
            MC_SPLAT_DEFAULT_MODE == 2 ? "zoom" : "1");
}

static int die(const char *msg, const char *arg)
{
    fprintf(stderr, "%s-view: %s%s%s\n", mc_app_model.model->name, msg, arg ? ": " : "", arg ? arg : "");
    return 2;
}

static int parse_double(const char *s, double lo, double hi, double *out)
{
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end || !(v >= lo && v <= hi)) return -1;
    *out = v;
    return 0;
}

int32_t mc_host_angle(double degrees) { return (int32_t)lround(fmod(degrees, 360.0) * MC_ANGLE_FULL / 360.0); }

static int bench(const mc_octree *octree, const mc_target *t, mc_view v, const mc_octree_options *opt, unsigned depth,
                 mc_fill fill, int frames)
{
    static double ms[100000];
    if (frames > 100000) frames = 100000;
    uint64_t points = 0;
    int32_t yaw0 = v.yaw;
    for (int i = 0; i < frames; i++) {
        v.yaw = yaw0 + (int32_t)((int64_t)MC_ANGLE_FULL * i / frames);
        mc_stats st;
        double t0 = mc_host_now_ms();
        mc_clear(t);
        mc_octree_render(octree, &v, depth, opt, t, NULL, NULL, &st);
        mc_finish(t, fill);
        ms[i] = mc_host_now_ms() - t0;
        points += st.points;
    }
    double median = mc_host_median(ms, (size_t)frames);
    double mean_points = (double)points / frames;
    printf("model %s depth %u size %ux%u frames %d%s\n", mc_app_model.model->name, depth, t->width, t->height,
           frames, fill == MC_FILL_NONE ? " no-finish" : "");
    printf("ms per frame (median): %.3f\n", median);
    printf("points drawn per frame: %.0f\n", mean_points);
    printf("Mpoints/s: %.2f\n", mean_points / median / 1e3);
    return 0;
}

/* --checksums: the same frames, lines and written frame as the firmware (runtime/front/fw/main.c). */
static int checksums(const mc_octree *octree, const mc_target *t, unsigned depth, const char *png, const char *ppm)
{
    int status = 0;
    for (unsigned i = 0; i < MC_FRONT_VIEW_COUNT; i++) {
        mc_front_result r = mc_front_frame(octree, i, depth, t);
        printf(MC_FRONT_FRAME_LINE, MC_FRONT_FRAME_ARGS(i, depth, t, r));
        if (r.rc != MC_OK) status = 1;
        if (i == MC_FRONT_PPM_VIEW && (png || ppm)) {
            mc_host_to_rgb(t, octree->palette, rgb_buffer);
            if (png && mc_host_write_png(png, rgb_buffer, t->width, t->height)) return die("cannot write PNG", png);
            if (ppm && mc_host_write_ppm(ppm, rgb_buffer, t->width, t->height)) return die(strerror(errno), ppm);
        }
    }
    return status;
}

int main(int argc, char **argv)
{
    const mc_model *model = mc_app_model.model;
    const mc_octree *octree = model->octree;
    if (!octree) {
        fprintf(stderr, "%s-view: the model has no octree to draw\n", model->name);
        return 2;
    }
    const char *png = NULL, *ppm = NULL;
    double yaw = 0, pitch = 0, roll = 0, zoom = 1, dv;
    unsigned depth = octree->depth, w = 320, h = 240;
    int perspective = 0, check = 0, sized = 0;
    mc_fill fill = MC_FILL_DEFAULT;
    mc_octree_options opt = {MC_SPLAT_DEFAULT};
    long frames = 0;
    static const struct option opts[] = {
        {"png", required_argument, 0, 'P'}, {"ppm", required_argument, 0, 'M'},
        {"bench", required_argument, 0, 'b'}, {"yaw", required_argument, 0, 'y'},
        {"pitch", required_argument, 0, 'p'}, {"roll", required_argument, 0, 'r'},
        {"zoom", required_argument, 0, 'z'}, {"depth", required_argument, 0, 'd'},
        {"size", required_argument, 0, 's'}, {"no-finish", no_argument, 0, 'n'},
        {"perspective", no_argument, 0, 'e'}, {"checksums", no_argument, 0, 'c'},
        {"help", no_argument, 0, 'h'}, {"fill", required_argument, 0, 'f'},
        {"splat", required_argument, 0, 'S'}, {0, 0, 0, 0}};
    opterr = 0;
    int c;
    while ((c = getopt_long(argc, argv, "", opts, NULL)) != -1) {
        switch (c) {
        case 'P': png = optarg; break;
        case 'M': ppm = optarg; break;
        case 'b':
            if (parse_double(optarg, 1, 100000, &dv)) return die("--bench expects 1..100000 frames", optarg);
            frames = (long)dv;
            break;
        case 'y': if (parse_double(optarg, -1e6, 1e6, &yaw)) return die("--yaw expects degrees", optarg); break;
        case 'p': if (parse_double(optarg, -1e6, 1e6, &pitch)) return die("--pitch expects degrees", optarg); break;
        case 'r': if (parse_double(optarg, -1e6, 1e6, &roll)) return die("--roll expects degrees", optarg); break;
        case 'z': if (parse_double(optarg, 1.0 / 64, 64, &zoom)) return die("--zoom expects 1/64..64", optarg); break;
        case 'd':
            if (parse_double(optarg, 1, octree->depth, &dv) || dv != (unsigned)dv)
                return die("--depth expects an integer from 1 to the model's depth", optarg);
            depth = (unsigned)dv;
            break;
        case 's':
            if (sscanf(optarg, "%ux%u", &w, &h) != 2 || w < 1 || h < 1 || w > mc_app_model.max_width ||
                h > mc_app_model.max_height)
                return die("--size expects WxH within the baked screen size", optarg);
            sized = 1;
            break;
        case 'c': check = 1; break;
        case 'n': fill = MC_FILL_NONE; break;
        case 'f':
            if (!strcmp(optarg, "none")) fill = MC_FILL_NONE;
            else if (!strcmp(optarg, "pixel")) fill = MC_FILL_PIXEL;
            else if (!strcmp(optarg, "scanline")) fill = MC_FILL_SCANLINE;
            else return die("--fill expects none, pixel or scanline", optarg);
            break;
        case 'S':
            if (!strcmp(optarg, "1") || !strcmp(optarg, "pixel")) opt.splat = MC_SPLAT_PIXEL;
            else if (!strcmp(optarg, "zoom")) opt.splat = MC_SPLAT_ZOOM;
            else return die("--splat expects 1 or zoom", optarg);
            break;
        case 'e': perspective = 1; break;
        case 'h': usage(stdout); return 0;
        default: return die("unknown option (see --help)", argv[optind - 1]);
        }
    }
    if (optind < argc) return die("unexpected argument (see --help)", argv[optind]);

    if (check && !sized) {
        w = mc_app_model.max_width;
        h = mc_app_model.max_height;
    }
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)w, (uint16_t)h};
    if (check) {
        if (frames) return die("--checksums and --bench exclude each other", NULL);
        return checksums(octree, &t, depth, png, ppm);
    }
    mc_view v = mc_view_default();
    v.yaw = mc_host_angle(yaw);
    v.pitch = mc_host_angle(pitch);
    v.roll = mc_host_angle(roll);
    v.zoom = (int32_t)lround(zoom * MC_ZOOM_ONE);
    v.projection = perspective ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;

    if (frames) return bench(octree, &t, v, &opt, depth, fill, (int)frames);
    if (!png && !ppm) {
        if (isatty(STDOUT_FILENO)) return mc_host_interactive(&mc_app_model, v, &opt, fill);
        return die("stdout is not a terminal: give --png FILE, --ppm FILE or --bench N (see --help)", NULL);
    }

    mc_stats st;
    double t0 = mc_host_now_ms();
    mc_clear(&t);
    int rc = mc_octree_render(octree, &v, depth, &opt, &t, NULL, NULL, &st);
    uint32_t filled = mc_finish(&t, fill);
    double ms = mc_host_now_ms() - t0;
    if (rc != MC_OK) return die("render failed", NULL);
    mc_host_to_rgb(&t, octree->palette, rgb_buffer);
    if (png && mc_host_write_png(png, rgb_buffer, (int)w, (int)h)) return die("cannot write PNG", png);
    if (ppm && mc_host_write_ppm(ppm, rgb_buffer, (int)w, (int)h)) return die(strerror(errno), ppm);
    printf("model %s depth %u size %ux%u points %u filled %u ms %.3f\n", model->name, depth, w, h, st.points,
           filled, ms);
    return 0;
}
