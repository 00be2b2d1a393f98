// The OpenMesh side of the progressive-mesh benchmark (tests/bench/pmesh.sh): the same decimation as
// modelc's (quadric error, no normal flips, to one vertex) recorded by OpenMesh's own ModProgMeshT
// and written as its .pm file; then that file read back as OpenMesh's ProgViewer app does (every
// vertex added, the base faces, then vertex splits and collapses on the half-edge mesh) and timed.
//
// usage: openmesh_pm MESH.off OUT.pm ROUNDS     decimate, write OUT.pm, then time it
//        openmesh_pm --read FILE.pm ROUNDS     time a .pm written before
// prints: "pm bytes N", "splits N", then per round "ns per level change X" (a full refinement from
// the base and a full coarsening back, over their 2 * splits changes), and checks the face count
// of the full level (the base faces plus one per wing vertex of each split).
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModNormalFlippingT.hh>
#include <OpenMesh/Tools/Decimater/ModProgMeshT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <vector>

struct Traits : OpenMesh::DefaultTraits {
    VertexAttributes(OpenMesh::Attributes::Status);
    EdgeAttributes(OpenMesh::Attributes::Status);
    FaceAttributes(OpenMesh::Attributes::Status | OpenMesh::Attributes::Normal);
};
using Mesh = OpenMesh::TriMesh_ArrayKernelT<Traits>;

int main(int argc, char **argv) {
    if (argc != 4) { std::fprintf(stderr, "usage: openmesh_pm MESH.off OUT.pm ROUNDS\n"); return 2; }
    const int rounds = std::atoi(argv[3]);
    if (std::strcmp(argv[1], "--read")) {
        Mesh m;
        if (!OpenMesh::IO::read_mesh(m, argv[1])) { std::fprintf(stderr, "cannot read %s\n", argv[1]); return 1; }
        m.request_face_normals();
        m.update_face_normals();
        OpenMesh::Decimater::DecimaterT<Mesh> d(m);
        OpenMesh::Decimater::ModQuadricT<Mesh>::Handle q;
        OpenMesh::Decimater::ModNormalFlippingT<Mesh>::Handle f;
        OpenMesh::Decimater::ModProgMeshT<Mesh>::Handle p;
        d.add(q), d.add(f), d.add(p);
        d.module(q).unset_max_err();
        d.initialize();
        d.decimate_to(1);
        if (!d.module(p).write(argv[2])) { std::fprintf(stderr, "cannot write %s\n", argv[2]); return 1; }
    }
    // read the .pm back (OpenMesh's format: "ProgMesh", base vertices, base faces, splits, then
    // float positions, base faces as three uint32, and per split v0's position, v1, vl, vr)
    std::ifstream in(argv[2], std::ios::binary);
    std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const char *at = bytes.data() + 8;
    auto u32 = [&] { uint32_t v; std::memcpy(&v, at, 4); at += 4; return v; };
    auto f32 = [&] { float v; std::memcpy(&v, at, 4); at += 4; return v; };
    const uint32_t nv = u32(), nf = u32(), ns = u32();
    std::printf("pm bytes %zu\nsplits %u\n", bytes.size(), ns);
    Mesh m;
    std::vector<Mesh::VertexHandle> vh;
    for (uint32_t i = 0; i < nv; i++) { float x = f32(), y = f32(), z = f32(); vh.push_back(m.add_vertex({x, y, z})); }
    for (uint32_t i = 0; i < nf; i++) { uint32_t a = u32(), b = u32(), c = u32(); m.add_face(vh[a], vh[b], vh[c]); }
    struct Split { Mesh::VertexHandle v0, v1, vl, vr; };
    std::vector<Split> sp;
    size_t full_faces = nf;
    for (uint32_t i = 0; i < ns; i++) {
        float x = f32(), y = f32(), z = f32();
        uint32_t v1 = u32(), vl = u32(), vr = u32();
        Mesh::VertexHandle v0 = m.add_vertex({x, y, z});
        vh.push_back(v0);
        sp.push_back({v0, vh[v1], vl == UINT32_MAX ? Mesh::VertexHandle() : vh[vl], vr == UINT32_MAX ? Mesh::VertexHandle() : vh[vr]});
        full_faces += (vl != UINT32_MAX) + (vr != UINT32_MAX);
    }
    for (int r = 0; r < rounds; r++) {
        auto t0 = std::chrono::steady_clock::now();
        for (const Split &s : sp) m.vertex_split(s.v0, s.v1, s.vl, s.vr);
        auto t1 = std::chrono::steady_clock::now();
        size_t faces = 0;   /* not timed */
        for (auto f : m.faces()) faces += !m.status(f).deleted();
        auto t1b = std::chrono::steady_clock::now();
        for (size_t i = sp.size(); i-- > 0;) m.collapse(m.find_halfedge(sp[i].v0, sp[i].v1));
        auto t2 = std::chrono::steady_clock::now();
        if (faces != full_faces) { std::fprintf(stderr, "full level has %zu faces, the file %zu\n", faces, full_faces); return 1; }
        std::printf("ns per level change %.2f\n",
                    std::chrono::duration<double, std::nano>((t1 - t0) + (t2 - t1b)).count() / (2.0 * sp.size()));
    }
    return 0;
}
