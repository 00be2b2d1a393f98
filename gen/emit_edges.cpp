// Emission of an edge-model bake (--as edges): see emit.hpp. The layout is edges.h's: one chunk list
// per array, every chunk but the last holding 2^record_shift whole records.
#include "emit.hpp"
#include "emit_files.hpp"
#include "runtime_costs.hpp"

namespace mc {
namespace {

const int kArrayCount = 4;
const char *const kArrays[kArrayCount] = {"positions", "lines", "faces", "line_faces"};
const char *const kWhat[kArrayCount] = {"vertex positions (um)", "lines to track", "faces that hide them",
                                        "the two faces of each line (convex models)"};

struct EdgePlan {
    std::vector<std::vector<uint8_t>> bytes;   // kArrays
    std::vector<Array> arrays;
    mstch::array lists;
    nlohmann::json budget_arrays = nlohmann::json::object();
    size_t data = 0, chunk_entries = 0;
    unsigned index_bytes = 0, record_shift = 0;
};

void put(std::vector<uint8_t> &b, uint32_t v, unsigned n) {
    for (unsigned i = 0; i < n; i++) b.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

// The plan keeps pointers into its own byte vectors: it is built in place, never copied.
void make_plan(const EdgeModel &e, const EmitOptions &opt, EdgePlan &p) {
    p.index_bytes = std::max(e.positions.size(), e.faces.size()) <= 65535 ? 2 : 4;
    const unsigned ib = p.index_bytes;
    const size_t record[kArrayCount] = {12, 2 * ib, 3 * ib, 2 * ib};
    const size_t largest = std::max<size_t>(12, 3 * ib);
    while ((size_t(2) << p.record_shift) * largest <= opt.chunk_bytes) p.record_shift++;
    p.bytes.assign(kArrayCount, {});
    for (const auto &q : e.positions)
        for (int32_t c : q) put(p.bytes[0], static_cast<uint32_t>(c), 4);
    for (const auto &l : e.lines) put(p.bytes[1], l[0], ib), put(p.bytes[1], l[1], ib);
    for (const auto &f : e.faces) put(p.bytes[2], f[0], ib), put(p.bytes[2], f[1], ib), put(p.bytes[2], f[2], ib);
    for (const auto &l : e.line_faces) put(p.bytes[3], l[0], ib), put(p.bytes[3], l[1], ib);
    for (int k = 0; k < kArrayCount; k++) {
        const std::string list = "mc_" + opt.name + "_e_" + kArrays[k];
        mstch::array chunks;
        size_t at = 0, i = 0;
        for (size_t size : split_chunks(p.bytes[k].size(), record[k] << p.record_shift, nullptr)) {
            const std::string sym = list + "_" + std::to_string(i++);
            p.arrays.push_back({sym, std::string("edge model ") + kWhat[k] + ", bytes " + std::to_string(at) + ".." +
                                         std::to_string(at + size - 1),
                                p.bytes[k].data() + at, size, false});
            chunks.push_back(mstch::map{{"symbol", sym}, {"size", std::to_string(size)}});
            p.budget_arrays[sym] = size;
            at += size;
        }
        p.chunk_entries += i + 1;   // the chunks and the {0, 0} sentinel
        p.lists.push_back(mstch::map{{"symbol", list}, {"chunks", chunks}});
        p.data += p.bytes[k].size();
    }
}

Budget budget_of(const EdgeModel &e, const EmitOptions &opt, const EdgePlan &p) {
    EdgeBakeSize s;
    s.data = p.data;
    s.chunk_entries = p.chunk_entries;
    s.name_bytes = opt.name.size() + 1;
    s.vertices = e.positions.size();
    s.particles = opt.particles;
    s.screen_w = opt.screen_w, s.screen_h = opt.screen_h;
    return budget_of(s);
}

std::string budget_json(const EdgeModel &e, const EmitOptions &opt, const EdgePlan &p, const Budget &bud,
                        const nlohmann::json &chunk_files) {
    nlohmann::json modules = nlohmann::json::array(), code = nlohmann::json::object();
    for (const char *name : rt::kTrackShared) modules.push_back(name);
    for (const auto &m : rt::kTrackModules) modules.push_back(m.name), code[m.name] = m.bytes;
    code["shared_with_the_renderers"] = bud.code - rt::kLibgccDivision - [] {
        size_t own = 0;
        for (const auto &m : rt::kTrackModules) own += m.bytes;
        return own;
    }();
    code["libgcc"] = rt::kLibgccDivision;
    code["total"] = bud.code;
    const TrackRam tr = track_ram(opt.screen_w, opt.screen_h, e.positions.size(), opt.particles);
    nlohmann::json budget = {
        {"model", opt.name},
        {"source", opt.source},
        {"kind", "edge-model"},
        {"vertices", e.positions.size()},
        {"lines", e.lines.size()},
        {"faces", e.faces.size()},
        {"closed", e.closed},
        {"convex", e.convex},
        {"lines_from", e.file_lines ? "file" : "feature edges"},
        {"index_bytes", p.index_bytes},
        {"record_shift", p.record_shift},
        {"chunk_bytes", opt.chunk_bytes},
        {"input",
         {{"faces_without_area", e.dropped_faces},
          {"vertex_copies_for_orientation", e.copied_vertices},
          {"border_lines", e.border_lines},
          {"crease_lines", e.crease_lines}}},
        {"flash",
         {{"arrays", p.budget_arrays},
          {"total", bud.data()},
          {"descriptors", bud.descriptors},
          {"runtime_code", code},
          {"image", bud.flash()},
          {"note", "total: the edge model's arrays. image: what --flash-budget checks, total plus descriptors "
                   "(32-bit layout) plus runtime_code, an estimate of the tracker's text and rodata for "
                   "Cortex-M4 -O2 (gen/runtime_costs.hpp)"}}},
        {"ram",
         {{"color_buffer", bud.color_buffer},
          {"depth_buffer", bud.depth_buffer},
          {"frame", tr.frame},
          {"masks", tr.masks},
          {"edge_scratch", tr.scratch},
          {"sdepth_bits", tr.sdepth},
          {"sdepth_matched", tr.matched},
          {"vertex_cache", tr.cache},
          {"particles", tr.particles},
          {"particle_count", opt.particles},
          {"runtime_static", bud.runtime_ram},
          {"image", bud.ram()},
          {"note", std::string(opt.lib ? "--emit lib: the caller provides these; sized here for --screen and "
                                         "--particles. "
                                       : "static arrays of NAME_app.c for --screen and --particles. ") +
                       "The frame buffers hold the sparse depth buffer's depths and colours. image: what "
                       "--ram-budget checks"}}},
        {"stack",
         {{"bound", bud.stack},
          {"note", "bytes of stack a tracker's frame uses in the runtime (the image edges, then mc_filter_step), "
                   "from -fstack-usage (larger of arm-none-eabi-gcc -mcpu=cortex-m4 -mthumb -O2 and host gcc -O2) "
                   "summed over its call graph (gen/runtime_costs.hpp kTrackFrames); add the front end's own"}}},
        {"screen", {opt.screen_w, opt.screen_h}},
        {"emit", opt.lib ? "lib" : "app"},
        {"chunks", chunk_files},
        {"modules", modules},
    };
    add_limits(budget, opt.limits, bud);
    return budget.dump(2) + "\n";
}

}  // namespace

Budget budget_of(const EdgeModel &e, const EmitOptions &opt) {
    EdgePlan p;
    make_plan(e, opt, p);
    return budget_of(e, opt, p);
}

std::string emit_edges(const EdgeModel &e, const GridCube &cube, const EmitOptions &opt) {
    EdgePlan p;
    make_plan(e, opt, p);
    const Budget bud = budget_of(e, opt, p);
    const std::string &name = opt.name;
    nlohmann::json chunk_files = nlohmann::json::array();
    Files out = data_file_texts(opt, data_files(p.arrays, opt.file_bytes), chunk_files);

    mstch::map part = common(opt);
    mstch::array decls, symbols;
    for (const Array &a : p.arrays) {
        decls.push_back(mstch::map{{"symbol", a.symbol}, {"size", std::to_string(a.size)}});
        symbols.push_back(mstch::map{{"symbol", a.symbol}, {"suffix", a.symbol.substr(4 + name.size())}});
    }
    const mstch::map sizes{{"vertices", std::to_string(e.positions.size())},
                           {"lines", std::to_string(e.lines.size())},
                           {"faces", std::to_string(e.faces.size())},
                           {"closed", std::string(e.closed ? "1" : "0")},
                           {"convex", std::string(e.convex ? "1" : "0")},
                           {"index_bytes", std::to_string(p.index_bytes)},
                           {"record_shift", std::to_string(p.record_shift)}};
    for (const auto &[k, v] : sizes) part.emplace(k, v);
    part.emplace("arrays", decls);
    part.emplace("lists", p.lists);
    for (int k = 0; k < kArrayCount; k++) part.emplace(std::string("list_") + kArrays[k], "mc_" + name + "_e_" + kArrays[k]);
    out.emplace_back(name + "_edges.c", mstch::render(template_text("edges.c"), part));

    mstch::map model = model_data(cube, opt);
    model.emplace("octree_ptr", std::string("0"));
    model.emplace("pmesh_ptr", std::string("0"));
    model.emplace("edges_ptr", "&mc_edges_" + name);
    out.emplace_back(name + "_model.c", mstch::render(template_text("model.c"), model));

    mstch::map header = common(opt);
    for (const auto &[k, v] : sizes) header.emplace(k, v);
    header.emplace("parts", mstch::array{mstch::map{{"part", std::string("edges")}}});
    header.emplace("symbols", symbols);
    header.emplace("data_bytes", std::to_string(bud.data()));
    header.emplace("screen_w", std::to_string(opt.screen_w));
    header.emplace("screen_h", std::to_string(opt.screen_h));
    header.emplace("particles", std::to_string(opt.particles));
    header.emplace("workspace_bytes", std::to_string(bud.ram() - bud.runtime_ram));
    header.emplace("lib", opt.lib);
    out.emplace_back(name + ".h", render_header("edges.h", header));
    header.emplace("edges", true);
    if (!opt.lib) out.emplace_back(name + "_app.c", mstch::render(template_text("app.c"), header));
    std::string text = budget_json(e, opt, p, bud, chunk_files);
    out.emplace_back("budget.json", text);
    write_directory(opt.out_dir, name, out);
    return text;
}

}  // namespace mc
