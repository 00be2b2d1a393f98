// What the runtime itself costs a firmware image, for the budgets (modelc --flash-budget etc.) and
// budget.json. Constants, measured; re-measure them when runtime/src changes (the commands are below)
// — tests/gen/budget.sh checks the stack table against a fresh -fstack-usage build when
// arm-none-eabi-gcc is installed.
//
// Code sizes: text + rodata of each module compiled for the smallest target we budget for,
//   arm-none-eabi-gcc 12.2 -std=c99 -ffreestanding -mcpu=cortex-m4 -mthumb -O2
//     -ffunction-sections -fdata-sections -Iruntime/include -c runtime/src/MODULE.c
//   arm-none-eabi-size MODULE.o
// once with the default MC_LEAF_SWITCH=1 and once with -DMC_LEAF_SWITCH=0 (config.h). The runtime
// has no .data and no .bss: its static RAM is 0. 64-bit divisions (view clamp, perspective,
// clipping) pull in libgcc's __aeabi_ldivmod/__aeabi_uldivmod/__udivmoddi4: 960 bytes, from the link
// map of a Cortex-M4 picolibc program. Host (x86-64 -O2) code is larger (octree_render.o 88831 bytes, with
// the depth test as a select, MC_DEPTH_SELECT's default there, and MC_FLAT_SQUARES); the budget is for
// the firmware target.
// Header-only modules (bits.h, chunk.h, rng.h) have no code of their own: what they inline is
// counted in their callers'.
//
// Stack: bytes per function from -fstack-usage (every entry "static", no dynamic frames), compiled
// as above for Cortex-M4 and with host gcc 12 -O2 (x86-64), taking the larger of the two. Both in the
// firmware's configuration: the host with -DMC_FLAT_SQUARES=0 (its x86-64 default, 1, walks 2x2
// squares with 64 leaf vectors in the renderer's context and a frame of runs: about 1 KB more,
// which a desktop viewer has and no firmware budget pays). Functions
// the compiler inlines (mc_cursor_*, exact_level2, setup_vectors, poll_abort, leaves) do not appear;
// their frames are part of their callers'.
#pragma once
#include <cstddef>

namespace mc::rt {

struct ModuleCode {
    const char *name;
    size_t bytes;        // MC_LEAF_SWITCH=1 (the default)
    size_t bytes_loop;   // MC_LEAF_SWITCH=0
    const char *what;
};

inline constexpr ModuleCode kModules[] = {
    {"fixed", 476, 476, "fixed-point helpers (fixed.c)"},
    {"trig", 4240, 4240, "sine and cosine: trig.c 140 + the 1025-entry table sintab.c 4100"},
    {"xform", 512, 512, "view clamping and rotation matrix (xform.c)"},
    {"target", 116, 116, "clearing the colour and depth buffers (target.c)"},
    {"octree_render", 69580, 12972, "the octree renderer (octree_render.c); MC_LEAF_SWITCH=1: a case per mask"},
    {"finish", 1908, 1908, "hole filling (finish.c)"},
};
// The mesh part's modules, counted when a bake has one (--as both): what a program drawing it links.
inline constexpr ModuleCode kMeshModules[] = {
    {"pmesh", 2408, 2408, "progressive-mesh level of detail, neighbours and their table (pmesh.c)"},
    {"xform_vertex", 4352, 4352, "vertex projection and near-plane and guard-band clipping (xform_vertex.c)"},
    {"raster", 7408, 7408, "filled triangles with a z-buffer, and the face pass over a sparse depth buffer (raster.c)"},
    {"line", 2904, 2904, "clipped lines with a depth test, or into a sparse depth buffer (line.c)"},
    {"sdepth", 868, 868, "the sparse depth buffer: entries at line pixels, bit vectors to skip the rest (sdepth.c)"},
    {"mesh_render", 3756, 3756, "flat-shaded faces of the current level in their stored shades or worked-out ones, clipped where needed (mesh_render.c)"},
    {"mesh_lines", 7876, 7876, "silhouettes, creases and borders, hidden lines by z-buffer or sparse depth buffer, clipped (mesh_lines.c)"},
    {"mesh_creases", 3692, 3692, "the level's crease bits, brought over after a small level change, or from the stored ones (mesh_creases.c)"},
    {"silhouette", 1536, 1536, "silhouette edges, exact and searched within a work bound (silhouette.c)"},
};
// The edge part's own modules (--as edges): a tracker links them with fixed, raster, line and sdepth
// from the tables above (budget.cpp track_code_bytes).
inline constexpr ModuleCode kTrackModules[] = {
    {"camera", 2252, 2252, "pinhole projection of poses, near-plane clipping (camera.c)"},
    {"imgedge", 2744, 2744, "image edges: Sobel, orientation bins, non-maximum suppression, masks (imgedge.c)"},
    {"track", 3360, 3360, "the score of a pose: lines and faces into the sparse depth buffer (track.c)"},
    {"particles", 3500, 3500, "the particle filter over poses (particles.c)"},
    {"detect", 1036, 1036, "re-detection: the image shift that fits a trial orientation best (detect.c)"},
};
inline constexpr const char *kTrackShared[] = {"fixed", "raster", "line", "sdepth"};
inline constexpr size_t kLibgccDivision = 960;
inline constexpr size_t kRuntimeStaticRam = 0;

// Sizes of the descriptors on a 32-bit target (chunk.h, octree.h, model.h; sizeof with
// arm-none-eabi-gcc): mc_chunk {pointer, uint32}, mc_octree_level {uint32, 3 pointers}, mc_octree
// {uint8, uint16, 2 pointers}, mc_model {4 int64, 4 pointers, uint8, padded to 8}.
inline constexpr size_t kChunkBytes = 8, kLevelBytes = 16, kOctreeBytes = 12, kModelBytes = 56;
// mc_pmesh {5 uint32, 4 uint8, uint16, int16, 7 pointers} on a 32-bit target.
inline constexpr size_t kPmeshBytes = 56;
// mc_edges {3 uint32, 4 uint8, 4 pointers}, mc_particle {7 int32, 3 uint32}, mc_xvertex on a 32-bit target.
inline constexpr size_t kEdgesBytes = 32, kParticleBytes = 40, kXvertexBytes = 16;

// -fstack-usage of every function of octree_render.c, fixed.c, trig.c and xform.c that
// mc_octree_render can reach.
struct Frame {
    const char *function;
    size_t arm, host;
    constexpr size_t bytes() const { return arm > host ? arm : host; }
};
inline constexpr Frame kFrames[] = {
    {"mc_octree_render", 2232, 2480},   // holds a ctx sized for MC_MAX_DEPTH = 12 levels
    {"mc_octree_lod_depth", 56, 80},
    {"culled", 24, 24},
    {"visit", 72, 112},                  // visit_children always inlined into it
    {"frame_children", 80, 112},
    {"persp_node", 96, 176},
    {"linear_frame", 208, 72},
    {"skip_subtree", 56, 48},
    {"visit_inside", 80, 96},
    {"draw_inside", 120, 72},
    {"draw_inside_squares", 160, 136},
    {"draw_checked", 80, 96},
    {"leaves_perspective", 80, 128},
    {"leaves_clipped", 72, 80},
    {"draw_square", 28, 16},
    {"classify", 16, 8},
    {"mc_mul_shift64", 24, 8},
    {"mc_view_clamp", 24, 8},
    {"mc_view_rotation", 176, 272},
    {"matmul.constprop", 24, 8},
    {"mc_sin", 0, 8},
    {"mc_cos", 0, 8},
};
// Function fn's frame in table t; unknown: no bound (a compile-time error where used in a constant).
template <size_t N>
constexpr size_t frame_in(const Frame (&t)[N], const char *fn) {
    for (const Frame &f : t) {
        const char *a = f.function, *b = fn;
        while (*a && *a == *b) a++, b++;
        if (*a == *b) return f.bytes();
    }
    return 1u << 30;
}
constexpr size_t frame(const char *fn) { return frame_in(kFrames, fn); }

// The bounded call graph of mc_octree_render drawing at depth d (octree_render.c):
//   mc_octree_render -> mc_view_clamp
//             -> mc_octree_lod_depth -> mc_view_clamp
//             -> [setup_vectors] -> mc_view_rotation -> matmul | mc_cos -> mc_sin ; mc_mul_shift64
//             -> classify
//             -> visit / visit_inside: one frame per level 0..d-3 (max(d-2, 1) frames; visit, with
//                visit_children inlined, recurses only into children at levels <= d-3, visit_inside
//                likewise), then (visit -> frame_children, or visit_inside) the deepest of the draws:
//                  draw_inside, draw_inside_squares (footprints over a pixel)
//                  draw_checked -> [leaves] -> leaves_perspective -> mc_mul_shift64 | draw_square
//                                           | leaves_clipped -> draw_square | classify
//                  classify, skip_subtree, culled (a leaf: it skips a culled subtree inline)
//                  [poll_abort] -> the abort callback (the caller's code: add its own stack)
//                or, in perspective, from visit_children at level d-4 (or mc_octree_render at d = 3):
//                  persp_node -> linear_frame | frame_children -> the draws | [exact_level2] -> leaves
// [bracketed] functions are inlined into their callers. The bound is mc_octree_render's frame plus
// the deepest of those paths. mc_clear and mc_finish_* are called by the front end beside it,
// never inside it, and their frames are smaller than the walk's.
constexpr size_t max2(size_t a, size_t b) { return a > b ? a : b; }
constexpr size_t stack_setup() {
    return max2(frame("mc_octree_lod_depth") + frame("mc_view_clamp"),
                frame("mc_view_rotation") + max2(frame("matmul.constprop"), frame("mc_cos") + frame("mc_sin")));
}
constexpr size_t stack_tail() {
    const size_t leaves = max2(frame("leaves_perspective") + max2(frame("mc_mul_shift64"), frame("draw_square")),
                               frame("leaves_clipped") + max2(frame("draw_square"), frame("classify")));
    const size_t draws = max2(max2(max2(frame("draw_inside"), frame("draw_inside_squares")), frame("culled")),
                              max2(frame("draw_checked") + leaves, max2(frame("classify"), frame("skip_subtree"))));
    const size_t frames = frame("frame_children") + draws;
    const size_t persp = frame("persp_node") + max2(max2(frame("linear_frame"), frames), leaves);
    return max2(frames, persp);
}
constexpr size_t stack_walk_frame() { return max2(frame("visit"), frame("visit_inside")); }
constexpr int walk_frames(int depth) { return depth > 3 ? depth - 2 : 1; }
constexpr size_t stack_bound(int depth) {
    return frame("mc_octree_render") + max2(stack_setup(), static_cast<size_t>(walk_frames(depth)) * stack_walk_frame() + stack_tail());
}
static_assert(stack_bound(8) < (1u << 20), "a function of the call graph is missing from kFrames");

// -fstack-usage of every function of particles.c, detect.c, track.c, camera.c, raster.c's face pass
// and imgedge.c that a tracker's frame can reach, measured as kFrames is.
inline constexpr Frame kTrackFrames[] = {
    {"mc_filter_step", 232, 304},
    {"mc_filter_resample", 64, 32},
    {"mc_filter_recall", 32, 16},
    {"mc_detect_shift", 912, 1008},
    {"best_of", 80, 56},
    {"mc_detect_move", 24, 8},
    {"move", 80, 112},
    {"step.part.0", 56, 32},
    {"score", 80, 112},
    {"mc_quat_unit", 88, 8},
    {"mc_pose_set", 96, 80},
    {"mc_pose_apply", 16, 8},
    {"mc_track_score_pose", 224, 320},
    {"mc_sdepth_forget", 56, 56},
    {"camera_point.isra", 24, 32},
    {"mc_camera_project", 32, 8},
    {"image_coord", 8, 8},
    {"udiv64_wide", 40, 56},
    {"divlu", 28, 32},
    {"round_shl", 20, 8},
    {"mc_camera_clip_segment", 48, 80},
    {"mc_camera_clip_triangle", 64, 104},
    {"cut", 56, 24},
    {"front.isra", 12, 16},
    {"draw_line", 80, 96},
    {"mc_imgedge_bin", 24, 8},
    {"mc_track_line", 128, 56},
    {"hide", 56, 64},
    {"mc_raster_slope", 64, 24},
    {"mc_raster_triangle_hide_offset", 280, 336},
    {"draw_rows_hide", 280, 368},
    {"plane_first", 72, 56},
    {"plane_step.isra", 40, 32},
    {"lazy_value", 32, 56},
    {"mc_imgedge", 176, 224},
    {"candidate_code", 36, 8},
    {"thin_row", 32, 40},
    {"mc_imgedge_masks", 32, 48},
    {"mc_imgedge_spread", 12, 8},
    {"mc_imgedge_spread.part.0", 80, 56},
};
constexpr size_t track_frame(const char *fn) { return frame_in(kTrackFrames, fn); }
constexpr size_t max3(size_t a, size_t b, size_t c) { return max2(a, max2(b, c)); }

// The call graph of a tracker's frame, each chain taken whole where the calls inside a file are not
// certain (a bound, not the exact deepest path):
//   front end -> mc_imgedge -> thin_row | candidate_code | mc_imgedge_bin ; mc_imgedge_masks -> mc_imgedge_spread
//             ; mc_imgedge_spread -> its outlined part
//             -> mc_filter_step -> mc_filter_resample | mc_filter_recall | step | move -> step | mc_quat_unit
//                  | score -> mc_pose_set -> mc_quat_unit
//                  | mc_detect_shift -> mc_track_score_pose (below) | best_of ; mc_detect_move
//                          | mc_track_score_pose -> mc_sdepth_forget | camera_point -> mc_pose_apply
//                              | projection: mc_camera_project -> image_coord -> udiv64_wide -> divlu, round_shl
//                              | mc_camera_clip_segment | mc_camera_clip_triangle -> cut -> projection
//                              | front | draw_line -> mc_imgedge_bin | mc_track_line
//                              | hide -> mc_raster_slope | mc_raster_triangle_hide_offset -> draw_rows_hide
//                                       -> plane_first | plane_step | lazy_value
// The caller's own frame (the front end's main) comes on top.
constexpr size_t track_projection() {
    return track_frame("mc_camera_project") + track_frame("image_coord") + track_frame("udiv64_wide") +
           track_frame("divlu") + track_frame("round_shl");
}
constexpr size_t track_score_pose() {
    const size_t clip = max2(track_frame("mc_camera_clip_segment"), track_frame("mc_camera_clip_triangle")) +
                        track_frame("cut") + track_projection();
    const size_t line = track_frame("draw_line") + max2(track_frame("mc_imgedge_bin"), track_frame("mc_track_line"));
    const size_t face = track_frame("hide") +
                        max2(track_frame("mc_raster_slope"),
                             track_frame("mc_raster_triangle_hide_offset") + track_frame("draw_rows_hide") +
                                 max3(track_frame("plane_first"), track_frame("plane_step.isra"), track_frame("lazy_value")));
    return track_frame("mc_track_score_pose") +
           max3(max3(track_frame("mc_sdepth_forget"), track_frame("camera_point.isra") + track_frame("mc_pose_apply"), clip),
                max2(track_frame("front.isra"), line), face);
}
constexpr size_t track_stack_bound() {
    const size_t move = track_frame("move") + max2(track_frame("step.part.0"), track_frame("mc_quat_unit"));
    const size_t filter = track_frame("mc_filter_step") +
                          max3(max3(track_frame("mc_filter_resample"), track_frame("mc_filter_recall"), track_frame("step.part.0")), move,
                               max3(track_frame("score") + max2(track_frame("mc_pose_set") + track_frame("mc_quat_unit"),
                                                                track_score_pose()),
                                    track_frame("mc_detect_shift") + max2(track_score_pose(), track_frame("best_of")),
                                    track_frame("mc_detect_move")));
    const size_t edges = max2(track_frame("mc_imgedge") + max3(track_frame("thin_row"), track_frame("candidate_code"),
                                                                track_frame("mc_imgedge_bin")),
                              track_frame("mc_imgedge_masks") + track_frame("mc_imgedge_spread") +
                                  track_frame("mc_imgedge_spread.part.0"));
    return max2(filter, edges);
}
static_assert(track_stack_bound() < (1u << 20), "a function of the tracker's call graph is missing from kTrackFrames");

}  // namespace mc::rt
