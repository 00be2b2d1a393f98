// What every kind of bake writes the same way: the chunked data files, the model descriptor's
// normalization, and the directory that appears whole or not at all. Shared by emit.cpp (the
// octree and the progressive mesh) and emit_edges.cpp (the edge model); not a public interface.
#pragma once
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <mstch/mstch.hpp>
#include <nlohmann/json.hpp>

#include "emit.hpp"
#include "normalize.hpp"

namespace mc {

// One data array of a bake: a chunk of some part's bytes.
struct Array {
    std::string symbol, what;
    const uint8_t *data;
    size_t size;
    bool mesh = false;   // declared in NAME_pmesh.c, not NAME_octree.c
};

// File name and contents, in the order they are written.
using Files = std::vector<std::pair<std::string, std::string>>;

std::string upper(std::string s);

// Initialiser lines, 24 decimal bytes a line.
mstch::array byte_lines(const uint8_t *p, size_t n);

// The template data every file has: name, NAME, source.
mstch::map common(const EmitOptions &opt);

// The model descriptor's template data (model.c.mustache) but its part pointers: the grid cube
// (normalize.hpp) in file coordinates, and the up axis.
mstch::map model_data(const GridCube &cube, const EmitOptions &opt);

// A header template (NAME.h of some kind of bake) with the placement partial (placement.h.mustache).
std::string render_header(const std::string &tmpl, const mstch::map &ctx);

// Arrays in order into data files, a new file once the current one holds file_bytes.
std::vector<std::vector<const Array *>> data_files(const std::vector<Array> &arrays, size_t file_bytes);

// NAME_data_N.c for each data file; records which file holds each array in chunk_files (budget.json).
Files data_file_texts(const EmitOptions &opt, const std::vector<std::vector<const Array *>> &files,
                      nlohmann::json &chunk_files);

// budget.json's "budgets": each limit asked for (--flash-budget, --ram-budget, --stack-budget) and
// what the bake uses of it; nothing when none was asked for.
void add_limits(nlohmann::json &budget, const Limits &limits, const Budget &bud);

// Writes every file into parent/name/ as a whole: into a temporary sibling directory first, then
// swapped in, so that a failure leaves the previous output (or none), never a part.
void write_directory(const std::filesystem::path &parent, const std::string &name, const Files &out);

}  // namespace mc
