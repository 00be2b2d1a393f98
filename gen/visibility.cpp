// Hidden-cell removal (--views): see visibility.hpp.
#include "visibility.hpp"
#include "modelc/depth.h"

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <regex>
#include <stdexcept>
#include <thread>
#include <unordered_map>

namespace mc {
namespace {

using Dir = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

double parse_number(const std::string &s, double lo, double hi, const std::string &what) {
    static const std::regex number("[-+]?([0-9]+(\\.[0-9]*)?|\\.[0-9]+)");
    if (!std::regex_match(s, number)) throw std::invalid_argument(what + " '" + s + "' is not a number");
    double v = std::stod(s);
    if (!(v >= lo && v <= hi))
        throw std::invalid_argument(what + " " + s + " is outside " + std::to_string(static_cast<int>(lo)) + ".." +
                                    std::to_string(static_cast<int>(hi)));
    return v;
}

std::vector<std::string> split(const std::string &s, char sep) {
    std::vector<std::string> out(1);
    for (char c : s)
        if (c == sep) out.emplace_back();
        else out.back().push_back(c);
    return out;
}

unsigned worker_count() { return std::max(1u, std::min(8u, std::thread::hardware_concurrency())); }

// Runs work(block, worker) for blocks 0..n-1 on worker_count() threads (worker 0 is the calling
// thread, which also reports progress). Blocks are independent, so the result never depends on the
// schedule.
template <class Work>
void parallel_blocks(size_t n, Progress &progress, Work work) {
    std::atomic<size_t> next{0}, done{0};
    auto run = [&](unsigned worker) {
        for (size_t b; (b = next++) < n;) {
            work(b, worker);
            size_t d = ++done;
            if (worker == 0) progress.update(static_cast<double>(d), static_cast<double>(n));
        }
    };
    std::vector<std::thread> pool;
    try {
        for (unsigned i = 1; i < worker_count(); i++) pool.emplace_back(run, i);
    } catch (const std::system_error &) {
        // no more threads: the ones started and this one do the work
    }
    run(0);
    for (auto &t : pool) t.join();
}

// ---- which cells a direction needs ------------------------------------------------------------
//
// A cell is needed for direction d when (1) no nearer cell of the model covers it: none whose centre
// projects within kCoverCells of its own centre (the renderer draws one pixel per cell at zoom 1,
// so such a cell takes its place), tested with a z-buffer-like binning of the projected centres at
// the octree's resolution; and, for meshes, (2) its point on the original surface is not hidden by
// the surface: a ray from it toward the viewer meets no triangle (CGAL AABB tree) beyond
// kEpsilonCells. (1) removes the cells of the voxelized surface that lie behind other cells of the
// same surface, which rays from the surface itself cannot see; (2) removes cells seen through the
// gaps between cells, behind nearer parts of the surface. Point sets have only (1).

using K = CGAL::Simple_cartesian<double>;
using Triangle = K::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<K, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<K, Primitive>>;

// A nearer cell whose centre projects within this distance (in cells, across the view) covers a
// cell: sqrt(2)/2, the largest radius at which a flat layer of cells seen head-on does not cover
// itself (neighbours are 1 apart) and the smallest at which discs around its centres leave no gap,
// so cells behind a layer are covered however it is turned. Measured on bunny00 front:60 (DEPTH 8):
// 0.5 keeps cells no view needs and never levels off (21.5, 18.1, 16.2 % removed at 100, 400, 1600
// directions); sqrt(2)/2 levels off (32.3, 31.1, 31.0 %); 1.0 covers head-on layers too.
// Cost: a covered cell's cover may itself be covered, so in a turned view a removed cell is not
// always replaced by a kept one next to it: grazing surfaces near the rim of the views thin out
// (requiring a kept cover in every view, tried too, removes only 13.5-14.6 %, no more than the rays).
constexpr double kCoverCells = 0.70710678118654752;

// Rays start this far out from the cell's surface point, along the ray, so that the triangles around
// the point itself (and the rest of the cell's own patch of surface) do not count as occluders; a
// surface less than a cell in front of a cell does not hide it, which only ever keeps a cell.
constexpr double kEpsilonCells = 1.0;

struct Scene {
    const Voxels &vox;
    std::vector<Dir> centre;  // cell centres, in cells
    const Tree *tree = nullptr;
    double cover = kCoverCells;  // the cover radius, in cells
};

// The typical distance between neighbouring cells, in cells: the median distance from a cell to its
// nearest other cell (over at most 20000 cells, evenly spread in Morton order), at least 1. Dense
// surfaces (every voxelized mesh) give 1; a sparse point set more, and its cells' cover grows with
// it, since its points stand for a surface sampled that coarsely.
double cell_spacing(const Voxels &vox) {
    const size_t n = vox.codes.size(), step = std::max<size_t>(1, n / 20000);
    const int reach = 8;
    std::vector<double> nearest;
    for (size_t i = 0; i < n; i += step) {
        const auto c = morton_decode(vox.codes[i], vox.depth);
        double best = INFINITY;
        for (int r = 1; r <= reach && best > r; r++)  // shells of growing Chebyshev radius
            for (int dz = -r; dz <= r; dz++)
                for (int dy = -r; dy <= r; dy++)
                    for (int dx = -r; dx <= r; dx++) {
                        if (std::max({std::abs(dx), std::abs(dy), std::abs(dz)}) != r) continue;
                        const int64_t x = int64_t(c[0]) + dx, y = int64_t(c[1]) + dy, z = int64_t(c[2]) + dz;
                        const int64_t side = int64_t(1) << vox.depth;
                        if (x < 0 || y < 0 || z < 0 || x >= side || y >= side || z >= side) continue;
                        const uint64_t code = morton_encode(uint32_t(x), uint32_t(y), uint32_t(z), vox.depth);
                        if (std::binary_search(vox.codes.begin(), vox.codes.end(), code))
                            best = std::min(best, std::sqrt(double(dx * dx + dy * dy + dz * dz)));
                    }
        nearest.push_back(std::min(best, double(reach)));
    }
    if (nearest.empty()) return 1;
    std::nth_element(nearest.begin(), nearest.begin() + static_cast<long>(nearest.size() / 2), nearest.end());
    return std::max(1.0, nearest[nearest.size() / 2]);
}

// Marks in seen[] the cells direction d needs (skipping cells already marked). bins and order are
// the worker's scratch space.
void one_direction(const Scene &s, const Dir &d, std::vector<uint8_t> &seen, std::vector<uint32_t> &bins,
                   std::vector<uint32_t> &order, std::vector<uint32_t> &next, std::vector<std::array<double, 3>> &proj) {
    const size_t n = s.centre.size();
    const double r = s.cover;
    // screen axes u = up x d, v = d x u (x and y at the front); up is z when looking along y
    Dir u = std::hypot(d[0], d[2]) > 1e-9 ? Dir{d[2], 0, -d[0]} : Dir{1, 0, 0};
    double len = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
    for (double &x : u) x /= len;
    const Dir v = {d[1] * u[2] - d[2] * u[1], d[2] * u[0] - d[0] * u[2], d[0] * u[1] - d[1] * u[0]};
    auto dot = [](const Dir &a, const Dir &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; };
    // bins of side r: every centre within r of a point lies in its bin or the eight around it
    proj.resize(n);
    double lo_u = INFINITY, lo_v = INFINITY, hi_u = -INFINITY, hi_v = -INFINITY;
    for (size_t i = 0; i < n; i++) {
        proj[i] = {dot(s.centre[i], u) / r, dot(s.centre[i], v) / r, dot(s.centre[i], d)};
        lo_u = std::min(lo_u, proj[i][0]), hi_u = std::max(hi_u, proj[i][0]);
        lo_v = std::min(lo_v, proj[i][1]), hi_v = std::max(hi_v, proj[i][1]);
    }
    const int64_t w = static_cast<int64_t>(hi_u - lo_u) + 3, h = static_cast<int64_t>(hi_v - lo_v) + 3;
    auto bin_of = [&](size_t i) {
        return (static_cast<int64_t>(proj[i][1] - lo_v) + 1) * w + static_cast<int64_t>(proj[i][0] - lo_u) + 1;
    };
    // counting sort of the cells by bin: bins[b]..bins[b+1] index order[]
    bins.assign(static_cast<size_t>(w * h + 1), 0);
    for (size_t i = 0; i < n; i++) bins[static_cast<size_t>(bin_of(i)) + 1]++;
    for (size_t b = 1; b < bins.size(); b++) bins[b] += bins[b - 1];
    order.resize(n);
    next.assign(bins.begin(), bins.end() - 1);
    for (size_t i = 0; i < n; i++) order[next[static_cast<size_t>(bin_of(i))]++] = static_cast<uint32_t>(i);
    // Does a nearer cell lie within r of cell i across the view?
    auto covered = [&](size_t i) {
        const int64_t b = bin_of(i);
        for (int64_t dy = -w; dy <= w; dy += w)
            for (int64_t dx = -1; dx <= 1; dx++) {
                const size_t nb = static_cast<size_t>(b + dy + dx);
                for (uint32_t k = bins[nb]; k < bins[nb + 1]; k++) {
                    const auto &q = proj[order[k]];
                    const double du = q[0] - proj[i][0], dv = q[1] - proj[i][1];
                    if (q[2] > proj[i][2] && du * du + dv * dv < 1.0) return true;
                }
            }
        return false;
    };
    for (size_t i = 0; i < n; i++) {
        if (seen[i] || covered(i)) continue;
        if (s.tree) {
            const auto &p = s.vox.surface[i];
            const double eps = kEpsilonCells * s.vox.cell;
            K::Point_3 o(p[0] + eps * d[0], p[1] + eps * d[1], p[2] + eps * d[2]);
            if (s.tree->do_intersect(K::Ray_3(o, K::Vector_3(d[0], d[1], d[2])))) continue;
        }
        seen[i] = 1;
    }
}

void merge_views(const Model &model, const Voxels &vox, const std::vector<Dir> &dirs, Progress &progress,
                 std::vector<uint8_t> &keep) {
    Scene s{vox, {}, nullptr};
    s.centre.resize(vox.codes.size());
    for (size_t i = 0; i < vox.codes.size(); i++) {
        auto c = morton_decode(vox.codes[i], vox.depth);
        s.centre[i] = {c[0] + 0.5, c[1] + 0.5, c[2] + 0.5};
    }
    s.cover = kCoverCells * cell_spacing(vox);
    std::vector<Triangle> tris;
    Tree tree;
    if (!vox.surface.empty()) {
        tris.reserve(model.tris.size());
        for (const auto &t : model.tris) {
            const auto &a = model.points[t[0]], &b = model.points[t[1]], &c = model.points[t[2]];
            Triangle tri(K::Point_3(a[0], a[1], a[2]), K::Point_3(b[0], b[1], b[2]), K::Point_3(c[0], c[1], c[2]));
            if (!tri.is_degenerate()) tris.push_back(tri);
        }
        if (!tris.empty()) {
            tree.insert(tris.begin(), tris.end());
            tree.build();  // before the threads: queries on a built tree only read it
            s.tree = &tree;
        }
    }
    // per worker: the cells it found needed (ORed at the end, so the schedule does not matter) and
    // its scratch space
    const unsigned workers = worker_count();
    std::vector<std::vector<uint8_t>> seen(workers, std::vector<uint8_t>(vox.codes.size(), 0));
    std::vector<std::vector<uint32_t>> bins(workers), order(workers), next(workers);
    std::vector<std::vector<std::array<double, 3>>> proj(workers);
    parallel_blocks(dirs.size(), progress, [&](size_t j, unsigned w) {
        one_direction(s, dirs[j], seen[w], bins[w], order[w], next[w], proj[w]);
    });
    for (const auto &sw : seen)
        for (size_t i = 0; i < keep.size(); i++) keep[i] |= sw[i];
}

// ---- the frontal view's winners ------------------------------------------------------------------

// With yaw = pitch = roll = 0 the runtime's rotation is exactly the identity, so a cell's pixel
// depends only on its x and y and its depth only on its z (nearer for larger z): every column of
// cells lands on one pixel. The pixel shows the nearest cell of the columns landing there, the first
// drawn (Morton order) on equal depth. Keeping the front cell of every column therefore keeps every
// winner, at every screen size, zoom and translation, and with the same depth buffer any finishing
// gives the same result. The same holds at each coarser level l for the front node of each level-l
// column, which needs one kept leaf under it.
//
// Depth-buffer rounding: a leaf's orthographic depth is a sum of d per-level vectors each rounded
// once (octree_render.c setup_vectors), so it is off by at most d/2 units, while neighbouring cells of a
// column lie A / 2^d units apart, A = the cube's side in depth units >= kDepthSpanMin / sqrt(3) (the
// bounding sphere's 2 * radius = sqrt(3) A spans at least kDepthSpanMin units). Cells further than
// d 2^d / A cells behind the front one can never tie with it: for d <= 10 only the front cell can
// win, for d = 11 and 12 the next one or two cells are kept too (any screen whose model cube is at
// least one pixel wide: only then does the bound on A hold).
constexpr double kDepthSpanMin = MC_DEPTH_SPAN / 2;   // modelc/depth.h

size_t keep_frontal(const Voxels &vox, std::vector<uint8_t> &keep) {
    const int D = vox.depth;
    const size_t n = vox.codes.size();
    std::vector<std::array<uint32_t, 3>> xyz(n);
    for (size_t i = 0; i < n; i++) xyz[i] = morton_decode(vox.codes[i], D);
    size_t added = 0;
    for (int l = D; l >= 1; l--) {
        const int shift = D - l;
        const uint32_t slack = static_cast<uint32_t>(std::floor(l * std::ldexp(1.0, l) / (kDepthSpanMin / std::sqrt(3.0))));
        auto column = [&](size_t i) { return (uint64_t(xyz[i][0] >> shift) << 32) | (xyz[i][1] >> shift); };
        std::unordered_map<uint64_t, uint32_t> front;
        front.reserve(n);
        for (size_t i = 0; i < n; i++) {
            auto it = front.emplace(column(i), 0).first;
            it->second = std::max(it->second, xyz[i][2] >> shift);
        }
        // a node's leaves are a run of consecutive codes
        for (size_t a = 0, b; a < n; a = b) {
            const uint64_t key = vox.codes[a] >> (3 * shift);
            for (b = a + 1; b < n && (vox.codes[b] >> (3 * shift)) == key; b++) {}
            if ((xyz[a][2] >> shift) + slack < front.at(column(a))) continue;
            if (std::any_of(keep.begin() + static_cast<long>(a), keep.begin() + static_cast<long>(b),
                            [](uint8_t k) { return k != 0; }))
                continue;
            size_t best = a;  // its front leaf
            for (size_t i = a + 1; i < b; i++)
                if (xyz[i][2] > xyz[best][2]) best = i;
            keep[best] = 1;
            added++;
        }
    }
    return added;
}

}  // namespace

ViewSpec parse_views(const std::string &spec) {
    ViewSpec out;
    out.text = spec;
    if (spec == "all") return out;
    out.all = false;
    if (spec.empty()) throw std::invalid_argument("empty; expected all, front:DEG, YAW:PITCH or YAW:PITCH:DEG");
    for (const std::string &item : split(spec, ',')) {
        if (item == "all") throw std::invalid_argument("all cannot be combined with other directions");
        std::string body = item;
        ViewSpec::Cone cone;
        auto at = item.find('@');
        if (at != std::string::npos) {
            body = item.substr(0, at);
            std::string count = item.substr(at + 1);
            if (!std::regex_match(count, std::regex("[0-9]{1,6}")) || std::stoi(count) < 1 || std::stoi(count) > 100000)
                throw std::invalid_argument("direction count '@" + count + "' in '" + item + "' must be 1..100000");
            cone.count = std::stoi(count);
        }
        auto parts = split(body, ':');
        if (parts.size() == 2 && parts[0] == "front") {
            cone.deg = parse_number(parts[1], 0, 180, "angle");
        } else if (parts.size() == 2 || parts.size() == 3) {
            cone.yaw = parse_number(parts[0], -1e6, 1e6, "yaw");
            cone.pitch = parse_number(parts[1], -1e6, 1e6, "pitch");
            if (parts.size() == 3) cone.deg = parse_number(parts[2], 0, 180, "angle");
        } else {
            throw std::invalid_argument("'" + item + "' is not one of all, front:DEG, YAW:PITCH, YAW:PITCH:DEG");
        }
        out.cones.push_back(cone);
    }
    return out;
}

// How many directions: the kept cells grow with the number of directions sampled (a cell needed only
// in a narrow range of views needs a direction inside it) and level off. bunny00, DEPTH 8, front:60:
// 32.3 % removed with 100 directions, 31.1 % with 400, 31.0 % with 1600 (0.1 point, 235 cells,
// for four times the work), so 400 per 60-degree cone (neighbours about 5 degrees apart), in 5 s.
int cone_directions(double deg) {
    if (deg <= 0) return 1;
    double share = (1 - std::cos(deg * kPi / 180)) / (1 - std::cos(60 * kPi / 180));
    return std::max(1, static_cast<int>(std::lround(kFrontDirections * share)));
}

std::vector<Dir> view_directions(const ViewSpec &spec) {
    std::vector<Dir> out;
    const double golden = kPi * (3 - std::sqrt(5.0));
    for (const auto &cone : spec.cones) {
        const int n = cone.deg <= 0 ? 1 : cone.count > 0 ? cone.count : cone_directions(cone.deg);
        const double cos_cap = std::cos(cone.deg * kPi / 180);
        const double y = cone.yaw * kPi / 180, p = cone.pitch * kPi / 180;
        const double cy = std::cos(y), sy = std::sin(y), cp = std::cos(p), sp = std::sin(p);
        for (int i = 0; i < n; i++) {
            // Fibonacci points on the cap around +z: i = 0 the axis, i = n-1 on the rim
            double z = n == 1 ? 1.0 : 1 - (1 - cos_cap) * i / (n - 1);
            double r = std::sqrt(std::max(0.0, 1 - z * z)), phi = golden * i;
            Dir a = {r * std::cos(phi), r * std::sin(phi), z};
            // to model space: R^T a with R = Rx(pitch) Ry(yaw), the runtime's rotation without roll
            Dir b = {a[0], cp * a[1] + sp * a[2], -sp * a[1] + cp * a[2]};
            out.push_back({cy * b[0] - sy * b[2], b[1], sy * b[0] + cy * b[2]});
        }
    }
    return out;
}

std::vector<uint8_t> visible_cells(const Model &model, const Voxels &vox, const std::vector<Dir> &dirs,
                                   Progress &progress, PruneStats &stats) {
    std::vector<uint8_t> keep(vox.codes.size(), 0);
    merge_views(model, vox, dirs, progress, keep);
    stats.directions = dirs.size();
    stats.cells_before = vox.codes.size();
    stats.kept_for_front = keep_frontal(vox, keep);
    stats.cells_removed = static_cast<size_t>(std::count(keep.begin(), keep.end(), 0));
    return keep;
}

std::string pruning_json(const ViewSpec &spec, const PruneStats &st) {
    nlohmann::json j = {{"views", spec.text},
                        {"directions", st.directions},
                        {"cells_before", st.cells_before},
                        {"cells_removed", st.cells_removed},
                        {"kept_for_front", st.kept_for_front}};
    return j.dump();
}

std::string pruning_report(const ViewSpec &spec, const PruneStats &st) {
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.1f", st.cells_before ? 100.0 * st.cells_removed / st.cells_before : 0.0);
    return "--views " + spec.text + ": removed " + std::to_string(st.cells_removed) + " of " +
           std::to_string(st.cells_before) + " cells (" + pct + " %) hidden from all " +
           std::to_string(st.directions) + " directions";
}

}  // namespace mc
