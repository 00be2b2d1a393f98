/* The automatic level of detail of the host viewer (--lod auto --target-ms T): before each frame,
 * whether to move the level and to what face budget (mc_pmesh_lod_fit_to); after it, what the
 * frame's measured time teaches.
 *
 * Why it moves seldom and then far: in the line styles a level change costs far more than its splits.
 * The crease bits are brought over around every new face's corners (mesh_lines.h), some
 * microseconds a split at coarse levels of bunny00, the time of some hundred faces, or recomputed
 * whole for a large change; a neighbour table is kept likewise. Small steps to follow a turning view
 * would each push their frame out of the band; so the level stays while the frames are within
 * MC_HOST_LOD_TRIGGER of the target and otherwise moves in one change to where the frames are
 * predicted to take the target, paying for it in one frame.
 *
 * The prediction: a frame's time is not proportional to its faces (a line drawing at a coarse level
 * walks across removed faces to find neighbours; fixed costs stay), so the level is fitted along a
 * power law t ~ F^e through the time of the current level and that of the last one, e clamped to
 * 0.15 .. 1.5 (1 until two levels have been timed). A level's time is a moving average of its
 * frames (about three deep: a turning view changes it).
 *
 * Promise: mc_host_lod_auto_plan keeps the level (move 0) until a frame at it has been measured after
 * the first, and while the level's time is within MC_HOST_LOD_TRIGGER of the target; else it gives
 * the face budget of the fit. The first frame teaches nothing: it pays for whatever the level's state
 * needs from nothing. Host only (double precision); the firmware's deterministic budget is
 * mesh_frames.h's.
 */
#ifndef MODELC_HOST_LOD_AUTO_H
#define MODELC_HOST_LOD_AUTO_H

#include <stdint.h>

/* How far (a share of the target) a level's time may stray before the level moves: inside the 10 %
 * the frames are held in, by the frames' noise and a turn's drift between moves. */
#define MC_HOST_LOD_TRIGGER 0.06

typedef struct mc_host_lod_auto {
    double target_ms;       /* > 0: the frame time held */
    double level_ms;        /* the current level's time per frame (valid when level_frames > 0) */
    double last_ms;         /* the last level's (valid when last_faces > 0) */
    double exponent;        /* e of t ~ F^e between the two */
    uint32_t level_faces;   /* faces of the current level */
    uint32_t level_frames;  /* its frames measured */
    uint32_t last_faces;    /* faces of the last level timed (0: none) */
    uint32_t frames;        /* frames measured */
    int style;              /* what is drawn (the caller's tag: a style), whose times these are */
} mc_host_lod_auto;

typedef struct mc_host_lod_plan {
    int move;               /* 0: keep the level */
    uint32_t max_faces;     /* the face budget when moving */
} mc_host_lod_plan;

/* Starts holding target_ms (> 0) with nothing learned, for style -1 (none yet). */
void mc_host_lod_auto_init(mc_host_lod_auto *a, double target_ms);

/* Before a frame drawn in `style` (the caller's tag): when it is not the style learned so far, starts
 * anew for it (a level's time in one style says nothing of another's). */
void mc_host_lod_auto_style(mc_host_lod_auto *a, int style);

/* The plan for the next frame at a level of `faces` faces. */
mc_host_lod_plan mc_host_lod_auto_plan(const mc_host_lod_auto *a, uint32_t faces);

/* Learns from a frame drawn at `faces` faces in ms, not counting the level change before it (which
 * the caller times apart: mesh_lines.h mc_mesh_lines_level brings the line styles' state over). */
void mc_host_lod_auto_frame(mc_host_lod_auto *a, uint32_t faces, double ms);

#endif
