// Budgets: what a bake costs a 32-bit firmware image, and the limits it must meet.
//
// Promise: every cost rule is written here once: the runtime's code (its modules and libgcc
// helpers), the descriptors' 32-bit layout, the frame buffers (one colour byte and a 16-bit depth
// per pixel), the runtime's static RAM and mc_octree_render's stack bound. The runtime's measured constants
// (code sizes, stack frames, descriptor sizes) come from runtime_costs.hpp; the sizes of the model's
// own arrays and chunk lists come from emit's layout (emit.hpp budget_of), which alone decides them.
#pragma once
#include <cstddef>
#include <stdexcept>
#include <string>
#include "runtime_costs.hpp"

namespace mc {

// Budgets to meet; 0 = none.
struct Limits {
    size_t flash = 0, ram = 0, stack = 0;
};

// A budget size: bytes, or with K/KB/KiB (1024) or M/MB/MiB (1048576). Throws std::invalid_argument
// with the whole message ("OPTION TEXT: ...") on anything else or 0.
size_t parse_size(const std::string &option, const std::string &text);

struct Budget {
    size_t masks = 0, colors = 0, palette = 0;   // bytes of model data
    size_t cones = 0;                            // bytes of the octree's normal cones (0: none)
    size_t pmesh = 0;                            // bytes of the progressive mesh's arrays (0: no mesh part)
    size_t edges = 0;                            // bytes of the edge model's arrays (0: no edge part)
    size_t descriptors = 0;                      // chunk lists, levels, octree, pmesh, model, name (32-bit layout)
    size_t code = 0;                             // runtime modules + libgcc helpers
    size_t flash() const { return data() + descriptors + code; }
    size_t data() const { return masks + colors + palette + cones + pmesh + edges; }
    size_t color_buffer = 0, depth_buffer = 0, runtime_ram = 0;
    size_t pmesh_lod = 0;                        // the mesh's level-of-detail state (its ancestor map)
    size_t pmesh_facing = 0;                     // the line drawings' memory (mesh_lines.h MC_MESH_LINES_BYTES)
    size_t pmesh_cache = 0;                      // the vertex projection cache (mesh_render.h)
    size_t pmesh_sdepth = 0;                     // the lines style's sparse depth buffer bits (sdepth.h)
    size_t pmesh_neighbours = 0;                 // the level's neighbour table (--mesh-neighbours; pmesh.h)
    size_t track = 0;                            // the tracker's memory beside the frame buffers (TrackRam)
    size_t ram() const {
        return color_buffer + depth_buffer + runtime_ram + pmesh_lod + pmesh_facing + pmesh_cache + pmesh_sdepth +
               pmesh_neighbours + track;
    }
    size_t frame_buffers() const { return color_buffer + depth_buffer; }
    size_t stack = 0;                            // bound for mc_octree_render at the model's depth, or a tracker's frame
};

// What a bake emits, as the budget counts it.
struct BakeSize {
    int depth = 0;
    size_t masks = 0, colors = 0, palette = 0;   // bytes of the model's arrays
    size_t cones = 0;                            // and of its normal cones
    size_t chunk_entries = 0;                    // entries of every chunk list, sentinels included
    size_t name_bytes = 0;                       // the model's name as a C string, NUL included
    int screen_w = 0, screen_h = 0;              // the frame the buffers are sized for
    int leaf_switch = 1;                         // the MC_LEAF_SWITCH the runtime is built with
    size_t pmesh = 0, pmesh_lod = 0;             // the mesh part: its arrays, its state's RAM (0: none)
    size_t pmesh_facing = 0;                     // and its line drawings' facing bits
    size_t pmesh_cache = 0;                      // and its vertex projection cache
    size_t pmesh_sdepth = 0;                     // and the bits of its lines style's sparse depth buffer
    size_t pmesh_neighbours = 0;                 // and its neighbour table (0: none)
};

Budget budget_of(const BakeSize &s);

// The tracker's memory for an edge model (app.h's edge fields, NAME_app.c's static arrays) beside
// the frame buffers, which hold the sparse depth buffer's depths and colours: a w x h camera frame
// and its edge masks, the edge detector's scratch rows, the sparse depth buffer's bit vectors (in
// use and matched), the vertex cache and two arrays of particles.
struct TrackRam {
    size_t frame = 0, masks = 0, scratch = 0, sdepth = 0, matched = 0, cache = 0, particles = 0;
    size_t total() const { return frame + masks + scratch + sdepth + matched + cache + particles; }
};
TrackRam track_ram(int w, int h, size_t vertices, size_t particles);

// What an edge-model bake (--as edges) emits, as the budget counts it.
struct EdgeBakeSize {
    size_t data = 0;                             // bytes of its arrays
    size_t chunk_entries = 0, name_bytes = 0;
    size_t vertices = 0, particles = 0;
    int screen_w = 0, screen_h = 0;
};
Budget budget_of(const EdgeBakeSize &s);

// A tracker's code: its own modules (kTrackModules), those it shares with the renderers
// (kTrackShared) and the libgcc division helpers.
size_t track_code_bytes();

// One runtime module's code, built with this MC_LEAF_SWITCH.
inline size_t module_code_bytes(const rt::ModuleCode &m, int leaf_switch) { return leaf_switch ? m.bytes : m.bytes_loop; }

// The runtime's code: every module it links plus the libgcc division helpers (and the mesh part's
// modules when the bake has one).
size_t runtime_code_bytes(int leaf_switch, bool pmesh = false);

// The frame buffers of a w x h screen: one palette-index byte and one 16-bit depth per pixel.
size_t color_buffer_bytes(int w, int h);
size_t depth_buffer_bytes(int w, int h);

// What --ram-budget checks for a w x h screen: its buffers and the runtime's static state.
size_t ram_bytes(int w, int h);

// mc_octree_render's stack bound drawing an octree of this depth.
size_t stack_bytes(int depth);

// "" when b is within limits, else "flash 301234 bytes > 262144 (by 39090); ram ..." naming each
// item over budget.
std::string over_budget(const Budget &b, const Limits &limits);

// A bake over its budget: what() is the whole error line (without "modelc: ").
struct BudgetError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

}  // namespace mc
