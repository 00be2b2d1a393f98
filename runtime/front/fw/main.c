/* The firmware front end: renders the fixed frame list (../common/views.h's views, then
 * ../common/frames.h's views with the renderer's options set) of the model linked in, on a Cortex-M
 * under QEMU or on a board with a semihosting debugger.
 *
 * Promise: for every point frame, one line on the semihosting console, exactly as the host viewer's
 * --checksums prints it (../common/frames.h: FNV-1a of the finished colour and depth buffers); the frame of
 * view MC_FRONT_PPM_VIEW written to the host as a binary PPM (ppm_out.h) named by the first
 * semihosting argument after the program name (default "frame.ppm"); then the measured stack
 * high-water mark and the free RAM it may grow into, and "done". When the bake has a mesh part
 * (modelc --as both) and the firmware is built for it (make firmware FW_MESH=1: MC_FW_MESH=1), the
 * mesh frames of ../common/mesh_frames.h come after the point frames, one line each, again exactly as
 * the host viewer's --checksums prints them. Without MC_FW_MESH no mesh code is linked: a points-only
 * firmware's flash is what its budget.json counts. With the word "bench" after the
 * file name, also a line "cost frame I clear N render N finish N" per point frame and "cost mesh frame
 * I lod N draw N ..." per mesh frame: the instructions of each stage counted through SysTick,
 * meaningful under qemu-system-arm -icount shift=0 (counter.h); for the mesh frames with lines, also
 * the same view and level drawn shaded only, so that the lines' own instructions are the difference.
 * Exits (semihosting) with 0, or 1
 * if a render or the file failed. All buffers are the model's static frame buffers (mc_app_model,
 * sized by modelc --screen); nothing is allocated.
 */
#include <semihost.h>
#include <stdio.h>
#include <string.h>

#include <modelc/app.h>
#include <modelc/modelc.h>

#include "cmdline.h"
#include "counter.h"
#include "mark.h"   /* defines MC_FRONT_MARK before frames.h */
#include "../common/frames.h"
#include "../common/mesh_frames.h"
#include "ppm_out.h"
#include "stack.h"

/* The semihosting command line's words after the program name: the output file name (default
 * "frame.ppm"), then optionally "bench". */
static const char *ppm_path = "frame.ppm";
static int bench;

static void read_cmdline(void)
{
    char *w[2];
    const unsigned n = mc_fw_cmdline(w, 2);
    if (n >= 1) ppm_path = w[0];
    if (n >= 2 && strcmp(w[1], "bench") == 0) bench = 1;
}

#ifndef MC_FW_MESH
#define MC_FW_MESH 0
#endif

#if MC_FW_MESH
static uint32_t marked(unsigned from, unsigned to)
{
    return mc_fw_counter_insns(mc_fw_marks[from], mc_fw_marks[to]);
}

/* The mesh frames after the point frames; returns 1 if a frame failed. */
static int mesh_frames(const mc_pmesh *pm, const mc_target *t)
{
    int status = 0;
    mc_pmesh_lod lod;
    mc_pmesh_lod_init(&lod, pm, mc_app_model.pmesh_anc);
    mc_pmesh_lod_neighbours(&lod, mc_app_model.pmesh_nbr);   /* (a bake with --mesh-neighbours; else none) */
    printf("modelc firmware: mesh %lu vertices %lu faces (base %lu, %lu) vertex cache %s neighbour table %s\n",
           (unsigned long)pm->vertices, (unsigned long)pm->faces, (unsigned long)pm->base_vertices,
           (unsigned long)pm->base_faces, mc_app_model.pmesh_cache ? "yes" : "no", lod.nbr ? "yes" : "no");
    for (unsigned i = 0; i < MC_FRONT_VIEW_COUNT; i++) {
        mc_front_mesh_result r = mc_front_mesh_check(&lod, mc_app_model.pmesh_facing, mc_app_model.pmesh_cache,
                                                         mc_app_model.pmesh_sdepth, i, t);
        printf(MC_FRONT_MESH_LINE, MC_FRONT_MESH_ARGS(i, pm, t, r));
        if (r.rc != MC_OK) status = 1;
        if (!bench) continue;
        const uint32_t lod_insns = marked(MC_FRONT_MESH_MARK_LOD, MC_FRONT_MESH_MARK_DRAW);
        const uint32_t draw = marked(MC_FRONT_MESH_MARK_DRAW, MC_FRONT_MESH_MARK_DONE);
        uint32_t shaded = draw;
        if (r.style != MC_FRONT_SHADED) {
            /* not checked: the frame again without its lines, at the same level and view */
            const mc_view v = mc_front_view_get(i);
            MC_FRONT_MARK(MC_FRONT_MESH_MARK_DRAW);
            mc_front_mesh_frame(&lod, mc_app_model.pmesh_facing, mc_app_model.pmesh_cache, mc_app_model.pmesh_sdepth,
                                &v, MC_FRONT_SHADED, t, 0);
            MC_FRONT_MARK(MC_FRONT_MESH_MARK_DONE);
            shaded = marked(MC_FRONT_MESH_MARK_DRAW, MC_FRONT_MESH_MARK_DONE);
        }
        printf("cost mesh frame %u style %s lod %lu draw %lu shaded-only %lu faces %lu drawn %lu face-pixels %lu "
               "edges %lu lines %lu line-pixels %lu\n",
               i, mc_front_mesh_style_name(r.style), (unsigned long)lod_insns, (unsigned long)draw,
               (unsigned long)shaded, (unsigned long)r.faces, (unsigned long)r.st.faces.drawn,
               (unsigned long)r.st.faces.pixels, (unsigned long)r.st.lines.edges,
               (unsigned long)(r.st.lines.silhouettes + r.st.lines.creases + r.st.lines.borders - r.st.lines.clipped_away),
               (unsigned long)r.st.lines.pixels);
    }
    return status;
}
#endif

int main(void)
{
    mc_fw_stack_paint();
    read_cmdline();
    if (bench) mc_fw_counter_start_report();
    const mc_model *model = mc_app_model.model;
    const mc_octree *octree = model->octree;
    if (!octree) {
        printf("modelc firmware: model %s has no octree to draw\n", model->name);
        return 1;
    }
    const mc_target t = {mc_app_model.color, mc_app_model.depth, mc_app_model.max_width, mc_app_model.max_height};
    const unsigned depth = octree->depth;
    int status = 0;
    printf("modelc firmware: model %s depth %u size %ux%u views %u frames %u\n", model->name, depth, (unsigned)t.width,
           (unsigned)t.height, MC_FRONT_VIEW_COUNT, MC_FRONT_FRAME_COUNT);
    for (unsigned i = 0; i < MC_FRONT_FRAME_COUNT; i++) {
        mc_front_result r = mc_front_frame(octree, i, depth, &t);
        printf(MC_FRONT_FRAME_LINE, MC_FRONT_FRAME_ARGS(i, depth, &t, r));
        if (r.rc != MC_OK) status = 1;
        if (bench)
            printf("cost frame %u clear %lu render %lu finish %lu points %lu\n", i,
                   (unsigned long)mc_fw_counter_insns(mc_fw_marks[0], mc_fw_marks[1]),
                   (unsigned long)mc_fw_counter_insns(mc_fw_marks[1], mc_fw_marks[2]),
                   (unsigned long)mc_fw_counter_insns(mc_fw_marks[2], mc_fw_marks[3]), (unsigned long)r.points);
        if (i == MC_FRONT_PPM_VIEW) {
            if (mc_fw_write_ppm(ppm_path, &t, octree->palette) != 0) {
                printf("cannot write %s through semihosting\n", ppm_path);
                status = 1;
            } else {
                printf("wrote frame %u to %s\n", i, ppm_path);
            }
        }
    }
#if MC_FW_MESH
    if (model->pmesh && mc_app_model.pmesh_anc && mc_app_model.pmesh_facing && mesh_frames(model->pmesh, &t))
        status = 1;
#endif
    printf("stack used %lu of %lu bytes free for it\n", (unsigned long)mc_fw_stack_used(),
           (unsigned long)mc_fw_stack_room());
    printf("done\n");
    return status;
}
