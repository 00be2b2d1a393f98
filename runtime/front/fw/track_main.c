/* The firmware tracker: follows the edge model linked in (modelc --as edges, the app binding's
 * buffers sized by --screen and --particles) through the frames stored with it in flash, on a
 * Cortex-M under QEMU or on a board with a semihosting debugger (make firmware-track BOARD=...).
 *
 * The data: track_frames.py's generated C file (frames of a real sequence shrunk K times on the host
 * to the bake's screen, the camera's intrinsics in pixels of the unshrunk frames, the start pose as
 * ViSP writes it, the particle count). The work is the host tracker's (../track/tracker.c), through
 * the same code (../common/track_frame.h): the camera scaled by K and turned to Q16, the start pose
 * to Q30 and micrometres (../track/track_input.c's mc_track_pose_to_fixed), the tracker's default
 * settings with that particle count, and per frame mc_track_edges (the stored frame copied into the
 * binding's frame buffer, its edges, the masks) then one mc_filter_step.
 *
 * Promise: on the semihosting console, one line per frame exactly as the host tracker's --fixed-out
 * writes it (MC_TRACK_POSE_LINE: "pose K q0 q1 q2 q3 t0 t1 t2 visible matched confidence", K the
 * frame's number in the sequence), so that a test compares the two as text; with the word "bench"
 * after the program name, also "cost track K edges N filter N edge-pixels N particles N layers N" per
 * frame: the instructions of mc_track_edges and of mc_filter_step counted through SysTick (counter.h,
 * meaningful under qemu-system-arm -icount shift=0); then the measured stack high-water mark and
 * "done". Exits (semihosting) with 0, or 1 when the camera, the start or a filter step failed. All
 * memory is static: the binding's buffers and this file's state; nothing is allocated.
 */
#include <semihost.h>
#include <stdio.h>
#include <string.h>

#include <modelc/app.h>
#include <modelc/modelc.h>

#include "../common/track_frame.h"
#include "../track/track_input.h"
#include "cmdline.h"
#include "counter.h"
#include "stack.h"

/* track_frames.py's generated file */
extern const uint16_t mc_fw_track_width, mc_fw_track_height;
extern const uint32_t mc_fw_track_count, mc_fw_track_first, mc_fw_track_scale, mc_fw_track_particles;
extern const double mc_fw_track_camera[4], mc_fw_track_init[6];
extern const uint8_t *const mc_fw_track_frames[];

static int bench;

/* The semihosting command line's words after the program name: "bench" or nothing. */
static void read_cmdline(void)
{
    char *w[1];
    if (mc_fw_cmdline(w, 1) == 1 && strcmp(w[0], "bench") == 0) bench = 1;
}

static mc_camera cam;
static mc_track_state tr;

int main(void)
{
    mc_fw_stack_paint();
    read_cmdline();
    if (bench) mc_fw_counter_start_report();
    const mc_app *app = &mc_app_model;
    const uint16_t w = mc_fw_track_width, h = mc_fw_track_height;
    printf("modelc firmware tracker: model %s, %lu frames %ux%u (shrunk %lu times), %lu particles\n",
           app->model->name, (unsigned long)mc_fw_track_count, (unsigned)w, (unsigned)h,
           (unsigned long)mc_fw_track_scale, (unsigned long)mc_fw_track_particles);
    if (!app->model->edges || !app->edges_frame || w > app->max_width || h > app->max_height ||
        mc_fw_track_particles > app->max_particles) {
        printf("the bake has no edge part, or its screen or particles are too small for the frames\n");
        return 1;
    }
    mc_track_settings s;
    mc_track_settings_default(&s);
    s.particles = (long)mc_fw_track_particles;
    if (mc_track_camera_fixed(&cam, mc_fw_track_camera[0], mc_fw_track_camera[1], mc_fw_track_camera[2],
                              mc_fw_track_camera[3], mc_fw_track_scale, w, h, s.near_m, s.far_m) != MC_OK) {
        printf("not a usable camera\n");
        return 1;
    }
    int32_t q[4], t[3];
    mc_track_pose_to_fixed(mc_fw_track_init, q, t);
    const int started = mc_track_start(&tr, app, &cam, &s, q, t);
    if (started != MC_TRACK_START_OK) {
        printf("%s\n", started == MC_TRACK_START_SDEPTH ? "cannot set up the depth buffer" : "the filter's settings are out of range");
        return 1;
    }
    int status = 0;
    for (uint32_t i = 0; i < mc_fw_track_count; i++) {
        const uint32_t k = mc_fw_track_first + i;
        const uint32_t c0 = mc_fw_counter_now();
        const uint32_t edges = mc_track_edges(&tr, mc_fw_track_frames[i], w, 1, NULL, NULL);
        const uint32_t c1 = mc_fw_counter_now();
        const int rc = mc_filter_step(&tr.f, &tr.view, NULL);
        const uint32_t c2 = mc_fw_counter_now();
        if (rc != MC_OK) {
            printf("frame %lu: the filter failed (%d)\n", (unsigned long)k, rc);
            status = 1;
            break;
        }
        printf(MC_TRACK_POSE_LINE, MC_TRACK_POSE_ARGS(k, &tr.f));
        if (bench)
            printf("cost track %lu edges %lu filter %lu edge-pixels %lu particles %lu layers %lu\n", (unsigned long)k,
                   (unsigned long)mc_fw_counter_insns(c0, c1), (unsigned long)mc_fw_counter_insns(c1, c2),
                   (unsigned long)edges, (unsigned long)tr.f.prm.particles, (unsigned long)(tr.f.prm.layers ? tr.f.prm.layers : 1));
    }
    printf("stack used %lu of %lu bytes free for it\n", (unsigned long)mc_fw_stack_used(),
           (unsigned long)mc_fw_stack_room());
    printf("done\n");
    return status;
}
