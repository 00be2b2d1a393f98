/* modelc runtime configuration.
 *
 * Every setting is a macro with a default; override it on the compiler command line
 * (-DMC_FRAC_BITS=20) or in a file named by -DMC_CONFIG_FILE="my_config.h". A setting that cannot
 * work fails the build with a message naming it, not with a wrong picture.
 */
#ifndef MODELC_CONFIG_H
#define MODELC_CONFIG_H

#ifdef MC_CONFIG_FILE
#include MC_CONFIG_FILE
#endif

/* MC_FRAC_BITS: fraction bits of the fixed-point screen coordinates (mc_fix). The source paper uses
 * 17 integer and 15 fraction bits in a 32-bit word. More fraction bits place points more exactly but
 * shrink the representable screen range: coordinates must stay below 2^(30 - MC_FRAC_BITS) pixels
 * (MC_COORD_LIMIT), and views are clamped to that (see xform.h). */
#ifndef MC_FRAC_BITS
#define MC_FRAC_BITS 15
#endif
#if MC_FRAC_BITS < 8 || MC_FRAC_BITS > 24
#error "MC_FRAC_BITS must be in 8..24: below 8 points land off by whole pixels, above 24 the screen range is under 64 pixels"
#endif

/* MC_POS_HEADER: a header replacing the renderer's screen-position arithmetic (runtime/src/pos.h,
 * Q MC_FRAC_BITS fixed point) with another number type through the same interface. Unset by
 * default and in every viewer, library and firmware build; the accuracy benchmark sets it to
 * measure fixed point against another format (tests/accuracy/pos_single.h). */

/* MC_MAX_DEPTH: deepest octree the runtime can decode. Sizes per-level tables on the stack
 * (about 110 bytes per level). The generator refuses deeper models. */
#ifndef MC_MAX_DEPTH
#define MC_MAX_DEPTH 12
#endif
#if MC_MAX_DEPTH < 1 || MC_MAX_DEPTH > 12
#error "MC_MAX_DEPTH must be in 1..12"
#endif

/* MC_ABORT_LEVEL: tree level at which the abort callback is polled. The source paper polls at level 4:
 * about 512 polls a frame for a face scan, so a frame gives up within a millisecond of a key press
 * while the poll costs nothing measurable. */
#ifndef MC_ABORT_LEVEL
#define MC_ABORT_LEVEL 4
#endif

/* MC_ANGLE_BITS: angles are integers, 2^MC_ANGLE_BITS units per full turn (default 4096, 0.088
 * degrees a unit). The sine table holds a quarter turn: 2^(MC_ANGLE_BITS-2)+1 entries. */
#ifndef MC_ANGLE_BITS
#define MC_ANGLE_BITS 12
#endif
#if MC_ANGLE_BITS != 12
#error "MC_ANGLE_BITS: only 12 is supported (the committed sine table has 1025 entries)"
#endif

/* MC_LEAF_SWITCH: how the renderer's hot loops visit the up to eight children of a node.
 *   1 (default): a switch with one case per mask value, each case drawing exactly its leaves: one
 *     indirect jump per node and no per-child tests; about 50 KB of code on x86-64. The walk above
 *     takes each node's children from a table (runtime/src/child_bits.h, 2 KB) instead of a bit
 *     scan each.
 *   0: the source paper's unrolled loop, a test and a branch per child, and a bit scan per child
 *     elsewhere; about 3 KB of code, for small flash. Both draw the same pixels in the same order. */
#ifndef MC_LEAF_SWITCH
#define MC_LEAF_SWITCH 1
#endif

/* MC_DEPTH_SELECT: how the hot loop's depth test updates a pixel.
 *   0 (default except on x86-64): a branch, taken when the leaf is nearer. Right for in-order cores
 *     without a branch predictor worth the name (Cortex-M), where a branch costs a cycle or two and
 *     every instruction counts (on Cortex-M4 the select costs about 2.5 more instructions a leaf).
 *   1 (default on x86-64): a select: the leaf's depth and colour are written to its pixel when it
 *     is nearer, else to a spare pixel that the renderer puts back afterwards; one conditional move
 *     of an index, so none of the mispredictions a deep desktop pipeline pays when near and far
 *     leaves alternate. On the benchmark machine (bunny00, depth 8, 320x240, gcc 12 -O2) 24.1
 *     instructions per drawn point against 23.0 for the branch, and about 0.8 times the branch's
 *     CPU time a frame, side by side in every run so far (tests/bench/RESULTS.md, "Depth test:
 *     branch or select").
 * Both draw the same pixels. */
#ifndef MC_DEPTH_SELECT
#if defined(__x86_64__) || defined(_M_X64)
#define MC_DEPTH_SELECT 1
#else
#define MC_DEPTH_SELECT 0
#endif
#endif

/* MC_LINE_SELECT: how the line walk (line.c, and the tracker's and the line drawings' passes into a
 * sparse depth buffer) steps its minor coordinate and its depth.
 *   0 (default except on x86-64): a branch each, taken when the error term passes the major
 *     length. Right for Cortex-M, where a branch costs a cycle or two and the select's masks cost
 *     more instructions.
 *   1 (default on x86-64): masks of all ones or zero, no branch: a line's steps follow its slope,
 *     which a deep desktop pipeline cannot predict. On the benchmark machine (gcc 12 -O2, the
 *     tracker's filter, 300 particles at 320x180) 14 % more instructions, half the mispredicted
 *     branches, and about 0.8 times the branches' time a frame, side by side (tests/bench/RESULTS.md,
 *     "Line walk: branches or masks", tests/bench/line_select.sh).
 * Both walk the same pixels at the same depths. */
#ifndef MC_LINE_SELECT
#if defined(__x86_64__) || defined(_M_X64)
#define MC_LINE_SELECT 1
#else
#define MC_LINE_SELECT 0
#endif
#endif
#if MC_LINE_SELECT != 0 && MC_LINE_SELECT != 1
#error "MC_LINE_SELECT must be 0 (branches) or 1 (masks)"
#endif

/* MC_MESH_SELECT: how the line drawings' passes over every edge and every face (mesh_lines.c) and
 * the rasterizer's triangle setup (raster.h, raster.c) take the tests whose outcome is a coin toss:
 * whether a face is front-facing, whether a face a pixel or two across covers a pixel centre and an
 * entry, which corner is the least or greatest.
 *   0 (default except on x86-64): a branch each. Right for Cortex-M, where a branch costs a cycle or
 *     two and the values cost instructions.
 *   1 (default on x86-64): taken as values, and only a rare answer branches (a line to draw, a face
 *     that hides an entry); the faces the edge pass visits and the front faces of the face pass are
 *     taken 32 at a time from their facing bits, and the edge pass is compiled once more for the
 *     full level (no stored opposite there needs a walk); the silhouette search's steps are inlined
 *     into its walks (silhouette.c), and the sparse way's face pass is a function of its own, so
 *     that a profile tells it apart (mesh_lines.c face_pass). On the benchmark machine (gcc 12 -O2,
 *     bunny00's lines at 320x240) about 5 % fewer instructions, a third of the mispredicted branches
 *     (cachegrind --branch-sim=yes, --frames 20) and about 0.77 times the branches' time a frame,
 *     side by side: tests/bench/mesh_frames.c built as tests/bench/mesh.sh builds it, once more with
 *     -DMC_MESH_SELECT=0, each run with --style lines --time 100, alternately.
 * Both draw the same pixels. */
#ifndef MC_MESH_SELECT
#if defined(__x86_64__) || defined(_M_X64)
#define MC_MESH_SELECT 1
#else
#define MC_MESH_SELECT 0
#endif
#endif
#if MC_MESH_SELECT != 0 && MC_MESH_SELECT != 1
#error "MC_MESH_SELECT must be 0 (branches) or 1 (values)"
#endif

/* MC_FLAT_SQUARES: how the point renderer walks the leaves of orthographic 2x2 squares (footprints
 * of two pixels: bunny00 at 640x480 and depth 8) wholly on screen.
 *   0 (default except on x86-64): each level d-1 node's leaves in their own loop. Right for
 *     firmware: the other way takes 1 KB more stack (gen/runtime_costs.hpp), which a board with
 *     64 KiB of RAM cannot spare, and its 64-bit masks cost a Cortex-M more instructions.
 *   1 (default on x86-64): a level d-2 node's up to 64 leaves as one 64-bit mask over leaf vectors
 *     summed once a frame, drawn in one loop: a leaf costs its square and a bit scan, and the
 *     loop's end, which a desktop pipeline mispredicts, comes once per level d-2 node instead of
 *     once per level d-1 node. On the benchmark machine (gcc 12 -O2, bunny00 at depth 8 and 640x480)
 *     0.86 times the instructions of a frame (tests/bench/flat_squares.sh, make bench-squares:
 *     RESULTS.md, "Squares"); its CPU time side by side has come out 0.94 to 1.27 times the loop's
 *     over four runs, as this machine's frame times jump between two levels (about 0.95 and 1.23 ms
 *     for either build) from one run of the program to the next.
 * Both draw the same pixels in the same order. */
#ifndef MC_FLAT_SQUARES
#if defined(__x86_64__) || defined(_M_X64)
#define MC_FLAT_SQUARES 1
#else
#define MC_FLAT_SQUARES 0
#endif
#endif
#if MC_FLAT_SQUARES != 0 && MC_FLAT_SQUARES != 1
#error "MC_FLAT_SQUARES must be 0 (a loop per level d-1 node) or 1 (per level d-2 node)"
#endif

/* MC_SPLAT_DEFAULT_MODE: the leaf footprint of octree renders whose splat is MC_SPLAT_DEFAULT
 * (octree_render.h):
 *   1 (MC_SPLAT_PIXEL): one pixel per leaf, the source paper's;
 *   2 (MC_SPLAT_ZOOM, default): a square that grows with the leaf's size on screen. Chosen by
 *     measurement: at zoom 2 it raises PSNR against the reference by several dB over one-pixel
 *     splats, finished or not, and at zoom <= 1 (leaves under a pixel) it draws the same pixels on
 *     the same code path (tests/bench/RESULTS.md, "Hole filling and splats").
 * MC_SPLAT_MAX: the largest footprint side in pixels (bounds the work per leaf at MC_SPLAT_MAX^2). */
#ifndef MC_SPLAT_DEFAULT_MODE
#define MC_SPLAT_DEFAULT_MODE 2
#endif
#if MC_SPLAT_DEFAULT_MODE != 1 && MC_SPLAT_DEFAULT_MODE != 2
#error "MC_SPLAT_DEFAULT_MODE must be 1 (one pixel) or 2 (grows with zoom)"
#endif
#ifndef MC_SPLAT_MAX
#define MC_SPLAT_MAX 16
#endif
#if MC_SPLAT_MAX < 1 || MC_SPLAT_MAX > 64
#error "MC_SPLAT_MAX must be in 1..64"
#endif

/* MC_LINEAR_ERROR: perspective projection, in 1/256 pixel. The renderer projects the centre of each
 * node three levels above the drawn one exactly (one division) and its leaves through the
 * projection's first-order expansion about that centre (additions only, like orthographic views),
 * where a bound computed per node shows the expansion puts every leaf within MC_LINEAR_ERROR / 256
 * pixel of its exact projection; where it does not (nodes near the eye, or near the near plane) it
 * tries each child, then divides per leaf. 16 (default): 1/16 pixel, below what a pixel grid shows
 * (tests/render and tests/stress measure it against the reference renderer, runtime/ref). 0: a division per leaf, the
 * exact projection everywhere. */
#ifndef MC_LINEAR_ERROR
#define MC_LINEAR_ERROR 16
#endif
#if MC_LINEAR_ERROR < 0 || MC_LINEAR_ERROR > 256
#error "MC_LINEAR_ERROR must be in 0..256 (1/256 pixel; 0: exact perspective per leaf)"
#endif

/* MC_FILL_REACH: how far (pixels) the scanline hole filler (finish.h, MC_FILL_SCANLINE) looks along
 * a row, a column and the two diagonals for a drawn pixel: holes up to MC_FILL_REACH pixels across
 * are closed. 1 closes only what the four-neighbour criterion sees; 3 (default) closes the holes of
 * rotated views at zoom up to 2 without joining parts of the model that are really apart. */
#ifndef MC_FILL_REACH
#define MC_FILL_REACH 3
#endif
#if MC_FILL_REACH < 1 || MC_FILL_REACH > 16
#error "MC_FILL_REACH must be in 1..16"
#endif

/* MC_FILL_DEFAULT_MODE: what mc_finish(t, MC_FILL_DEFAULT) does: 0 none, 1 one-pixel holes (the
 * four-neighbour fill), 2 (default) the source paper's scanline neighbourhood criterion (finish.h). */
#ifndef MC_FILL_DEFAULT_MODE
#define MC_FILL_DEFAULT_MODE 2
#endif
#if MC_FILL_DEFAULT_MODE < 0 || MC_FILL_DEFAULT_MODE > 2
#error "MC_FILL_DEFAULT_MODE must be 0, 1 or 2"
#endif

/* MC_ASR_CHECK: the runtime takes a right shift of a negative signed number as a floor division by
 * a power of two (an arithmetic shift: fixed.h mc_fix_floor, raster.h mc_raster_floor16, the
 * projection's rounding), which C99 leaves to the implementation and every compiler modelc targets
 * does (gcc, clang, arm-none-eabi-gcc). Not a setting: a compiler that shifts otherwise stops the
 * build here, naming it. */
typedef char MC_ASR_CHECK_right_shift_of_a_negative_number_must_be_arithmetic
    [(-7 >> 1) == -4 && (-(1LL << 40) >> 39) == -2 ? 1 : -1];

/* MC_PLOT_HOOK(fx, fy, color_ptr): called for every point that lands on screen, before the depth
 * test, with its screen position in Q MC_FRAC_BITS pixels (int32; pixels in MC_POS_HEADER's type
 * when that is set) and a pointer to its palette index (which identifies the leaf). Empty by default; tests define it
 * to compare each point with the reference renderer (runtime/ref, host-only). */
#ifndef MC_PLOT_HOOK
#define MC_PLOT_HOOK(fx, fy, color_ptr) ((void)0)
#endif

#endif
