// modelc: compiles a 3D model into C source for the modelc runtime. This file parses the options
// and runs the stages in order (gen/README.md): input, normalize, voxels, visibility, octree,
// budget or fit, emit.
#include <CLI/CLI.hpp>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <cmath>
#include <cstdlib>
#include <regex>

#include "budget.hpp"
#include "cones.hpp"
#include "edge_model.hpp"
#include "emit.hpp"
#include "fit.hpp"
#include "model.hpp"
#include "normalize.hpp"
#include "octree.hpp"
#include "pmesh.hpp"
#include "progress.hpp"
#include "reference.hpp"
#include "visibility.hpp"
#include "voxel.hpp"
#include "modelc/config.h"   // MC_MAX_DEPTH: the deepest octree the runtime decodes

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
                 "Writes OUT/NAME/{NAME.h, NAME_data_N.c, NAME_octree.c, NAME_model.c, NAME_app.c, budget.json}."};
    std::string input, out_dir = "build", name, screen = "640x480";
    mc::VoxelOptions vox;
    mc::EmitOptions emit;
    int palette = 256;
    bool quiet = false, fit = false;
    std::string up = "y", emit_kind = "app", stream_splits = "plain", flash_budget, ram_budget, stack_budget;
    int min_palette = 16;
    std::string views = "all";
    std::string dump_reference;  // hidden: tests and benchmarks only
    std::string as = "points";
    std::string cull = "on";
    std::string dump_pmesh;       // hidden: tests only, N:FILE
    mc::PMeshOptions pmesh_opt;
    mc::EdgeModelOptions edge_opt;
    std::string unit = "m";
    app.add_option("input", input, "model file: .off .obj .ply .stl .cao .gltf .glb (meshes), .xyz .ply (point sets)")->required();
    app.add_option("-o,--out", out_dir, "parent directory of the output directory")->capture_default_str();
    app.add_option("-n,--name", name, "model name, a C identifier (default: from the file name)");
    app.add_option("-d,--depth", vox.depth, "octree depth D: a grid of 2^D cells per side")
        ->check(CLI::Range(1, MC_MAX_DEPTH))->capture_default_str();
    app.add_option("--spacing", vox.spacing, "mesh sampling grid spacing, in cells")
        ->check(CLI::Range(0.05, 1.0))->capture_default_str();
    std::string point_fill = "auto";
    app.add_option("--point-fill", point_fill, "point sets sparser than the grid (CGAL's average spacing 0.3 cells "
                   "or more): auto fills in the surface between the points (gen/point_fill.hpp); off: one cell per point")
        ->check(CLI::IsMember({"auto", "off"}))->capture_default_str();
    app.add_option("--palette", palette, "most palette entries")->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--chunk-bytes", emit.chunk_bytes, "most bytes in one generated array")
        ->check(CLI::Range(64, 1 << 30))->capture_default_str();
    app.add_option("--file-bytes", emit.file_bytes, "bytes of arrays per generated .c file before starting another")
        ->check(CLI::Range(64, 1 << 30))->capture_default_str();
    app.add_option("--screen", screen, "largest frame WxH the app binding's static buffers hold")
        ->capture_default_str();
    app.add_option("--up", up, "the model's up axis: y, or z for scans and CAD models that stand on the xy plane")
        ->check(CLI::IsMember({"y", "z"}))->capture_default_str();
    app.add_option("--views", views,
                   "directions the model will be seen from; cells visible from none are removed: all (no "
                   "pruning), or a comma list of front:DEG (within DEG degrees of the front axis), YAW:PITCH "
                   "(one view, degrees as the viewer's --yaw --pitch), YAW:PITCH:DEG (a cone around it), "
                   "each optionally @N directions")
        ->capture_default_str();
    app.add_option("--emit", emit_kind, "app: the model and NAME_app.c with static frame buffers for a front end; "
                   "lib: only the model's .c/.h, for an existing firmware project; stream: app and NAME.mcs, the "
                   "bake as one binary stream, coarse first: the octree's levels, then with --as both the mesh's "
                   "base and splits (runtime/include/modelc/stream.h)")
        ->check(CLI::IsMember({"app", "lib", "stream"}))->capture_default_str();
    app.add_option("--stream-splits", stream_splits, "with --emit stream and --as both, how the mesh's splits travel: "
                   "plain (fixed-width records, stream version 2) or packed (bit-coded, what the reader can infer "
                   "left out: about a third of the bytes, stream version 3; the reader then needs MC_STREAM_PACKED_BYTES "
                   "more RAM to decode them)")
        ->check(CLI::IsMember({"plain", "packed"}))->capture_default_str();
    app.add_option("--flash-budget", flash_budget, "fail (exit 1, no output) unless data, descriptors and the "
                   "runtime's code fit SIZE bytes (e.g. 262144, 256K, 1M)");
    app.add_option("--ram-budget", ram_budget, "fail unless the frame buffers for --screen and the runtime's static "
                   "state fit SIZE bytes");
    app.add_option("--stack-budget", stack_budget, "fail unless mc_octree_render's stack bound at --depth fits SIZE bytes");
    app.add_flag("--fit", fit, "with the budgets: bake the finest depth <= --depth, then the largest palette <= "
                 "--palette (halving, not below --min-palette) and the largest screen of --screen's aspect (not "
                 "below " + std::to_string(mc::kFitMinSide) + " pixels a side) that fit; prints what it chose in one line");
    app.add_option("--min-palette", min_palette, "--fit: fewest palette entries to try")
        ->check(CLI::Range(1, 256))->capture_default_str();
    app.add_option("--leaf-switch", emit.leaf_switch, "MC_LEAF_SWITCH the runtime is built with (config.h): "
                   "1 costs about 56 KB more code on Cortex-M, counted in the flash budget")
        ->check(CLI::Range(0, 1))->capture_default_str();
    app.add_option("--as", as, "the parts to bake: points (the point octree), both (the octree and a progressive "
                   "mesh, for triangle meshes only), or edges (an edge model for tracking, alone: meshes and .cao)")
        ->check(CLI::IsMember({"points", "both", "edges"}))->capture_default_str();
    app.add_option("--unit", unit, "--as edges: the length of one file unit: m, cm, mm, um, or metres as a number "
                   "(.cao models are in metres)")
        ->capture_default_str();
    app.add_option("--particles", emit.particles, "--as edges: the most particles the app binding holds")
        ->check(CLI::Range(size_t(1), size_t(65535)))->capture_default_str();
    app.add_option("--max-faces", pmesh_opt.max_faces, "--as both: the most faces of the mesh's finest level (0: all "
                   "of the file's)")
        ->check(CLI::Range(size_t(0), size_t(1) << 31))->capture_default_str();
    app.add_flag("--mesh-neighbours", emit.mesh_neighbours, "--as both: the app binding also keeps a table of the "
                 "current level's neighbours, 3 half-edges a face of RAM, so that line drawings at coarse levels "
                 "do not walk across removed faces (runtime/include/modelc/pmesh.h)");
    app.add_option("--mesh-groups", emit.mesh_groups, "--as both: also store the faces in groups of N (a power of "
                   "two, 2 to 1024; 0: none), near faces together, with each group's box (12 bytes a group and 2 or 3 "
                   "a face of flash), so that a line drawing at the full level of an orthographic view passes over "
                   "a group that cannot hide a line (runtime/include/modelc/pmesh.h)")
        ->check(CLI::Range(size_t(0), size_t(1024)))->capture_default_str();
    app.add_option("--crease-angle", pmesh_opt.crease_angle, "--as both, --as edges: degrees between two faces' "
                   "normals above which their edge is drawn as a crease, or tracked")
        ->check(CLI::Range(0.0, 180.0))->capture_default_str();
    app.add_option("--hide-faces", edge_opt.hide_faces, "--as edges: hide lines behind the mesh decimated to about "
                   "N faces (OpenMesh's Decimater; the lines stay the full mesh's); 0: every face")
        ->check(CLI::Range(size_t(0), size_t(1) << 31))->capture_default_str();
    app.add_option("--dump-pmesh-level", dump_pmesh, "N:FILE: write the faces OpenMesh's decimater leaves at N "
                   "vertices (pmesh.hpp dump_decimated), for the tests")
        ->group("");
    app.add_option("--dump-reference", dump_reference, "write the normalised original model for the tests' "
                   "mesh reference renderer (runtime/ref/mesh_ref.h)")
        ->group("");
    app.add_option("--cull", cull, "normal cones so the renderer skips subtrees whose surface all faces away: on "
                   "(closed meshes; made only where every edge has two faces, nothing self-intersects) or off")
        ->check(CLI::IsMember({"on", "off"}))->capture_default_str();
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
    mc::ViewSpec view_spec;
    try {
        view_spec = mc::parse_views(views);
    } catch (const std::invalid_argument &e) {
        return fail("--views " + views + ": " + e.what(), 2);
    }
    try {
        if (!flash_budget.empty()) emit.limits.flash = mc::parse_size("--flash-budget", flash_budget);
        if (!ram_budget.empty()) emit.limits.ram = mc::parse_size("--ram-budget", ram_budget);
        if (!stack_budget.empty()) emit.limits.stack = mc::parse_size("--stack-budget", stack_budget);
    } catch (const std::exception &e) {
        return fail(e.what(), 2);
    }
    const mc::Limits &limits = emit.limits;
    if (fit && !limits.flash && !limits.ram && !limits.stack)
        return fail("--fit needs at least one of --flash-budget, --ram-budget, --stack-budget", 2);
    if (as == "edges") {
        if (fit) return fail("--fit: an edge model has no depth or palette to choose (--as edges)", 2);
        if (emit_kind == "stream") return fail("--emit stream: streams hold a point octree; an edge model has none (--as edges)", 2);
        static const std::map<std::string, double> units = {{"m", 1.0}, {"cm", 0.01}, {"mm", 0.001}, {"um", 1e-6}};
        auto u = units.find(unit);
        char *end = nullptr;
        edge_opt.unit = u != units.end() ? u->second : std::strtod(unit.c_str(), &end);
        if (u == units.end() && (end == unit.c_str() || *end || !(edge_opt.unit > 0) || !std::isfinite(edge_opt.unit)))
            return fail("--unit " + unit + ": expected m, cm, mm, um or a positive number of metres", 2);
        edge_opt.crease_angle = pmesh_opt.crease_angle;
    }
    emit.lib = emit_kind == "lib";
    emit.stream = emit_kind == "stream";
    emit.stream_packed = stream_splits == "packed";
    if (emit.stream_packed && (!emit.stream || as != "both"))
        return fail("--stream-splits packed: only a stream with a mesh part has splits (--emit stream --as both)", 2);
    if (emit.mesh_groups && (emit.mesh_groups < 2 || (emit.mesh_groups & (emit.mesh_groups - 1))))
        return fail("--mesh-groups " + std::to_string(emit.mesh_groups) + ": faces a group must be a power of two from 2 to 1024, or 0", 2);
    if (emit.mesh_groups && as != "both")
        return fail("--mesh-groups: only a mesh part has faces to group (--as both)", 2);
    if (emit.mesh_groups && emit.stream)
        return fail("--mesh-groups: a stream does not carry face groups (--emit stream)", 2);
    if (emit.mesh_neighbours && as != "both")
        return fail("--mesh-neighbours: only a mesh part has neighbours to keep (--as both)", 2);
    if (emit.mesh_neighbours && emit.lib)
        return fail("--mesh-neighbours: the table is the app binding's memory, which --emit lib leaves out", 2);
    emit.up = up == "z" ? mc::UpAxis::z : mc::UpAxis::y;
    if (name.empty()) name = name_from_path(input);
    if (!std::regex_match(name, std::regex("[A-Za-z_][A-Za-z0-9_]{0,63}")))
        return fail("--name " + name + ": must be a C identifier of at most 64 characters", 2);

    try {
        mc::Progress progress(quiet);
        progress.step("loading");
        mc::Model model = mc::load_model(input);
        emit.name = name;
        emit.source = std::filesystem::path(input).filename().string();
        emit.out_dir = out_dir;
        if (as == "edges") {   // in the file's own frame: built before normalize() turns the model
            progress.step("edge model");
            const mc::EdgeModel edges = mc::build_edge_model(model, input, edge_opt);
            const mc::GridCube cube = mc::normalize(model, emit.up);
            std::string over = mc::over_budget(mc::budget_of(edges, emit), limits);
            if (!over.empty()) throw mc::BudgetError("over budget: " + over);
            progress.step("writing");
            mc::emit_edges(edges, cube, emit);
            progress.finish();
            return 0;
        }
        const mc::GridCube cube = mc::normalize(model, emit.up);
        // the mesh part first: a point set asked for one stops here, before the long stages
        mc::PMesh pmesh;
        if (as == "both") {
            if (!model.is_mesh)
                throw mc::InputError(input, mc::InputError::Where::none, 0,
                                     "a point set cannot be baked as a mesh (--as both): it has no faces");
            progress.step("progressive mesh");
            pmesh = mc::build_pmesh(model, cube, pmesh_opt);
            emit.pmesh = &pmesh;
            if (!dump_pmesh.empty()) {
                const size_t colon = dump_pmesh.find(':');
                if (colon == std::string::npos) throw std::runtime_error("--dump-pmesh-level " + dump_pmesh + ": expected N:FILE");
                std::ofstream f(dump_pmesh.substr(colon + 1));
                mc::dump_decimated(model, cube, std::stoul(dump_pmesh.substr(0, colon)), f);
                if (!f) throw std::runtime_error("--dump-pmesh-level " + dump_pmesh + ": cannot write");
            }
        }
        vox.point_fill = point_fill == "auto";
        mc::Voxels voxels = mc::voxelize(model, cube, input, vox, progress);
        if (!model.is_mesh) emit.budget_extra.emplace_back("point_fill", voxels.fill.json());
        if (!dump_reference.empty()) mc::dump_reference(model, voxels, dump_reference);
        // --views: the cells to keep, whatever depth and palette the octree gets (empty: keep all)
        std::vector<uint8_t> keep;
        mc::PruneStats pruned;
        if (!view_spec.all) {
            progress.step("visibility");
            keep = mc::visible_cells(model, voxels, mc::view_directions(view_spec), progress, pruned);
            emit.budget_extra.emplace_back("pruning", mc::pruning_json(view_spec, pruned));
        }
        mc::ConeSource cones;
        if (cull == "on") {
            progress.step("normal cones");
            cones = mc::cone_source(model, cube);
        } else {
            cones.why = "--cull off";
        }
        emit.budget_extra.emplace_back("cones", cones.impl ? std::string("{\"made\": true}")
                                                           : "{\"made\": false, \"why_not\": \"" + cones.why + "\"}");
        progress.step("building octree");
        mc::Octree tree;
        if (!fit) {
            tree = mc::build_octree(voxels, palette);
            if (!keep.empty()) tree = mc::prune_octree(tree, voxels, keep);
            mc::add_cones(tree, cones);
            std::string over = mc::over_budget(mc::budget_of(tree, emit), limits);
            if (!over.empty()) throw mc::BudgetError("over budget: " + over);
        } else {
            mc::FitChoice choice = mc::fit(voxels, keep, emit, {palette, min_palette, screen, &cones});
            tree = std::move(choice.tree);
            emit.screen_w = choice.screen_w, emit.screen_h = choice.screen_h;
            emit.fit_note = choice.note;
        }
        progress.step("writing");
        mc::emit_model(tree, voxels, emit);
        progress.finish();
        if (fit) std::printf("modelc: %s\n", emit.fit_note.c_str());
        if (!view_spec.all && !quiet) std::fprintf(stderr, "modelc: %s\n", mc::pruning_report(view_spec, pruned).c_str());
    } catch (const mc::InputError &e) {
        return fail(e.line());
    } catch (const mc::BudgetError &e) {
        return fail(e.what());
    } catch (const std::bad_alloc &) {
        return fail(input + ": out of memory (try a smaller --depth)");
    } catch (const std::exception &e) {
        return fail(input + ": " + e.what());
    }
    return 0;
}
