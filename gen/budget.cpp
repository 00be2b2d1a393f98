// Budgets: see budget.hpp.
#include "budget.hpp"

#include <regex>
#include <stdexcept>

#include "modelc/imgedge.h"   // MC_IMGEDGE_SCRATCH_WORDS
#include "modelc/sdepth.h"    // MC_SDEPTH_WORDS, MC_SDEPTH_MATCHED_WORDS

namespace mc {

size_t parse_size(const std::string &option, const std::string &text) {
    std::smatch m;
    if (!std::regex_match(text, m, std::regex("([0-9]{1,12})\\s*(|[kK]|[kK][bB]|[kK]i[bB]|M|MB|MiB)")))
        throw std::invalid_argument(option + " " + text + ": expected a size in bytes, e.g. 262144, 256K, 256KiB, 1M");
    size_t n = std::stoull(m[1]);
    std::string unit = m[2];
    if (!unit.empty()) n *= (unit[0] == 'M') ? 1048576 : 1024;
    if (n == 0) throw std::invalid_argument(option + " " + text + ": a budget must be more than 0 bytes");
    return n;
}

size_t runtime_code_bytes(int leaf_switch, bool pmesh) {
    size_t code = rt::kLibgccDivision;
    for (const auto &m : rt::kModules) code += module_code_bytes(m, leaf_switch);
    if (pmesh)
        for (const auto &m : rt::kMeshModules) code += module_code_bytes(m, leaf_switch);
    return code;
}

size_t color_buffer_bytes(int w, int h) { return static_cast<size_t>(w) * static_cast<size_t>(h); }
size_t depth_buffer_bytes(int w, int h) { return 2 * color_buffer_bytes(w, h); }
size_t ram_bytes(int w, int h) { return color_buffer_bytes(w, h) + depth_buffer_bytes(w, h) + rt::kRuntimeStaticRam; }

size_t stack_bytes(int depth) { return rt::stack_bound(depth); }

// The descriptors in a 32-bit image (octree.h, model.h): the chunk lists, one level record per level,
// the octree and model descriptors and the name string.
static size_t descriptor_bytes(const BakeSize &s) {
    return s.chunk_entries * rt::kChunkBytes + static_cast<size_t>(s.depth + 1) * rt::kLevelBytes +
           rt::kOctreeBytes + (s.pmesh ? rt::kPmeshBytes : 0) + rt::kModelBytes + s.name_bytes;
}

Budget budget_of(const BakeSize &s) {
    Budget b;
    b.masks = s.masks;
    b.colors = s.colors;
    b.cones = s.cones;
    b.palette = s.palette;
    b.descriptors = descriptor_bytes(s);
    b.pmesh = s.pmesh;
    b.pmesh_lod = s.pmesh_lod;
    b.pmesh_facing = s.pmesh_facing;
    b.pmesh_cache = s.pmesh_cache;
    b.pmesh_sdepth = s.pmesh_sdepth;
    b.pmesh_neighbours = s.pmesh_neighbours;
    b.code = runtime_code_bytes(s.leaf_switch, s.pmesh > 0);
    b.color_buffer = color_buffer_bytes(s.screen_w, s.screen_h);
    b.depth_buffer = depth_buffer_bytes(s.screen_w, s.screen_h);
    b.runtime_ram = rt::kRuntimeStaticRam;
    b.stack = stack_bytes(s.depth);
    return b;
}

size_t track_code_bytes() {
    size_t code = rt::kLibgccDivision;
    for (const auto &m : rt::kTrackModules) code += m.bytes;
    for (const char *name : rt::kTrackShared) {
        size_t found = 0;
        for (const auto &m : rt::kModules) found += std::string(m.name) == name ? m.bytes : 0;
        for (const auto &m : rt::kMeshModules) found += std::string(m.name) == name ? m.bytes : 0;
        if (!found) throw std::logic_error(std::string("runtime_costs.hpp has no module ") + name);
        code += found;
    }
    return code;
}

TrackRam track_ram(int w, int h, size_t vertices, size_t particles) {
    TrackRam r;
    r.frame = color_buffer_bytes(w, h);
    r.masks = color_buffer_bytes(w, h);
    r.scratch = 4u * MC_IMGEDGE_SCRATCH_WORDS(w);
    r.sdepth = 4u * MC_SDEPTH_WORDS(w, h);
    r.matched = 4u * MC_SDEPTH_MATCHED_WORDS(w, h);
    r.cache = vertices * rt::kXvertexBytes;
    r.particles = 2 * particles * rt::kParticleBytes;
    return r;
}

Budget budget_of(const EdgeBakeSize &s) {
    Budget b;
    b.edges = s.data;
    b.descriptors = s.chunk_entries * rt::kChunkBytes + rt::kEdgesBytes + rt::kModelBytes + s.name_bytes;
    b.code = track_code_bytes();
    b.color_buffer = color_buffer_bytes(s.screen_w, s.screen_h);
    b.depth_buffer = depth_buffer_bytes(s.screen_w, s.screen_h);
    b.runtime_ram = rt::kRuntimeStaticRam;
    b.track = track_ram(s.screen_w, s.screen_h, s.vertices, s.particles).total();
    b.stack = rt::track_stack_bound();
    return b;
}

std::string over_budget(const Budget &b, const Limits &limits) {
    std::string s;
    auto item = [&](const char *what, size_t have, size_t limit) {
        if (!limit || have <= limit) return;
        if (!s.empty()) s += "; ";
        s += std::string(what) + " " + std::to_string(have) + " bytes > " + std::to_string(limit) + " (by " +
             std::to_string(have - limit) + ")";
    };
    item("flash", b.flash(), limits.flash);
    item("ram", b.ram(), limits.ram);
    item("stack", b.stack, limits.stack);
    return s;
}

}  // namespace mc
