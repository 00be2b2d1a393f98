// Emission: see emit.hpp.
#include "emit.hpp"
#include "cones.hpp"
#include "emit_files.hpp"
#include "runtime_costs.hpp"
#include "modelc/mesh_lines.h"   // MC_MESH_LINES_BYTES: the line drawings' memory
#include "modelc/mesh_face.h"   // the face bits: shades and crease bits stored for the faces
#include "modelc/sdepth.h"  // MC_SDEPTH_WORDS: the lines style's sparse depth buffer
#include "modelc/xform.h"   // mc_xvertex: the vertex cache's entries (16 bytes on every target)
#include "modelc/stream.h"  // MC_STREAM_PACKED_BYTES, which pm_packed_bytes restates in 64 bits

#include <mstch/mstch.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace mc {

std::vector<size_t> split_chunks(size_t n, size_t limit, const std::vector<uint8_t> *groups) {
    std::vector<size_t> sizes;
    if (!groups) {
        for (size_t at = 0; at < n; at += limit) sizes.push_back(std::min(limit, n - at));
        return sizes;
    }
    size_t cur = 0;
    for (uint8_t g : *groups) {
        if (cur + g > limit) sizes.push_back(cur), cur = 0;
        cur += g;
    }
    if (cur) sizes.push_back(cur);
    return sizes;
}

PmWidths pm_widths(uint64_t vertices, uint64_t faces) {
    return {vertices <= 65535 ? 2u : 4u, 4 * faces + 3 < 65535 ? 2u : 4u};
}

static_assert(pm_packed_bytes(37706, 75408) == MC_STREAM_PACKED_BYTES(37706, 75408),
              "pm_packed_bytes is stream.h's MC_STREAM_PACKED_BYTES");

uint64_t pm_draw_bytes(uint64_t V, uint64_t V0, uint64_t F) {
    const uint64_t ib = pm_widths(V, F).index_bytes;   // the record sizes of pmesh_arrays below
    // and the face bits the reader works out, and the splits' face-count bits
    return 6 * V + ib * V + ib * (V - V0) + 3 * ib * F + F + (V - V0 + 7) / 8;
}

namespace {

// Every array a bake emits and the chunk lists that point at them.
struct Plan {
    std::vector<Array> arrays;
    mstch::array lists, levels;
    nlohmann::json budget_arrays = nlohmann::json::object();
    std::vector<uint8_t> palette;   // RGB triplets
    size_t mask_bytes = 0, color_bytes = 0, cone_bytes = 0, chunk_entries = 0;
    // the mesh part (pmesh.h): its arrays' bytes, chunk lists and layout
    std::vector<std::vector<uint8_t>> pm_bytes;   // kPmArrays
    std::vector<uint8_t> pm_palette;              // RGB triplets
    mstch::array pm_lists;
    size_t pm_data = 0;                           // every array of the mesh part
    size_t pm_line_data = 0;                      // of which the line drawings' (opposite, edges)
    size_t pm_face_data = 0;                      // and the face bits (shades, creases)
    size_t pm_group_data = 0;                     // and the face groups (--mesh-groups)
    unsigned index_bytes = 0, half_bytes = 0, record_shift = 0;
    size_t group_size = 0;                        // --mesh-groups (0: none)
    unsigned group_bytes = 0;
};

// The mesh part's chunked arrays, in mc_pmesh's order (pmesh.h; the template's field names), and the
// symbol of each one's chunk list.
const int kPmArrayCount = 10, kPmOpposite = 4, kPmEdgeOrder = 5, kPmFaceBits = 6, kPmSplitFaces = 7, kPmGroups = 8,
          kPmGroupFaces = 9;
const char *const kPmArrays[kPmArrayCount] = {"positions", "tree",      "splits",      "corners", "opposite",
                                               "edge_order", "face_bits", "split_faces", "groups",  "group_faces"};
std::string pm_list(const std::string &name, int k) { return "mc_" + name + "_pm_" + kPmArrays[k]; }
// Whether array k is baked: the face groups' two only with --mesh-groups (else null in mc_pmesh).
bool pm_baked(int k, size_t group_size) { return group_size || (k != kPmGroups && k != kPmGroupFaces); }

// The mesh part's arrays in pmesh.h's layout: little-endian records, index fields index_bytes wide;
// all but the split faces' bits, whose layout follows the chunks' record_shift (split_face_bits).
void pmesh_arrays(const PMesh &pm, Plan &p) {
    const PmWidths wd = pm_widths(pm.vertices(), pm.faces.size());
    const unsigned ib = wd.index_bytes;
    p.index_bytes = ib;
    p.half_bytes = wd.half_bytes;
    p.pm_bytes.assign(kPmArrayCount, {});
    auto put = [](std::vector<uint8_t> &b, uint32_t v, unsigned n) {
        for (unsigned i = 0; i < n; i++) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
    };
    for (const auto &q : pm.positions)
        for (uint16_t c : q) put(p.pm_bytes[0], c, 2);
    for (size_t v = 0; v < pm.vertices(); v++) put(p.pm_bytes[1], pm.size[v], ib);
    for (size_t s = 0; s < pm.split_vertex.size(); s++) put(p.pm_bytes[2], pm.split_vertex[s], ib);
    for (const auto &f : pm.faces)
        for (uint32_t c : f) put(p.pm_bytes[3], c, ib);
    for (const auto &f : pm.opposite)
        for (uint32_t h : f) put(p.pm_bytes[kPmOpposite], h, p.half_bytes);
    for (uint32_t h : pm.edge_order) put(p.pm_bytes[kPmEdgeOrder], h, p.half_bytes);
    // each face's shade and crease bits by the runtime's own code (mesh_face.h mc_mesh_face_bits, which
    // a stream's reader calls too) over the arrays just laid out, one chunk each
    const auto whole = [&](int k) { return mc_chunk{p.pm_bytes[k].data(), static_cast<uint32_t>(p.pm_bytes[k].size())}; };
    const mc_chunk positions = whole(0), corners = whole(3), opposite = whole(kPmOpposite);
    mc_pmesh view{};
    view.faces = static_cast<uint32_t>(pm.faces.size());
    view.index_bytes = static_cast<uint8_t>(ib);
    view.half_bytes = static_cast<uint8_t>(p.half_bytes);
    view.record_shift = 30;   // one chunk: far more records than any bake has
    view.crease_cos = pm.crease_cos;
    view.positions = &positions, view.corners = &corners, view.opposite = &opposite;
    p.pm_bytes[kPmFaceBits].resize(pm.faces.size());
    mc_mesh_face_bits(&view, p.pm_bytes[kPmFaceBits].data());
    for (const auto &c : pm.palette) p.pm_palette.insert(p.pm_palette.end(), c.begin(), c.end());
}

// The 16 bits of v spread to every third bit (bit i to bit 3 i: a Morton code of three coordinates).
uint64_t spread16(uint64_t v) {
    v &= 0xFFFF;
    v = (v | v << 32) & 0x001F00000000FFFFull;
    v = (v | v << 16) & 0x001F0000FF0000FFull;
    v = (v | v << 8) & 0x100F00F00F00F00Full;
    v = (v | v << 4) & 0x10C30C30C30C30C3ull;
    return (v | v << 2) & 0x1249249249249249ull;
}

// The face groups (pmesh.h groups, group_faces): the full mesh's faces in the Morton order of their
// centres (ties by index), size at a time; each group's box of its faces' corners. Groups lie in one
// chunk each: size divides 2^shift.
void face_groups(const PMesh &pm, size_t size, unsigned shift, Plan &p) {
    const size_t F = pm.faces.size();
    if (size > (size_t(1) << shift))
        throw std::runtime_error("--mesh-groups " + std::to_string(size) + ": at most " +
                                 std::to_string(size_t(1) << shift) + " faces a group with these --chunk-bytes");
    std::vector<uint64_t> key(F);
    std::vector<uint32_t> order(F);
    for (size_t f = 0; f < F; f++) {
        uint64_t m = 0;
        for (int a = 0; a < 3; a++) {
            const uint32_t sum = uint32_t(pm.positions[pm.faces[f][0]][a]) + pm.positions[pm.faces[f][1]][a] +
                                 pm.positions[pm.faces[f][2]][a];
            m |= spread16(sum / 3) << a;
        }
        key[f] = m, order[f] = static_cast<uint32_t>(f);
    }
    std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key[a] < key[b]; });
    p.group_bytes = F <= 65536 ? 2 : 3;
    auto &boxes = p.pm_bytes[kPmGroups], &faces = p.pm_bytes[kPmGroupFaces];
    for (size_t first = 0; first < F; first += size) {
        std::array<uint16_t, 3> lo{0xFFFF, 0xFFFF, 0xFFFF}, hi{0, 0, 0};
        for (size_t k = first; k < first + size && k < F; k++) {
            const uint32_t f = order[k];
            for (int i = 0; i < static_cast<int>(p.group_bytes); i++) faces.push_back(static_cast<uint8_t>(f >> (8 * i)));
            for (uint32_t c : pm.faces[f])
                for (int a = 0; a < 3; a++)
                    lo[a] = std::min(lo[a], pm.positions[c][a]), hi[a] = std::max(hi[a], pm.positions[c][a]);
        }
        for (const auto &q : {lo, hi})
            for (uint16_t c : q) boxes.push_back(static_cast<uint8_t>(c)), boxes.push_back(static_cast<uint8_t>(c >> 8));
    }
    p.group_size = size;
}

// The split faces' bits (pmesh.h split_faces): a chunk's 2^shift splits in (2^shift + 7) / 8 bytes.
std::vector<uint8_t> split_face_bits(const PMesh &pm, unsigned shift) {
    const size_t per = (size_t(1) << shift), chunk_bytes = (per + 7) / 8, S = pm.split_faces.size();
    std::vector<uint8_t> b((S + per - 1) / per * chunk_bytes, 0);
    for (size_t s = 0; s < S; s++) {
        const size_t i = s & (per - 1);
        if (pm.split_faces[s] == 2) b[s / per * chunk_bytes + i / 8] |= static_cast<uint8_t>(1u << (i & 7));
    }
    if (S % per) b.resize(S / per * chunk_bytes + (S % per + 7) / 8);   // the last chunk: its splits' bytes
    return b;
}

// A monochrome octree (one palette entry) stores no colours: every level's colour list is NULL and
// the renderer draws palette index 0 (octree.h).
Plan make_plan(const Octree &t, const EmitOptions &opt) {
    const int D = t.depth;
    const std::string &name = opt.name;
    const bool mono = t.palette.size() == 1;
    Plan p;
    // One chunk list per array, each chunk its own array, into lists: chunks of at most limit bytes,
    // ending only between groups when there are groups.
    auto add_list = [&](const std::vector<uint8_t> &bytes, size_t limit, const std::vector<uint8_t> *groups,
                        const std::string &list, const std::string &what, mstch::array &lists, bool mesh) {
        mstch::array chunks;
        size_t at = 0, i = 0;
        for (size_t size : split_chunks(bytes.size(), limit, groups)) {
            std::string sym = list + "_" + std::to_string(i++);
            p.arrays.push_back({sym, what + ", bytes " + std::to_string(at) + ".." + std::to_string(at + size - 1),
                                bytes.data() + at, size, mesh});
            chunks.push_back(mstch::map{{"symbol", sym}, {"size", std::to_string(size)}});
            p.budget_arrays[sym] = size;
            at += size;
        }
        p.chunk_entries += i + 1;   // the chunks and the {0, 0} sentinel
        lists.push_back(mstch::map{{"symbol", list}, {"chunks", chunks}});
        return list;
    };
    // the octree's: one list per level and kind
    auto add_stream = [&](const std::vector<uint8_t> &bytes, const std::vector<uint8_t> *groups,
                          const std::string &kind, int level, const std::string &what) {
        return add_list(bytes, opt.chunk_bytes, groups, "mc_" + name + "_" + kind + std::to_string(level),
                        what + " of level " + std::to_string(level), p.lists, false);
    };
    for (int l = 0; l <= D; l++) {
        std::string masks = "0", colors = "0";
        if (l < D)
            masks = add_stream(t.masks[l], l > 0 ? &t.siblings[l] : nullptr, "m", l, "child masks"),
            p.mask_bytes += t.masks[l].size();
        if (l > 0 && !mono)
            colors = add_stream(t.colors[l], &t.cousins[l], "c", l, "palette indices"),
            p.color_bytes += t.colors[l].size();
        std::string cones = "0";
        if (l < static_cast<int>(t.cones.size()) && !t.cones[l].empty()) {
            const std::vector<uint8_t> records(t.cones[l].size() / kConeBytes, kConeBytes);   // whole records a chunk
            cones = add_stream(t.cones[l], &records, "k", l, "normal cones");
            p.cone_bytes += t.cones[l].size();
        }
        p.levels.push_back(
            mstch::map{{"nodes", std::to_string(t.nodes(l))}, {"masks", masks}, {"colors", colors}, {"cones", cones}});
    }
    for (const auto &c : t.palette) p.palette.insert(p.palette.end(), c.begin(), c.end());
    p.budget_arrays["mc_" + name + "_palette"] = p.palette.size();
    if (opt.pmesh) {
        // every chunk of every array holds 2^record_shift whole records (the last fewer), the most
        // that fit --chunk-bytes for the largest record (three corners)
        pmesh_arrays(*opt.pmesh, p);
        const size_t largest = 3 * std::max(p.index_bytes, p.half_bytes);
        while ((size_t(2) << p.record_shift) * largest <= opt.chunk_bytes) p.record_shift++;
        p.pm_bytes[kPmSplitFaces] = split_face_bits(*opt.pmesh, p.record_shift);
        if (opt.mesh_groups) face_groups(*opt.pmesh, opt.mesh_groups, p.record_shift, p);
        const char *whats[kPmArrayCount] = {"vertex positions", "vertex subtree sizes", "split vertices",
                                            "face corners", "opposite half-edges", "edges, sharpest first",
                                            "face shades and crease bits", "split face counts", "face group boxes",
                                            "faces by group"};
        const size_t per = size_t(1) << p.record_shift;
        const size_t chunk[kPmArrayCount] = {6 * per, p.index_bytes * per, p.index_bytes * per, 3 * p.index_bytes * per,
                                             3 * p.half_bytes * per, p.half_bytes * per, per, (per + 7) / 8,
                                             12 * per, p.group_bytes * per};
        for (int k = 0; k < kPmArrayCount; k++) {
            if (!pm_baked(k, p.group_size)) continue;
            add_list(p.pm_bytes[k], chunk[k], nullptr, pm_list(name, k),
                     std::string("mesh ") + whats[k], p.pm_lists, true);
            p.pm_data += p.pm_bytes[k].size();
            if (k == kPmFaceBits) p.pm_face_data += p.pm_bytes[k].size();
            else if (k == kPmGroups || k == kPmGroupFaces) p.pm_group_data += p.pm_bytes[k].size();
            else if (k == kPmOpposite || k == kPmEdgeOrder) p.pm_line_data += p.pm_bytes[k].size();   // the line drawings'
        }
        p.budget_arrays["mc_" + name + "_pm_palette"] = p.pm_palette.size();
        p.pm_data += p.pm_palette.size();
    }
    return p;
}

Budget budget_of(const Octree &t, const EmitOptions &opt, const Plan &p) {
    BakeSize s;
    s.depth = t.depth;
    s.masks = p.mask_bytes;
    s.colors = p.color_bytes;
    s.cones = p.cone_bytes;
    s.palette = p.palette.size();
    s.chunk_entries = p.chunk_entries;
    s.name_bytes = opt.name.size() + 1;
    s.screen_w = opt.screen_w, s.screen_h = opt.screen_h;
    s.leaf_switch = opt.leaf_switch;
    if (opt.pmesh) {
        s.pmesh = p.pm_data;
        s.pmesh_lod = opt.pmesh->vertices() * p.index_bytes;
        s.pmesh_facing = MC_MESH_LINES_BYTES(opt.pmesh->faces.size());
        s.pmesh_cache = opt.pmesh->vertices() * sizeof(mc_xvertex);   // MC_MESH_CACHE_BYTES
        s.pmesh_sdepth = 4u * MC_SDEPTH_WORDS(opt.screen_w, opt.screen_h);
        if (opt.mesh_neighbours) s.pmesh_neighbours = MC_PMESH_NEIGHBOUR_BYTES(opt.pmesh->faces.size(), p.half_bytes);
    }
    return budget_of(s);
}

}  // namespace

Budget budget_of(const Octree &t, const EmitOptions &opt) { return budget_of(t, opt, make_plan(t, opt)); }

namespace {

// ---- template data -------------------------------------------------------------------------------
// Everything the templates are filled with, and the files they make (all but budget.json), rendered
// in memory: nothing touches the disk until all of it succeeded. chunk_files: which data file holds
// each array, for budget.json.
Files fill_templates(const Octree &t, const Voxels &vox, const EmitOptions &opt, const Plan &plan,
                     const Budget &bud, const std::vector<std::vector<const Array *>> &files,
                     nlohmann::json &chunk_files) {
    const int D = t.depth;
    const std::string &name = opt.name;
    const std::vector<Array> &arrays = plan.arrays;
    const std::vector<uint8_t> &palette = plan.palette;
    const size_t data_bytes = bud.data();
    const size_t points = t.nodes(D);
    const size_t workspace = bud.frame_buffers();

    Files out = data_file_texts(opt, files, chunk_files);
    mstch::map octree = common(opt);
    mstch::array decls;
    for (const Array &a : arrays)
        if (!a.mesh)   // the mesh's are NAME_pmesh.c's
            decls.push_back(mstch::map{{"symbol", a.symbol}, {"size", std::to_string(a.size)}});
    octree.emplace("arrays", decls);
    octree.emplace("lists", plan.lists);
    octree.emplace("levels", plan.levels);
    octree.emplace("level_count", std::to_string(D + 1));
    octree.emplace("depth", std::to_string(D));
    octree.emplace("palette_size", std::to_string(t.palette.size()));
    octree.emplace("palette_bytes", std::to_string(palette.size()));
    octree.emplace("palette_lines", byte_lines(palette.data(), palette.size()));
    out.emplace_back(name + "_octree.c", mstch::render(template_text("octree.c"), octree));
    mstch::map model = model_data(vox.cube(), opt);
    model.emplace("octree_ptr", "&mc_octree_" + name);
    model.emplace("edges_ptr", std::string("0"));
    model.emplace("pmesh_ptr", std::string(opt.pmesh ? "&mc_pmesh_" + name : "0"));
    out.emplace_back(name + "_model.c", mstch::render(template_text("model.c"), model));
    mstch::map pmesh_header;
    if (opt.pmesh) {
        const PMesh &pm = *opt.pmesh;
        mstch::map m = common(opt);
        mstch::array pdecls;
        for (const Array &a : arrays)
            if (a.mesh) pdecls.push_back(mstch::map{{"symbol", a.symbol}, {"size", std::to_string(a.size)}});
        pmesh_header = mstch::map{{"vertices", std::to_string(pm.vertices())},
                                  {"faces", std::to_string(pm.faces.size())},
                                  {"base_vertices", std::to_string(pm.base_vertices)},
                                  {"base_faces", std::to_string(pm.base_faces)},
                                  {"index_bits", std::to_string(8 * plan.index_bytes)},
                                  {"lod_bytes", std::to_string(bud.pmesh_lod)},
                                  {"facing_bytes", std::to_string(bud.pmesh_facing)},
                                  {"neighbour_bytes", std::to_string(bud.pmesh_neighbours)},
                                  {"neighbours", bud.pmesh_neighbours > 0}};
        for (const auto &[k, v] : pmesh_header) m.emplace(k, v);
        m.emplace("arrays", pdecls);
        m.emplace("lists", plan.pm_lists);
        m.emplace("index_bytes", std::to_string(plan.index_bytes));
        m.emplace("half_bytes", std::to_string(plan.half_bytes));
        m.emplace("edges", std::to_string(pm.edge_order.size()));
        m.emplace("crease_cos", std::to_string(pm.crease_cos));
        m.emplace("closed", std::string(pm.closed() ? "1" : "0"));
        m.emplace("record_shift", std::to_string(plan.record_shift));
        m.emplace("layout", std::to_string(MC_PMESH_LAYOUT));   // the arrays' layout: pmesh.h's, which this generator includes
        m.emplace("palette_size", std::to_string(pm.palette.size()));
        m.emplace("palette_bytes", std::to_string(plan.pm_palette.size()));
        m.emplace("palette_lines", byte_lines(plan.pm_palette.data(), plan.pm_palette.size()));
        for (int k = 0; k < kPmArrayCount; k++)
            m.emplace(std::string("list_") + kPmArrays[k], pm_baked(k, plan.group_size) ? pm_list(name, k) : std::string("0"));
        m.emplace("group_size", std::to_string(plan.group_size));
        m.emplace("group_bytes", std::to_string(plan.group_bytes));
        out.emplace_back(name + "_pmesh.c", mstch::render(template_text("pmesh.c"), m));
    }

    mstch::map header = common(opt);
    header.emplace("depth", std::to_string(D));
    header.emplace("points", std::to_string(points));
    header.emplace("palette_size", std::to_string(t.palette.size()));
    header.emplace("data_bytes", std::to_string(data_bytes));
    header.emplace("screen_w", std::to_string(opt.screen_w));
    header.emplace("screen_h", std::to_string(opt.screen_h));
    header.emplace("workspace_bytes", std::to_string(workspace));
    header.emplace("lib", opt.lib);
    header.emplace("mono", t.palette.size() == 1);
    if (opt.stream) header.emplace("stream", mstch::array{mstch::map{{"stream_bytes", std::to_string(opt.stream_bytes)}}});
    mstch::array symbols;
    for (const Array &a : arrays)
        symbols.push_back(mstch::map{{"symbol", a.symbol}, {"suffix", a.symbol.substr(4 + name.size())}});
    header.emplace("symbols", symbols);
    if (opt.pmesh) header.emplace("pmesh", mstch::array{pmesh_header});
    mstch::array parts{mstch::map{{"part", std::string("octree")}}};
    if (opt.pmesh) parts.push_back(mstch::map{{"part", std::string("pmesh")}});
    header.emplace("parts", parts);
    out.emplace_back(name + ".h", render_header("model.h", header));
    if (!opt.lib) out.emplace_back(name + "_app.c", mstch::render(template_text("app.c"), header));
    return out;
}
// ---- end of template data ------------------------------------------------------------------------

// budget.json: what the bake costs (budget.hpp's rules) and where each array went.
std::string budget_json(const Octree &t, const Voxels &vox, const EmitOptions &opt, const Plan &plan,
                        const Budget &bud, const nlohmann::json &chunk_files) {
    const int D = t.depth;
    const std::string &name = opt.name;
    const std::vector<uint8_t> &palette = plan.palette;
    const size_t mask_bytes = plan.mask_bytes, color_bytes = plan.color_bytes;
    const size_t data_bytes = bud.data();
    const size_t points = t.nodes(D);
    const size_t workspace = bud.frame_buffers();

    // The runtime modules this model needs (it links nothing else) and their estimated code.
    nlohmann::json modules = nlohmann::json::array(), runtime_code = nlohmann::json::object();
    for (const auto &m : rt::kModules) {
        modules.push_back(m.name);
        runtime_code[m.name] = module_code_bytes(m, opt.leaf_switch);
    }
    if (opt.pmesh)
        for (const auto &m : rt::kMeshModules) {
            modules.push_back(m.name);
            runtime_code[m.name] = module_code_bytes(m, opt.leaf_switch);
        }
    runtime_code["libgcc"] = rt::kLibgccDivision;
    runtime_code["leaf_switch"] = opt.leaf_switch;
    runtime_code["total"] = bud.code;
    nlohmann::json stack_frames = nlohmann::json::object();
    for (const auto &f : rt::kFrames) stack_frames[f.function] = f.bytes();
    stack_frames["walk_frames"] = rt::walk_frames(D);
    nlohmann::json per_level = nlohmann::json::array();
    for (int l = 0; l <= D; l++) per_level.push_back(t.nodes(l));
    nlohmann::json budget = {
        {"model", name},
        {"source", opt.source},
        {"kind", "point-octree"},
        {"depth", D},
        {"points", points},
        {"points_per_level", per_level},
        {"samples", vox.samples},
        {"palette_entries", t.palette.size()},
        {"chunk_bytes", opt.chunk_bytes},
        {"flash",
         {{"arrays", plan.budget_arrays},
          {"masks", mask_bytes},
          {"colors", color_bytes},
          {"cones", plan.cone_bytes},
          {"palette", palette.size()},
          {"total", data_bytes},
          {"descriptors", bud.descriptors},
          {"runtime_code", runtime_code},
          {"image", bud.flash()},
          {"note", "total: the model's data arrays and palette. image: what --flash-budget checks, total plus "
                   "descriptors (32-bit layout) plus runtime_code, an estimate of the runtime's text and rodata "
                   "for Cortex-M4 -O2 (constants in gen/runtime_costs.hpp)"}}},
        {"ram",
         {{"color_buffer", bud.color_buffer},
          {"depth_buffer", bud.depth_buffer},
          {"total", workspace},
          {"runtime_static", bud.runtime_ram},
          {"image", bud.ram()},
          {"note", std::string(opt.lib ? "--emit lib: the caller provides the buffers; sized here for --screen. "
                                       : "static buffers of NAME_app.c for --screen. ") +
                       "image: what --ram-budget checks (buffers plus the runtime's static state)"}}},
        {"stack",
         {{"bound", bud.stack},
          {"depth", D},
          {"frames", stack_frames},
          {"note", "bytes of stack mc_octree_render uses at any depth <= the model's, from -fstack-usage (larger of "
                   "arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -O2 and host gcc -O2) summed over the bounded call "
                   "graph (gen/runtime_costs.hpp); add the abort callback's own stack"}}},
        {"screen", {opt.screen_w, opt.screen_h}},
        {"emit", opt.lib ? "lib" : opt.stream ? "stream" : "app"},
        {"bits_per_point",
         {{"geometry", 8.0 * mask_bytes / points},
          {"color", 8.0 * color_bytes / points},
          {"total", 8.0 * data_bytes / points}}},
        {"chunks", chunk_files},
        {"modules", modules},
    };
    add_limits(budget, opt.limits, bud);
    if (opt.pmesh) {
        const PMesh &pm = *opt.pmesh;
        const size_t splits = pm.split_vertex.size();
        budget["pmesh"] = {
            {"vertices", pm.vertices()},
            {"faces", pm.faces.size()},
            {"base_vertices", pm.base_vertices},
            {"base_faces", pm.base_faces},
            {"splits", splits},
            {"index_bytes", plan.index_bytes},
            {"record_shift", plan.record_shift},
            {"edges", pm.edge_order.size()},
            {"half_edge_bytes", plan.half_bytes},
            {"bytes", plan.pm_data - plan.pm_line_data - plan.pm_face_data - plan.pm_group_data},
            {"bytes_per_split",
             splits ? double(plan.pm_data - plan.pm_line_data - plan.pm_face_data - plan.pm_group_data) / double(splits)
                    : 0.0},
            {"face_bytes", plan.pm_face_data},
            {"group_size", plan.group_size},
            {"group_bytes", plan.pm_group_data},
            {"line_bytes", plan.pm_line_data},
            {"line_bytes_per_face", double(plan.pm_line_data) / double(pm.faces.size())},
            {"lod_ram", bud.pmesh_lod},
            {"facing_ram", bud.pmesh_facing},
            {"cache_ram", bud.pmesh_cache},
            {"sdepth_ram", bud.pmesh_sdepth},
            {"neighbour_ram", bud.pmesh_neighbours},
            {"closed", pm.closed()},
            {"input",
             {{"faces_with_a_repeated_corner", pm.dropped_faces},
              {"vertex_copies_for_non_manifold_faces", pm.split_vertices},
              {"collapses_applied_for_max_faces", pm.capped_collapses}}},
        };
        budget["flash"]["pmesh"] = plan.pm_data;
        budget["ram"]["pmesh_lod"] = bud.pmesh_lod;
        budget["ram"]["pmesh_facing"] = bud.pmesh_facing;
        budget["ram"]["pmesh_cache"] = bud.pmesh_cache;
        budget["ram"]["pmesh_sdepth"] = bud.pmesh_sdepth;
        budget["ram"]["pmesh_neighbours"] = bud.pmesh_neighbours;
    }
    if (!opt.fit_note.empty()) budget["fit"] = opt.fit_note;
    for (const auto &[key, text] : opt.budget_extra) budget[key] = nlohmann::json::parse(text);
    return budget.dump(2) + "\n";
}

}  // namespace

std::string emit_model(const Octree &t, const Voxels &vox, const EmitOptions &options) {
    Stream st;
    EmitOptions opt = options;
    if (opt.stream) {
        st = bake_stream(t, opt.pmesh, opt.stream_packed);
        opt.stream_bytes = st.buffer;
    }
    const Plan plan = make_plan(t, opt);
    const Budget bud = budget_of(t, opt, plan);
    const auto files = data_files(plan.arrays, opt.file_bytes);
    nlohmann::json chunk_files = nlohmann::json::array();
    Files out = fill_templates(t, vox, opt, plan, bud, files, chunk_files);
    std::string budget_text = budget_json(t, vox, opt, plan, bud, chunk_files);
    if (opt.stream) {
        nlohmann::json b = nlohmann::json::parse(budget_text);
        b["stream"] = {{"file", opt.name + ".mcs"},
                       {"bytes", st.bytes.size()},
                       {"buffer", st.buffer},
                       {"drawable_at", st.drawable_at},
                       {"note", "drawable_at[i]: the bytes a reader needs to draw depth i + 1 (stream.h); "
                                "a receiver's buffer (buffer: NAME.h MC_NAME_STREAM_BYTES; the app binding's "
                                "stream_buf, RAM not counted in ram.image, which is the baked model's) holds all "
                                "bytes, and with a mesh part its arrays after them"}};
        if (opt.pmesh) {
            nlohmann::json levels = nlohmann::json::array();
            for (const auto &[at, level] : st.mesh_levels) levels.push_back({{"at", at}, {"level", level}});
            b["stream"]["mesh_levels"] = levels;
            b["stream"]["mesh_lines_at"] = st.lines_at;
            b["stream"]["note_mesh"] = "mesh_levels: the bytes after which the mesh draws at that level (the "
                                       "shaded style: base, then each batch of splits); mesh_lines_at: after which "
                                       "the line styles draw (the adjacency)";
        }
        budget_text = b.dump(2) + "\n";
        out.emplace_back(opt.name + ".mcs", std::move(st.bytes));
    }
    out.emplace_back("budget.json", budget_text);
    write_directory(opt.out_dir, opt.name, out);
    return budget_text;
}

}  // namespace mc
