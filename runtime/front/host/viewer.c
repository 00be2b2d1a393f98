/* The host viewer: one binary per model (linked with the model's generated app binding).
 *
 *   NAME-view [--png FILE | --ppm FILE] [--yaw D --pitch D --roll D --zoom Z --depth N --size WxH
 *              --perspective --fill none|pixel|scanline --no-finish --splat 1|zoom
 *              --error PX --cull on|off --mode points|shaded|lines|shaded+lines --lod N]
 *   NAME-view --bench N [...]
 *   NAME-view --checksums [--ppm FILE | --png FILE] [--depth N --size WxH]
 *   NAME-view --stream SRC [...]   a streamed bake (modelc --emit stream): its points, or its mesh
 *   NAME-view            interactive, when stdout is a terminal
 *
 * The model is compiled in; --stream reads its stream instead (stream_in.h). Host-only code (stdio, clocks, terminal) lives here,
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
#include "scene.h"
#include "stream_in.h"
#include "term.h"
#include "timing.h"
#include "../common/frames.h"   /* the view list and frame checksum the firmware prints: --checksums */
#include "../common/mesh_frames.h"   /* and its mesh frames, when the bake has a mesh part */

static uint8_t rgb_buffer[4096 * 4096 * 3];

static void usage(FILE *f)
{
    fprintf(f,
            "usage: %s-view [options]\n"
            "  --png FILE      render one frame to a PNG file\n"
            "  --ppm FILE      render one frame to a binary PPM file\n"
            "  --bench N       render N frames of one full turn and print ms per frame (median)\n"
            "  --checksums     render the firmware's fixed frame list (runtime/front/common/frames.h) at the\n"
            "                  baked screen size and the model's depth (unless --size, --depth) and\n"
            "                  print the firmware's checksum line per frame, then with a mesh part\n"
            "                  (--as both) its mesh frames' (runtime/front/common/mesh_frames.h; with\n"
            "                  --stream, the stream's mesh within the levels that have come);\n"
            "                  --ppm/--png then write the frame the firmware writes out\n"
            "  --yaw DEG       rotation about the vertical axis (default 0)\n"
            "  --pitch DEG     rotation about the horizontal axis (default 0)\n"
            "  --roll DEG      rotation about the view axis (default 0)\n"
            "  --zoom Z        1 = the model's bounding cube spans the shorter side (default 1)\n"
            "  --depth N       octree depth to draw at most, 1..%d (default %d)\n"
            "  --error PX      level of detail: draw the shallowest level whose nodes span at most PX\n"
            "                  pixels on screen, 1/16..64, or 0 for --depth itself (default 1)\n"
            "  --cull on|off   skip subtrees whose surface all faces away, where the bake has normal cones\n"
            "                  (closed meshes; default on)\n"
            "  --size WxH      frame size, at most %ux%u (default 320x240)\n"
            "  --perspective   perspective projection, eye 2 cube sides away (default orthographic)\n"
            "  --fill MODE     hole filling after rendering: none, pixel (one-pixel holes) or scanline\n"
            "                  (the paper's neighbourhood criterion, hole types 1-4; default %s)\n"
            "  --no-finish     the same as --fill none\n"
            "  --splat MODE    pixels per leaf: 1 (one pixel, the paper's) or zoom (a square that grows\n"
            "                  with the leaf's size on screen; default %s)\n"
            "  --mode MODE     points (the octree), or the mesh part (bakes --as both): shaded, lines\n"
            "                  (silhouettes, creases, borders; hidden lines removed) or shaded+lines\n"
            "                  (default points)\n"
            "  --lod N|auto    the mesh's level of detail: N vertices, from its base to its full count, or\n"
            "                  auto: the finest that keeps frames at --target-ms (default full)\n"
            "  --target-ms T   the frame time --lod auto holds (default 16.7)\n"
            "  --stream SRC    draw the model's stream (a bake with modelc --emit stream) as it arrives from\n"
            "                  SRC: - (standard input), a file or FIFO, or tcp:HOST:PORT; the points at the\n"
            "                  deepest complete level, or (--mode, with --as both) the mesh at the finest\n"
            "                  level that has come, at most --lod N, or with --lod auto the finest of those\n"
            "                  the frame time allows (a line per level on stdout; the line\n"
            "                  styles draw shaded until the mesh's adjacency, which comes last); a stream\n"
            "                  that ends early or fails its checks is reported and its last complete level\n"
            "                  drawn (exit status 1)\n"
            "  --help          this text\n"
            "With no output option and stdout a terminal, runs interactively: arrow keys rotate, + and -\n"
            "zoom, m changes the mode, [ and ] the mesh's level of detail, q quits.\n",
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

static int bench(mc_host_scene *s, const mc_target *t, mc_view v, unsigned depth, int frames)
{
    static double ms[100000];
    if (frames > 100000) frames = 100000;
    uint64_t drawn = 0, culled = 0;
    int32_t yaw0 = v.yaw;
    for (int i = 0; i < frames; i++) {
        v.yaw = yaw0 + (int32_t)((int64_t)MC_ANGLE_FULL * i / frames);
        uint32_t n = 0;
        double t0 = mc_host_now_ms();
        mc_host_scene_draw(s, &v, depth, NULL, t, &n);
        ms[i] = mc_host_now_ms() - t0;
        drawn += n;
        culled += s->culled;
    }
    int in = 0, settled = 0;   /* frames the automatic level of detail held within 10 %, after 20 */
    for (int i = 20; i < frames; i++, settled++) in += fabs(ms[i] - s->target_ms) <= 0.1 * s->target_ms;
    double median = mc_host_median(ms, (size_t)frames);
    double mean = (double)drawn / frames;
    if (s->target_ms > 0) printf("target %.3f ms: %d of %d frames after the first 20 within 10 %%\n", s->target_ms, in, settled);
    const char *what = s->mode == MC_HOST_POINTS ? "points" : "faces";
    if (s->mode == MC_HOST_POINTS)
        printf("model %s depth %u size %ux%u frames %d%s\n", mc_app_model.model->name, s->drawn_depth, t->width, t->height,
               frames, s->fill == MC_FILL_NONE ? " no-finish" : "");
    else
        printf("model %s mode %s lod %u of %u vertices size %ux%u frames %d%s\n", mc_app_model.model->name,
               mc_host_mode_name(s->mode), s->lod.level, s->lod.pm->vertices, t->width, t->height, frames,
               s->lod.nbr ? " neighbour-table" : "");
    printf("ms per frame (median): %.3f\n", median);
    printf("%s drawn per frame: %.0f\n", what, mean);
    if (s->mode == MC_HOST_POINTS) printf("back-facing nodes skipped per frame: %.0f\n", (double)culled / frames);
    printf("M%s/s: %.2f\n", what, mean / median / 1e3);
    return 0;
}

/* --checksums: the same frames, lines and written frame as the firmware (runtime/front/fw/main.c,
 * stream_main.c): the point frames of octree (null: none, a stream's mesh came first), then the
 * mesh frames of pm (null: none) within its levels up to max_level, the line styles when lines
 * (mesh_frames.h mc_front_mesh_check_to). */
static int checksums(const mc_octree *octree, const mc_pmesh *pm, uint32_t max_level, int lines, const mc_target *t,
                     unsigned depth, const char *png, const char *ppm)
{
    int status = 0;
    for (unsigned i = 0; octree && i < MC_FRONT_FRAME_COUNT; i++) {
        mc_front_result r = mc_front_frame(octree, i, depth, t);
        printf(MC_FRONT_FRAME_LINE, MC_FRONT_FRAME_ARGS(i, depth, t, r));
        if (r.rc != MC_OK) status = 1;
        if (i == MC_FRONT_PPM_VIEW && (png || ppm)) {
            mc_host_to_rgb(t, octree->palette, rgb_buffer);
            if (png && mc_host_write_png(png, rgb_buffer, t->width, t->height)) return die("cannot write PNG", png);
            if (ppm && mc_host_write_ppm(ppm, rgb_buffer, t->width, t->height)) return die(strerror(errno), ppm);
        }
    }
    if (pm && mc_app_model.pmesh_anc && mc_app_model.pmesh_facing) {
        mc_pmesh_lod lod;
        mc_pmesh_lod_init(&lod, pm, mc_app_model.pmesh_anc);
        mc_host_mesh_neighbours(&lod, &mc_app_model);   /* (the same frames) */
        for (unsigned i = 0; i < MC_FRONT_VIEW_COUNT; i++) {
            mc_front_mesh_result r = mc_front_mesh_check_to(&lod, mc_app_model.pmesh_facing, mc_app_model.pmesh_cache,
                                                            mc_app_model.pmesh_sdepth, i, t, max_level, lines);
            printf(MC_FRONT_MESH_LINE, MC_FRONT_MESH_ARGS(i, pm, t, r));
            if (r.rc != MC_OK) status = 1;
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
    mc_octree_options opt = {MC_SPLAT_DEFAULT, MC_LOD_PIXEL, MC_CULL_DEFAULT};
    mc_host_mode mode = MC_HOST_POINTS;
    const char *lod_arg = NULL, *stream_src = NULL;
    double target_ms = 1000.0 / 60;
    long frames = 0;
    static const struct option opts[] = {
        {"png", required_argument, 0, 'P'}, {"ppm", required_argument, 0, 'M'},
        {"bench", required_argument, 0, 'b'}, {"yaw", required_argument, 0, 'y'},
        {"pitch", required_argument, 0, 'p'}, {"roll", required_argument, 0, 'r'},
        {"zoom", required_argument, 0, 'z'}, {"depth", required_argument, 0, 'd'},
        {"size", required_argument, 0, 's'}, {"no-finish", no_argument, 0, 'n'},
        {"perspective", no_argument, 0, 'e'}, {"checksums", no_argument, 0, 'c'},
        {"help", no_argument, 0, 'h'}, {"fill", required_argument, 0, 'f'},
        {"splat", required_argument, 0, 'S'}, {"mode", required_argument, 0, 'm'},
        {"lod", required_argument, 0, 'l'}, {"target-ms", required_argument, 0, 't'},
        {"error", required_argument, 0, 'E'}, {"cull", required_argument, 0, 'C'},
        {"stream", required_argument, 0, 'R'}, {0, 0, 0, 0}};
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
        case 'C':
            if (!strcmp(optarg, "on")) opt.cull = MC_CULL_DEFAULT;
            else if (!strcmp(optarg, "off")) opt.cull = MC_CULL_OFF;
            else return die("--cull expects on or off", optarg);
            break;
        case 'E':
            if (parse_double(optarg, 0, 64, &dv) || (dv > 0 && dv < 1.0 / 16))
                return die("--error expects 0 or 1/16..64 pixels", optarg);
            opt.max_error = (uint16_t)lround(dv * MC_LOD_PIXEL);
            break;
        case 'm':
            if (mc_host_mode_parse(optarg, &mode)) return die("--mode expects points, shaded, lines or shaded+lines", optarg);
            break;
        case 'l': lod_arg = optarg; break;
        case 'R': stream_src = optarg; break;
        case 't':
            if (parse_double(optarg, 0.01, 10000, &target_ms)) return die("--target-ms expects 0.01..10000 ms", optarg);
            break;
        case 'h': usage(stdout); return 0;
        default: return die("unknown option (see --help)", argv[optind - 1]);
        }
    }
    if (optind < argc) return die("unexpected argument (see --help)", argv[optind]);
    mc_host_scene scene;
    if (mc_host_scene_init(&scene, &mc_app_model, mode, &opt, fill))
        return die("the model has no mesh part to draw (bake it with modelc --as both)", mc_host_mode_name(mode));
    if (lod_arg) {
        if (!mc_host_scene_has_mesh(&scene)) return die("--lod needs a mesh part (bake with modelc --as both)", lod_arg);
        const mc_pmesh *pm = model->pmesh;
        if (!strcmp(lod_arg, "auto")) mc_host_scene_auto(&scene, target_ms);
        else if (parse_double(lod_arg, pm->base_vertices, pm->vertices, &dv) || dv != (uint32_t)dv)
            return die("--lod expects auto or a vertex count from the mesh's base to its full count", lod_arg);
        else mc_host_scene_set_level(&scene, (uint32_t)dv);
    }

    if (check && !sized) {
        w = mc_app_model.max_width;
        h = mc_app_model.max_height;
    }
    mc_target t = {mc_app_model.color, mc_app_model.depth, (uint16_t)w, (uint16_t)h};
    static mc_host_stream stream;
    int stream_failed = 0;
    if (stream_src) {
        char why[512];
        if (frames) return die("--stream and --bench exclude each other", NULL);
        if (mc_host_stream_open(&stream, &mc_app_model, stream_src, why, sizeof why)) return die(why, NULL);
        scene.octree = NULL;
        mc_host_scene_stream_mesh(&scene, NULL, 0);
        if (check || png || ppm || !isatty(STDOUT_FILENO)) {
            /* one-shot: read it all, a line per level (octree depth, mesh level) as it becomes drawable */
            unsigned depth_shown = 0;
            uint32_t mesh_shown = 0;
            int lines_shown = 0;
            while (!stream.done) {
                if (!mc_host_stream_pump(&stream, 1)) continue;
                const unsigned long len = stream.reader.len, total = stream.reader.total;
                if (stream.depth > depth_shown)
                    printf("stream: depth %u of %u after %lu of %lu bytes\n", stream.depth, (unsigned)stream.reader.depth,
                           len, total);
                if (stream.mesh_level > mesh_shown)
                    printf("stream: mesh level %lu of %lu after %lu of %lu bytes\n", (unsigned long)stream.mesh_level,
                           (unsigned long)stream.reader.pmesh.vertices, len, total);
                if (stream.mesh_lines > lines_shown) printf("stream: mesh lines after %lu of %lu bytes\n", len, total);
                depth_shown = stream.depth, mesh_shown = stream.mesh_level, lines_shown = stream.mesh_lines;
            }
            if (mc_host_stream_ok(&stream))
                printf("stream: complete, depth %u, %lu bytes\n", stream.depth, (unsigned long)stream.reader.len);
            fflush(stdout);
            /* --checksums draws what has come: the point frames of its octree, the mesh frames of its mesh */
            const int drawable = check ? stream.depth != 0 || stream.mesh_level != 0
                                 : mode == MC_HOST_POINTS ? stream.depth != 0 : stream.mesh_level != 0;
            if (!mc_host_stream_ok(&stream)) {
                char line[300];
                mc_host_stream_status(&stream, line, sizeof line);
                fprintf(stderr, "%s-view: %s\n", model->name, line);
                if (!drawable) return 1;
                stream_failed = 1;
            } else if (!drawable) {   /* a whole stream of a points bake, read by a mesh mode */
                return die("the stream has no mesh part (bake it with modelc --as both --emit stream)", stream_src);
            }
            if (mode != MC_HOST_POINTS) {
                mc_host_scene_stream_mesh(&scene, mc_host_stream_pmesh(&stream), stream.mesh_level);
                if (mode != MC_HOST_SHADED && !stream.mesh_lines)
                    fprintf(stderr, "%s-view: drawing shaded: the line styles need the mesh's adjacency, which had not come\n",
                            model->name);
            }
            /* the stream's points (none when only its mesh has come: --checksums draws the mesh alone) */
            octree = scene.octree = mc_host_stream_octree(&stream);
            if (octree && depth > octree->depth) depth = octree->depth;
        }
    }
    if (check) {
        if (frames) return die("--checksums and --bench exclude each other", NULL);
        if (mode != MC_HOST_POINTS) return die("--checksums draws points only", NULL);
        /* a stream's mesh frames within the levels that have come, as the stream firmware draws them */
        const mc_pmesh *pm = model->pmesh;
        uint32_t max_level = pm ? pm->vertices : 0;
        int lines = 1;
        if (stream_src) {
            pm = mc_host_stream_pmesh(&stream);
            max_level = stream.mesh_level;
            lines = stream.mesh_lines && pm && max_level == pm->vertices;
        }
        int rc = checksums(octree, pm, max_level, lines, &t, depth, png, ppm);
        return rc ? rc : stream_failed;
    }
    mc_view v = mc_view_default();
    v.yaw = mc_host_angle(yaw);
    v.pitch = mc_host_angle(pitch);
    v.roll = mc_host_angle(roll);
    v.zoom = (int32_t)lround(zoom * MC_ZOOM_ONE);
    v.projection = perspective ? MC_PERSPECTIVE : MC_ORTHOGRAPHIC;

    if (frames) return bench(&scene, &t, v, depth, (int)frames);
    if (!png && !ppm) {
        if (isatty(STDOUT_FILENO)) return mc_host_interactive(&scene, v, stream_src ? &stream : NULL);
        return die("stdout is not a terminal: give --png FILE, --ppm FILE or --bench N (see --help)", NULL);
    }

    uint32_t drawn = 0;
    double t0 = mc_host_now_ms();
    int rc = mc_host_scene_draw(&scene, &v, depth, NULL, &t, &drawn);
    double ms = mc_host_now_ms() - t0;
    if (rc != MC_OK) return die("render failed", NULL);
    mc_host_to_rgb(&t, mc_host_scene_palette(&scene), rgb_buffer);
    if (png && mc_host_write_png(png, rgb_buffer, (int)w, (int)h)) return die("cannot write PNG", png);
    if (ppm && mc_host_write_ppm(ppm, rgb_buffer, (int)w, (int)h)) return die(strerror(errno), ppm);
    if (mode == MC_HOST_POINTS)
        printf("model %s depth %u size %ux%u points %u ms %.3f\n", model->name, scene.drawn_depth, w, h, drawn, ms);
    else
        printf("model %s mode %s lod %u of %u vertices, %u faces size %ux%u faces drawn %u ms %.3f\n", model->name,
               mc_host_mode_name(mode), scene.lod.level, scene.lod.pm->vertices, scene.lod.faces, w, h, drawn, ms);
    return stream_failed;
}
