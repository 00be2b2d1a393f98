// A mesh reference for a point set the catalogue has no mesh of (tests/points/suite.sh):
//
//   reconstruct POINTS_DUMP MESH_DUMP
//
// reads `modelc SET --dump-reference POINTS_DUMP` (runtime/ref/mesh_ref.h: the points in the unit
// cube of the set's grid) and writes MESH_DUMP in the same format and the same cube: the surface
// CGAL's advancing-front reconstruction interpolates through the points (every point a vertex, the
// triangles its Delaunay-based front picks; a closed scan such as the kitten comes out closed).
// Normals are left zero (the mesh reference then shades a flat grey; the suite uses its coverage
// and depth only). Exit 0, or 1 with one line on stderr.
#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <vector>

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

int main(int argc, char **argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: reconstruct POINTS_DUMP MESH_DUMP\n");
        return 1;
    }
    std::FILE *f = std::fopen(argv[1], "rb");
    char magic[8];
    uint32_t hdr[4];
    double g[5];
    if (!f || std::fread(magic, 1, 8, f) != 8 || std::memcmp(magic, "MCREF01\n", 8) != 0 || std::fread(hdr, 4, 4, f) != 4 ||
        std::fread(g, 8, 5, f) != 5 || hdr[0] != 1 || hdr[2] < 4) {
        std::fprintf(stderr, "reconstruct: %s: not a point set's reference dump\n", argv[1]);
        return 1;
    }
    std::vector<K::Point_3> pts;
    pts.reserve(hdr[2]);
    for (uint32_t i = 0; i < hdr[2]; i++) {
        double rec[9];
        if (std::fread(rec, 8, 9, f) != 9) {
            std::fprintf(stderr, "reconstruct: %s: truncated\n", argv[1]);
            return 1;
        }
        pts.emplace_back(rec[0], rec[1], rec[2]);
    }
    std::fclose(f);
    std::vector<std::array<std::size_t, 3>> facets;
    CGAL::advancing_front_surface_reconstruction(pts.begin(), pts.end(), std::back_inserter(facets));
    std::FILE *o = std::fopen(argv[2], "wb");
    if (!o) {
        std::fprintf(stderr, "reconstruct: %s: cannot write\n", argv[2]);
        return 1;
    }
    const uint32_t out_hdr[4] = {0, 1, hdr[2], static_cast<uint32_t>(facets.size())};   // a mesh, shaded
    g[4] = 0;                                                                              // no splat radius
    std::fwrite("MCREF01\n", 1, 8, o);
    std::fwrite(out_hdr, 4, 4, o);
    std::fwrite(g, 8, 5, o);
    for (const auto &p : pts) {
        const double rec[9] = {p.x(), p.y(), p.z(), 0, 0, 0, 0, 0, 0};
        std::fwrite(rec, 8, 9, o);
    }
    for (const auto &t : facets) {
        const uint32_t tri[3] = {static_cast<uint32_t>(t[0]), static_cast<uint32_t>(t[1]), static_cast<uint32_t>(t[2])};
        std::fwrite(tri, 4, 3, o);
    }
    if (std::fclose(o) != 0) {
        std::fprintf(stderr, "reconstruct: %s: write failed\n", argv[2]);
        return 1;
    }
    std::printf("%zu points, %zu triangles\n", pts.size(), facets.size());
    return 0;
}
