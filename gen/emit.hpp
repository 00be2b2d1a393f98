// Writing a baked model: chunked C arrays, descriptor, app binding, header and budget.json, through
// the templates in templates/, into a directory that appears whole or not at all.
#pragma once
#include <string>
#include "octree.hpp"

namespace mc {

// Budgets to meet; 0 = none.
struct Limits {
    size_t flash = 0, ram = 0, stack = 0;
};

struct EmitOptions {
    std::string name;          // C identifier
    std::string source;        // input file name, recorded in comments and budget.json
    std::string out_dir;       // parent directory: writes out_dir/name/
    size_t chunk_bytes = 65536;
    size_t file_bytes = 262144;
    int screen_w = 640, screen_h = 480;
    bool lib = false;          // --emit lib: no NAME_app.c (no frame buffers, no mc_app_model)
    char up = 'y';             // the file's axis shown as up (--up): recorded in the model descriptor
    int leaf_switch = 1;       // the MC_LEAF_SWITCH the runtime is built with, for its code size
    Limits limits;             // recorded in budget.json (checked by the caller)
    std::string fit_note;      // what --fit chose, recorded in budget.json
    std::vector<std::pair<std::string, std::string>> budget_extra;  // more budget.json entries: key, JSON text
};

// What a bake costs a 32-bit firmware image, computed before anything is written (see
// runtime_costs.hpp for the runtime's constants and where they come from).
struct Budget {
    size_t masks = 0, colors = 0, palette = 0;   // bytes of model data
    size_t descriptors = 0;                      // chunk lists, levels, octree, model, name (32-bit layout)
    size_t code = 0;                             // runtime modules + libgcc helpers
    size_t flash() const { return masks + colors + palette + descriptors + code; }
    size_t data() const { return masks + colors + palette; }
    size_t color_buffer = 0, depth_buffer = 0, runtime_ram = 0;
    size_t ram() const { return color_buffer + depth_buffer + runtime_ram; }
    size_t stack = 0;                            // bound for mc_octree_render at the model's depth
};

Budget budget_of(const Octree &tree, const EmitOptions &opt);

// "" when b is within limits, else "flash 301234 bytes > 262144 (by 39090); ram ..." naming each
// item over budget.
std::string over_budget(const Budget &b, const Limits &limits);

// The templates, compiled in from templates/*.mustache (build/gen/templates.cpp).
const std::string &template_text(const std::string &name);

// Splits n bytes into chunks of at most limit bytes. With groups (sizes of consecutive runs that
// must stay together, each <= limit), chunks end only between groups. Returns chunk sizes.
std::vector<size_t> split_chunks(size_t n, size_t limit, const std::vector<uint8_t> *groups);

// Writes everything to out_dir/name/ via a temporary directory renamed on success.
// Returns the budget as JSON text (also written as budget.json).
std::string emit_model(const Octree &tree, const Voxels &vox, const EmitOptions &opt);

}  // namespace mc
