// Shared emission helpers: see emit_files.hpp.
#include "emit_files.hpp"

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>

namespace fs = std::filesystem;

namespace mc {
namespace {

void write_file(const fs::path &path, const std::string &text) {
    std::ofstream f(path, std::ios::binary);
    f << text;
    f.close();
    if (!f) throw std::runtime_error(path.string() + ": cannot write: " + std::strerror(errno));
}

// A file coordinate as Q32.32 (modelc/model.h), rounded to nearest, saturated.
std::string q32(double v) {
    const double scaled = std::ldexp(v, 32);
    if (!(scaled < 9.2e18)) return "INT64_MAX";
    if (!(scaled > -9.2e18)) return "INT64_MIN";
    return "INT64_C(" + std::to_string(std::llround(scaled)) + ")";
}

std::string g9(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    return buf;
}

}  // namespace

std::string upper(std::string s) {
    for (char &c : s) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

mstch::array byte_lines(const uint8_t *p, size_t n) {
    mstch::array lines;
    std::string line;
    for (size_t i = 0; i < n; i++) {
        line += std::to_string(p[i]) + ",";
        if (i % 24 == 23 || i + 1 == n) lines.push_back(line), line.clear();
    }
    return lines;
}

mstch::map common(const EmitOptions &opt) {
    return mstch::map{{"name", opt.name}, {"NAME", upper(opt.name)}, {"source", opt.source}};
}

mstch::map model_data(const GridCube &cube, const EmitOptions &opt) {
    const double side = cube.side;
    std::array<double, 3> c{};
    for (int i = 0; i < 3; i++) c[i] = cube.origin[i] + side / 2;
    c = file_frame(c, opt.up);
    mstch::map m = common(opt);
    m.emplace("centre_q", q32(c[0]) + ", " + q32(c[1]) + ", " + q32(c[2]));
    m.emplace("side_q", q32(side));
    m.emplace("centre_text", g9(c[0] + 0.0) + ", " + g9(c[1] + 0.0) + ", " + g9(c[2] + 0.0));   // no "-0"
    m.emplace("side_text", g9(side));
    const bool z = opt.up == UpAxis::z;
    m.emplace("up", std::string(z ? "z" : "y"));
    m.emplace("up_code", std::string(z ? "MC_UP_Z" : "MC_UP_Y"));
    return m;
}

std::string render_header(const std::string &tmpl, const mstch::map &ctx) {
    return mstch::render(template_text(tmpl), ctx, {{"placement", template_text("placement.h")}});
}

void add_limits(nlohmann::json &budget, const Limits &limits, const Budget &bud) {
    if (!limits.flash && !limits.ram && !limits.stack) return;
    nlohmann::json lim = nlohmann::json::object();
    if (limits.flash) lim["flash"] = {{"limit", limits.flash}, {"used", bud.flash()}};
    if (limits.ram) lim["ram"] = {{"limit", limits.ram}, {"used", bud.ram()}};
    if (limits.stack) lim["stack"] = {{"limit", limits.stack}, {"used", bud.stack}};
    budget["budgets"] = lim;
}

std::vector<std::vector<const Array *>> data_files(const std::vector<Array> &arrays, size_t file_bytes) {
    std::vector<std::vector<const Array *>> files(1);
    size_t in_file = 0;
    for (const Array &a : arrays) {
        if (in_file > 0 && in_file + a.size > file_bytes) files.emplace_back(), in_file = 0;
        files.back().push_back(&a);
        in_file += a.size;
    }
    return files;
}

void write_directory(const fs::path &parent, const std::string &name, const Files &out) {
    const fs::path final_dir = parent / name;
    std::string pid = std::to_string(getpid());
    fs::path tmp = parent / ("." + name + ".tmp-" + pid), old = parent / ("." + name + ".old-" + pid);
    try {
        fs::create_directories(parent);
        fs::remove_all(tmp);
        fs::create_directory(tmp);
        for (const auto &[fname, text] : out) write_file(tmp / fname, text);
        if (fs::exists(final_dir)) fs::rename(final_dir, old);
        fs::rename(tmp, final_dir);
        fs::remove_all(old);
    } catch (...) {
        std::error_code ec;
        fs::remove_all(tmp, ec);
        if (!fs::exists(final_dir, ec) && fs::exists(old, ec)) fs::rename(old, final_dir, ec);
        throw;
    }
}

Files data_file_texts(const EmitOptions &opt, const std::vector<std::vector<const Array *>> &files,
                      nlohmann::json &chunk_files) {
    const std::string &name = opt.name;
    Files out;
    for (size_t f = 0; f < files.size(); f++) {
        mstch::map ctx = common(opt);
        mstch::array arr;
        size_t bytes = 0;
        std::string fname = name + "_data_" + std::to_string(f) + ".c";
        for (const Array *a : files[f]) {
            arr.push_back(mstch::map{{"symbol", a->symbol}, {"what", a->what}, {"size", std::to_string(a->size)},
                                     {"lines", byte_lines(a->data, a->size)}});
            bytes += a->size;
            chunk_files.push_back({{"symbol", a->symbol}, {"bytes", a->size}, {"file", fname}});
        }
        ctx.emplace("arrays", arr);
        ctx.emplace("index", std::to_string(f + 1));
        ctx.emplace("files", std::to_string(files.size()));
        ctx.emplace("bytes", std::to_string(bytes));
        ctx.emplace("count", std::to_string(files[f].size()));
        out.emplace_back(fname, mstch::render(template_text("data.c"), ctx));
    }
    return out;
}

}  // namespace mc
