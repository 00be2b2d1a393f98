// Sampling (CGAL sample_triangle_mesh), voxelization and per-cell colour.
#include "voxel.hpp"

#include "cgal_mesh.hpp"
#include "light.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Polygon_mesh_processing/compute_normal.h>
#include <CGAL/Polygon_mesh_processing/distance.h>
#include <CGAL/Polygon_mesh_processing/locate.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <boost/function_output_iterator.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace mc {
namespace {

double frontal_light(const Vector &n) { return mc::frontal_light(n.x(), n.y(), n.z()); }

struct Cell {
    double sum[3] = {0, 0, 0};  // sample positions (meshes) or colours/normals (point sets)
    double extra[3] = {0, 0, 0};
    double at[3] = {0, 0, 0};   // meshes: the surface point nearest the samples' centroid
    uint32_t count = 0;
};

// The 2^D grid over the model's grid cube (normalize.hpp): a model-space point to its cell.
class Grid {
public:
    Grid(const GridCube &cube, int depth)
        : depth_(depth), n_(1u << depth), cell_(cube.cell(depth)), origin_(cube.origin) {}
    uint64_t code(double x, double y, double z) const {
        return morton_encode(index(x, 0), index(y, 1), index(z, 2), depth_);
    }
    double cell() const { return cell_; }
    const std::array<double, 3> &origin() const { return origin_; }

private:
    uint32_t index(double v, int a) const {
        double t = std::floor((v - origin_[a]) / cell_);
        return t < 0 ? 0 : t >= n_ ? n_ - 1 : static_cast<uint32_t>(t);
    }
    int depth_;
    uint32_t n_;
    double cell_;
    std::array<double, 3> origin_;
};

// Receives CGAL's samples one by one: the samples themselves are never stored, only the cells.
// (A plain struct of pointers: CGAL copy-assigns the output iterator, which a lambda cannot be.)
struct SampleSink {
    const Grid *grid;
    std::unordered_map<uint64_t, Cell> *cells;
    uint64_t *samples;
    Progress *progress;
    double expected;
    void operator()(const Point &p) const {
        Cell &c = (*cells)[grid->code(p.x(), p.y(), p.z())];
        c.sum[0] += p.x(), c.sum[1] += p.y(), c.sum[2] += p.z();
        c.count++;
        if ((++*samples & 0xFFFF) == 0) progress->update(std::min(static_cast<double>(*samples), 0.99 * expected), expected);
    }
};

// PMP::locate_with_AABB_tree, except on a face without area (two corners at one position, or all
// three on a line), where CGAL's barycentric coordinates fail an assertion: there the nearest
// corner takes the whole weight. Models without such faces never reach the fallback.
template <class Tree>
PMP::Face_location<Mesh, double> locate(const Point &p, const Tree &tree, const Mesh &mesh) {
    try {
        return PMP::locate_with_AABB_tree(p, tree, mesh);
    } catch (const CGAL::Failure_exception &) {
        const auto face = tree.closest_point_and_primitive(p).second;
        const auto h = mesh.halfedge(face);
        const Mesh::Vertex_index vs[3] = {mesh.source(h), mesh.target(h), mesh.target(mesh.next(h))};
        int best = 0;
        for (int i = 1; i < 3; i++)
            if (CGAL::squared_distance(p, mesh.point(vs[i])) < CGAL::squared_distance(p, mesh.point(vs[best]))) best = i;
        PMP::Barycentric_coordinates<double> w{0, 0, 0};
        w[best] = 1;
        return {face, w};
    }
}

// The cells one sampling of the surface hits, at grid spacing opt.spacing cells of grid: each
// cell's sample sum and count.
void sample_level(const Mesh &mesh, const Grid &grid, const VoxelOptions &opt, Progress &progress,
                  std::unordered_map<uint64_t, Cell> &cells, uint64_t &samples) {
    // grid sampling puts about one sample per spacing^2 of area: the denominator of the progress
    const double spacing = grid.cell() * opt.spacing;
    const double total = PMP::area(mesh) / (spacing * spacing) + 1;
    uint64_t taken = 0;
    SampleSink sink{&grid, &cells, &taken, &progress, total};
    PMP::sample_triangle_mesh(mesh, boost::make_function_output_iterator(sink),
                              CGAL::parameters::use_grid_sampling(true)
                                  .grid_spacing(spacing)
                                  .do_sample_vertices(true)
                                  .do_sample_edges(true));
    samples += taken;
}

// A cell's colour is the surface colour at the centroid of its samples, found with one AABB
// query per cell (a cell's samples lie within one cell of each other, so per-sample queries
// would cost ten times more for differences below a grey level).
template <class Tree, class NormalMap>
void shade_cells(const Model &m, const Mesh &mesh, const Tree &tree, const NormalMap &vnormal, Progress &progress,
                 std::unordered_map<uint64_t, Cell> &cells) {
    const bool colored = !m.colors.empty();
    size_t done = 0;
    for (auto &kv : cells) {
        Cell &c = kv.second;
        Point centroid(c.sum[0] / c.count, c.sum[1] / c.count, c.sum[2] / c.count);
        auto loc = locate(centroid, tree, mesh);
        auto h = mesh.halfedge(loc.first);
        Mesh::Vertex_index vs[3] = {mesh.source(h), mesh.target(h), mesh.target(mesh.next(h))};
        double rgb[3] = {0, 0, 0};
        Vector n(0, 0, 0);
        for (int i = 0; i < 3; i++) {
            double w = loc.second[i];
            if (colored)
                for (int a = 0; a < 3; a++) rgb[a] += w * m.colors[vs[i].idx()][a];
            n = n + w * vnormal[vs[i]];
        }
        if (!colored) rgb[0] = rgb[1] = rgb[2] = 255.0 * frontal_light(n);
        for (int a = 0; a < 3; a++) c.extra[a] = rgb[a];
        for (int i = 0; i < 3; i++)  // the located point itself (PMP::construct_point is 50x slower)
            for (int a = 0; a < 3; a++) c.at[a] += loc.second[i] * mesh.point(vs[i])[a];
        if ((++done & 0xFFF) == 0) progress.update(static_cast<double>(done), static_cast<double>(cells.size()));
    }
}

// Level l's cells under the kept nodes of level l - 1 (parents): cells whose parent is not kept
// are dropped (drop_orphans), and a parent none of whose children level l's sampling hit (the two
// levels' sample lattices do not nest, so this happens) gets the child holding its surface point,
// with its colour (adopt). Why: a level's sampling at --spacing of its cell decides which cells a
// bake of that depth has; a finer sampling also hits cells the surface only grazes at a corner or
// an edge, and those, drawn as pixels at their centres, stand off the surface. Level 8 taken as the
// parents of all of level 9's hits has 7 % more cells than a depth-8 bake (of level 10's, 11 %), as
// a depth-8 bake sampled at --spacing 0.25 (0.125) has, and draws worse images (bunny00, 320x240,
// PSNR against the mesh reference: 25.54 and 25.45 dB, where the depth-8 bake has 25.74; make
// bench-views). tests/gen/suite.sh checks the levels against shallower bakes.
void drop_orphans(const std::unordered_map<uint64_t, Cell> &parents, std::unordered_map<uint64_t, Cell> &cells) {
    for (auto it = cells.begin(); it != cells.end();)
        it = parents.count(it->first >> 3) ? std::next(it) : cells.erase(it);
}

void adopt(const std::unordered_map<uint64_t, Cell> &parents, const GridCube &cube, int parent_level,
           std::unordered_map<uint64_t, Cell> &cells) {
    const double side = cube.cell(parent_level);
    for (const auto &kv : parents) {
        bool any = false;
        for (uint64_t k = 0; k < 8 && !any; k++) any = cells.count(kv.first << 3 | k) != 0;
        if (any) continue;
        // the octant of the parent's cube its surface point lies in (the point itself may stand a
        // hair outside the cube: the nearest surface point to its samples' centroid)
        const auto idx = morton_decode(kv.first, parent_level);
        uint64_t octant = 0;
        for (int a = 0; a < 3; a++)
            if (kv.second.at[a] >= cube.origin[a] + (idx[a] + 0.5) * side) octant |= uint64_t{1} << a;
        cells.emplace(kv.first << 3 | octant, kv.second);
    }
}

// The colours of cells in ascending code order.
std::vector<std::array<double, 3>> colours_in_order(const std::unordered_map<uint64_t, Cell> &cells) {
    std::vector<uint64_t> codes;
    codes.reserve(cells.size());
    for (const auto &kv : cells) codes.push_back(kv.first);
    std::sort(codes.begin(), codes.end());
    std::vector<std::array<double, 3>> rgb;
    rgb.reserve(codes.size());
    for (uint64_t c : codes) {
        const Cell &cell = cells.at(c);
        rgb.push_back({cell.extra[0], cell.extra[1], cell.extra[2]});
    }
    return rgb;
}

// The cells of the bake's depth, sampled and shaded; deeper than kSampledLevel, level by level from
// it (drop_orphans, adopt), the colours of the levels above the leaves in level_rgb.
void voxelize_mesh(const Model &m, const std::string &file, const GridCube &cube, const VoxelOptions &opt,
                   Progress &progress, std::unordered_map<uint64_t, Cell> &cells, uint64_t &samples,
                   std::vector<std::vector<std::array<double, 3>>> &level_rgb) {
    Mesh mesh = to_cgal(m);
    if (mesh.number_of_faces() == 0)
        throw InputError(file, InputError::Where::none, 0, "no triangle can be built from the faces (non-manifold?)");
    const int first = std::min(opt.depth, kSampledLevel);
    auto vnormal = mesh.add_property_map<Mesh::Vertex_index, Vector>("v:n", Vector(0, 0, 0)).first;
    PMP::compute_vertex_normals(mesh, vnormal);
    using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
    using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;
    Tree tree;
    PMP::build_AABB_tree(mesh, tree);
    std::unordered_map<uint64_t, Cell> parents;
    if (first < opt.depth) level_rgb.assign(opt.depth, {});
    for (int l = first; l <= opt.depth; l++) {
        progress.step("sampling");
        std::unordered_map<uint64_t, Cell> level;
        sample_level(mesh, Grid(cube, l), opt, progress, level, samples);
        if (l > first) drop_orphans(parents, level);   // before shading: dropped cells cost nothing
        progress.step("shading");
        shade_cells(m, mesh, tree, vnormal, progress, level);
        if (l > first) {
            adopt(parents, cube, l - 1, level);   // after: adopted cells come shaded, from their parents
            level_rgb[l - 1] = colours_in_order(parents);
        }
        parents = std::move(level);
    }
    cells = std::move(parents);
}

void voxelize_points(const Model &m, const GridCube &cube, const Grid &grid, const VoxelOptions &opt,
                     Progress &progress, std::unordered_map<uint64_t, Cell> &cells, uint64_t &samples,
                     std::vector<FilledCell> &filled, PointFill &fill) {
    // Without colours, shade by normals: the file's, or PCA estimates (point_normals).
    if (m.colors.empty() && m.normals.empty()) progress.step("estimating normals");
    const std::vector<std::array<double, 3>> normals = point_normals(m);
    progress.step("voxelizing");
    std::vector<std::array<double, 3>> colors(m.points.size());
    for (size_t i = 0; i < m.points.size(); i++) {
        const auto &p = m.points[i];
        Cell &c = cells[grid.code(p[0], p[1], p[2])];
        if (!m.colors.empty()) {
            for (int a = 0; a < 3; a++) colors[i][a] = m.colors[i][a];
        } else {
            double g = 255.0 * frontal_light(Vector(normals[i][0], normals[i][1], normals[i][2]));
            colors[i] = {g, g, g};
        }
        for (int a = 0; a < 3; a++) c.extra[a] += colors[i][a];
        c.count++;
        samples++;
        if ((i & 0xFFFF) == 0) progress.update(static_cast<double>(i), static_cast<double>(m.points.size()));
    }
    for (auto &kv : cells)
        for (int a = 0; a < 3; a++) kv.second.extra[a] /= kv.second.count;
    // sparse for the grid: the surface between the points (point_fill.hpp)
    fill.enabled = opt.point_fill;
    std::vector<uint64_t> occupied;
    if (fill.enabled) {
        progress.step("filling between points");
        occupied.reserve(cells.size());
        for (const auto &kv : cells) occupied.push_back(kv.first);
        std::sort(occupied.begin(), occupied.end());
    }
    filled = fill_points(m, colors, normals, cube, opt.depth, occupied, fill, progress);
}

}  // namespace

uint64_t morton_encode(uint32_t x, uint32_t y, uint32_t z, int depth) {
    uint64_t code = 0;
    for (int b = depth - 1; b >= 0; b--)
        code = (code << 3) | (((z >> b) & 1u) << 2) | (((y >> b) & 1u) << 1) | ((x >> b) & 1u);
    return code;
}

std::array<uint32_t, 3> morton_decode(uint64_t code, int depth) {
    std::array<uint32_t, 3> c{0, 0, 0};
    for (int b = depth - 1; b >= 0; b--)
        for (int a = 0; a < 3; a++) c[a] |= static_cast<uint32_t>((code >> (3 * b + a)) & 1u) << b;
    return c;
}

Voxels voxelize(const Model &model, const GridCube &cube, const std::string &file, const VoxelOptions &opt,
                Progress &progress) {
    Grid grid(cube, opt.depth);   // point sets
    std::unordered_map<uint64_t, Cell> cells;
    Voxels out;
    out.depth = opt.depth;
    out.origin = grid.origin();
    out.cell = grid.cell();
    std::vector<FilledCell> filled;   // point sets: cells between sparse points, ascending
    if (model.is_mesh)
        voxelize_mesh(model, file, cube, opt, progress, cells, out.samples, out.level_rgb);
    else
        voxelize_points(model, cube, grid, opt, progress, cells, out.samples, filled, out.fill);
    if (cells.empty()) throw InputError(file, InputError::Where::none, 0, "no sample landed in the grid");
    out.codes.reserve(cells.size() + filled.size());
    for (const auto &kv : cells) out.codes.push_back(kv.first);
    std::sort(out.codes.begin(), out.codes.end());  // hash order is not deterministic across libraries
    out.rgb.reserve(out.codes.size());
    for (uint64_t c : out.codes) {
        const Cell &cell = cells.at(c);
        out.rgb.push_back({cell.extra[0], cell.extra[1], cell.extra[2]});
        if (model.is_mesh) out.surface.push_back({cell.at[0], cell.at[1], cell.at[2]});
    }
    if (!filled.empty()) {   // merged in code order: both lists are ascending and disjoint
        std::vector<uint64_t> codes;
        std::vector<std::array<double, 3>> rgb;
        codes.reserve(out.codes.size() + filled.size());
        rgb.reserve(codes.capacity());
        size_t i = 0, j = 0;
        while (i < out.codes.size() || j < filled.size()) {
            if (j == filled.size() || (i < out.codes.size() && out.codes[i] < filled[j].code))
                codes.push_back(out.codes[i]), rgb.push_back(out.rgb[i]), i++;
            else
                codes.push_back(filled[j].code), rgb.push_back(filled[j].rgb), j++;
        }
        out.codes = std::move(codes);
        out.rgb = std::move(rgb);
    }
    return out;
}

}  // namespace mc
