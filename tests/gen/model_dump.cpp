// Prints the model mc::load_model() reads from each FILE, one line per point, per triangle and per
// tracking line (coordinates in hexadecimal floating point, so equal text means equal bits), or the
// error line. The line count is printed only when there are lines (CAO), so the other formats'
// dumps read as they always did.
// Used by readers.sh to compare files that must give the same model.
#include <cstdio>

#include "model.hpp"

int main(int argc, char **argv) {
    for (int i = 1; i < argc; ++i) {
        try {
            const mc::Model m = mc::load_model(argv[i]);
            std::printf("%s points %zu triangles %zu colours %zu normals %zu", m.is_mesh ? "mesh" : "point set",
                        m.points.size(), m.tris.size(), m.colors.size(), m.normals.size());
            if (!m.lines.empty()) std::printf(" lines %zu", m.lines.size());
            std::printf("\n");
            for (size_t k = 0; k < m.points.size(); ++k) {
                std::printf("v %a %a %a", m.points[k][0], m.points[k][1], m.points[k][2]);
                if (!m.colors.empty()) std::printf(" rgb %d %d %d", m.colors[k][0], m.colors[k][1], m.colors[k][2]);
                if (!m.normals.empty()) std::printf(" n %a %a %a", m.normals[k][0], m.normals[k][1], m.normals[k][2]);
                std::printf("\n");
            }
            for (const auto &t : m.tris) std::printf("f %u %u %u\n", t[0], t[1], t[2]);
            for (const auto &l : m.lines) std::printf("l %u %u\n", l[0], l[1]);
        } catch (const mc::InputError &e) {
            std::printf("modelc: %s\n", e.line().c_str());
            return 1;
        }
    }
    return 0;
}
