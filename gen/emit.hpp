// Writing a baked model: chunked C arrays, descriptor, app binding, header and budget.json, through
// the templates in templates/, into a directory that appears whole or not at all.
//
// Promise: emit decides the layout of what it writes (which arrays, their chunks, which file holds
// each) and nothing else; what the bake costs is budget.hpp's, what it contains the octree's.
#pragma once
#include <string>
#include <utility>
#include <vector>
#include "budget.hpp"
#include "edge_model.hpp"
#include "normalize.hpp"
#include "octree.hpp"
#include "pmesh.hpp"

namespace mc {

struct EmitOptions {
    std::string name;          // C identifier
    std::string source;        // input file name, recorded in comments and budget.json
    std::string out_dir;       // parent directory: writes out_dir/name/
    size_t chunk_bytes = 65536;
    size_t file_bytes = 262144;
    int screen_w = 640, screen_h = 480;
    bool lib = false;          // --emit lib: no NAME_app.c (no frame buffers, no mc_app_model)
    bool stream = false;       // --emit stream: also NAME.mcs, the bake as one stream (stream.h)
    bool stream_packed = false;   // --stream-splits packed: the mesh's splits packed (version 3)
    size_t stream_bytes = 0;   // its receive buffer, set by emit_model: NAME.h's MC_NAME_STREAM_BYTES and the app's
    UpAxis up = UpAxis::y;     // the file's axis shown as up (--up): recorded in the model descriptor
    int leaf_switch = 1;       // the MC_LEAF_SWITCH the runtime is built with, for its code size
    Limits limits;             // recorded in budget.json (checked by the caller)
    std::string fit_note;      // what --fit chose, recorded in budget.json
    std::vector<std::pair<std::string, std::string>> budget_extra;  // more budget.json entries: key, JSON text
    const PMesh *pmesh = nullptr;   // the mesh part (--as both), or none
    bool mesh_neighbours = false;   // --mesh-neighbours: the app binding holds a neighbour table (pmesh.h)
    size_t mesh_groups = 0;    // --mesh-groups: faces a face group (pmesh.h groups), a power of two; 0: none
    size_t particles = 300;    // --as edges: particles the app binding's static arrays hold
};

// The bake as a stream (runtime/include/modelc/stream.h): version 1 for the octree alone, version 2
// with the mesh part after it. Its bytes; the bytes a reader needs to draw depth 1, 2, ..., D (the
// end of each level's record); with a mesh, where each of its records that raises the drawable level
// ends and that level (the base's, then each batch of splits'), and where the adjacency ends (the
// line styles then draw); and the receive buffer the reader needs (the stream, then the mesh's
// arrays: MC_NAME_STREAM_BYTES).
struct Stream {
    std::string bytes;
    std::vector<size_t> drawable_at;
    std::vector<std::pair<size_t, size_t>> mesh_levels;   // (end of record, mesh level)
    size_t lines_at = 0;
    size_t buffer = 0;
};
struct PMesh;
Stream bake_stream(const Octree &tree, const PMesh *pmesh, bool packed = false);

// The mesh part's field widths (pmesh.h), one rule for the baked arrays (emit.cpp) and the stream's
// mesh records (emit_stream.cpp): vertex indices 2 bytes up to 65,535 vertices, else 4; half-edges
// (4 f + k, all ones for none) 2 bytes while 4 F + 3 stays below 65,535, else 4.
struct PmWidths {
    unsigned index_bytes, half_bytes;
};
PmWidths pm_widths(uint64_t vertices, uint64_t faces);
// The bytes of the arrays the shaded style reads (positions, tree, splits, corners, face bits) for V
// vertices, V0 of them in the base, and F faces: what a stream's receive buffer holds after the
// stream (stream.h MC_STREAM_MESH_BYTES).
uint64_t pm_draw_bytes(uint64_t V, uint64_t V0, uint64_t F);
// What a packed stream's reader needs after them to decode (stream.h MC_STREAM_PACKED_BYTES, here in 64
// bits so that the caller can see a buffer past 4 GiB).
constexpr uint64_t pm_packed_bytes(uint64_t V, uint64_t F) { return 24 * F + 12 * V + 4; }

// The budget of the bake emit_model would write (the arrays and chunk lists are sized here, where
// they are laid out; the cost rules are budget.hpp's).
Budget budget_of(const Octree &tree, const EmitOptions &opt);

// The templates, compiled in from templates/*.mustache (build/gen/templates.cpp).
const std::string &template_text(const std::string &name);

// Splits n bytes into chunks of at most limit bytes. With groups (sizes of consecutive runs that
// must stay together, each <= limit), chunks end only between groups. Returns chunk sizes.
std::vector<size_t> split_chunks(size_t n, size_t limit, const std::vector<uint8_t> *groups);

// Writes everything to out_dir/name/ via a temporary directory renamed on success.
// Returns the budget as JSON text (also written as budget.json).
std::string emit_model(const Octree &tree, const Voxels &vox, const EmitOptions &opt);

// An edge-model bake (--as edges): the budget of what emit_edges would write, and the writing:
// NAME.h, NAME_data_N.c, NAME_edges.c, NAME_model.c (cube: the model's grid cube, for its
// normalization), NAME_app.c (not with --emit lib) and budget.json, all at once as emit_model does.
Budget budget_of(const EdgeModel &e, const EmitOptions &opt);
std::string emit_edges(const EdgeModel &e, const GridCube &cube, const EmitOptions &opt);

}  // namespace mc
