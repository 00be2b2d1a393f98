// modelc: compiles a 3D model into C source for the modelc runtime.
#include <CLI/CLI.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <regex>

#include "emit.hpp"
#include "model.hpp"
#include "octree.hpp"
#include "progress.hpp"
#include "voxel.hpp"

namespace {

// A C identifier from a file name: lower case, other characters become '_'.
std::string name_from_path(const std::string &path) {
    std::string stem = std::filesystem::path(path).stem().string(), name;
    for (char c : stem) name += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(c)) : '_';
    if (name.empty() || std::isdigit(static_cast<unsigned char>(name[0]))) name = "m_" + name;
    return name;
}

int fail(const std::string &line, int status = 1) {
    std::fprintf(stderr, "modelc: %s\n", line.c_str());
    return status;
}

}  // namespace

int main(int argc, char **argv) {
    CLI::App app{"modelc: compile a triangle mesh or point set into C source for the modelc runtime.\n"
                 "Writes OUT/NAME/{NAME.h, NAME_data_N.c, NAME_scene.c, NAME_app.c, budget.json}."};
    std::string input, out_dir = "build", name, screen = "640x480";
    mc::VoxelOptions vox;
    mc::EmitOptions emit;
    int palette = 256;
    bool quiet = false;
    std::string up = "y";
    app.add_option("input", input, "model file: .off .obj .ply .stl (meshes), .xyz .ply (point sets)")->required();
    app.add_option("-o,--out", out_dir, "parent directory of the output directory")->capture_default_str();
    app.add_option("-n,--name", name, "model name, a C identifier (default: from the file name)");
    app.add_option("-d,--depth", vox.depth, "octree depth D: a grid of 2^D cells per side")
        ->check(CLI::Range(1, 12))->capture_default_str();
    app.add_option("--spacing", vox.spacing, "mesh sampling grid spacing, in cells")
        ->check(CLI::Range(0.05, 1.0))->capture_default_str();
    app.add_option("--palette", palette, "most palette entries")->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--chunk-bytes", emit.chunk_bytes, "most bytes in one generated array")
        ->check(CLI::Range(64, 1 << 30))->capture_default_str();
    app.add_option("--file-bytes", emit.file_bytes, "bytes of arrays per generated .c file before starting another")
        ->check(CLI::Range(64, 1 << 30))->capture_default_str();
    app.add_option("--screen", screen, "largest frame WxH the app binding's static buffers hold")
        ->capture_default_str();
    app.add_option("--up", up, "the model's up axis: y, or z for scans and CAD models that stand on the xy plane")
        ->check(CLI::IsMember({"y", "z"}))->capture_default_str();
    app.add_flag("-q,--quiet", quiet, "no progress output even on a terminal");
    app.set_version_flag("--version", "modelc 0.1");

    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        if (e.get_exit_code() == 0) return app.exit(e);
        return fail(std::string(e.what()) + " (see modelc --help)", 2);
    }
    std::smatch m;
    if (!std::regex_match(screen, m, std::regex("([0-9]{1,4})x([0-9]{1,4})")))
        return fail("--screen " + screen + ": expected WxH, e.g. 320x240", 2);
    emit.screen_w = std::stoi(m[1]);
    emit.screen_h = std::stoi(m[2]);
    if (emit.screen_w < 1 || emit.screen_h < 1 || emit.screen_w > 4096 || emit.screen_h > 4096)
        return fail("--screen " + screen + ": each side must be in 1..4096", 2);
    if (name.empty()) name = name_from_path(input);
    if (!std::regex_match(name, std::regex("[A-Za-z_][A-Za-z0-9_]{0,63}")))
        return fail("--name " + name + ": must be a C identifier of at most 64 characters", 2);

    try {
        mc::Progress progress(quiet);
        progress.step("loading");
        mc::Model model = mc::load_model(input);
        if (up == "z") mc::make_z_up_y_up(model);
        mc::Voxels voxels = mc::voxelize(model, input, vox, progress);
        progress.step("building octree");
        mc::Octree tree = mc::build_octree(voxels, palette);
        progress.step("writing");
        emit.name = name;
        emit.source = std::filesystem::path(input).filename().string();
        emit.out_dir = out_dir;
        mc::emit_model(tree, voxels, emit);
        progress.finish();
    } catch (const mc::InputError &e) {
        return fail(e.line());
    } catch (const std::bad_alloc &) {
        return fail(input + ": out of memory (try a smaller --depth)");
    } catch (const std::exception &e) {
        return fail(input + ": " + e.what());
    }
    return 0;
}
