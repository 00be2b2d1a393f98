// libFuzzer target for one reader: the input bytes become a file with the reader's extension
// (MC_FUZZ_EXT, set at compile time) and go through mc::load_model, the generator's only entry
// point for input files.
//
// Promise: an InputError is the expected answer to a bad file and is not a finding. Anything else
// that escapes (another exception, a crash, a sanitizer report, an abort such as a failed CGAL
// assertion, an allocation over libFuzzer's -malloc_limit_mb, an input over its -timeout) is.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "fuzz_file.hpp"
#include "model.hpp"

#ifndef MC_FUZZ_EXT
#error "compile with -DMC_FUZZ_EXT='\"off\"' (or obj, ply, stl, xyz)"
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    static const mc_fuzz::TempInput tmp;
    const std::string path = tmp.write(MC_FUZZ_EXT, data, size);
    try {
        mc::Model m = mc::load_model(path);
        // what the later stages rely on: every triangle names a point, colours and normals match
        for (const auto &t : m.tris)
            for (uint32_t i : t)
                if (i >= m.points.size()) std::abort();
        if (!m.colors.empty() && m.colors.size() != m.points.size()) std::abort();
        if (!m.normals.empty() && m.normals.size() != m.points.size()) std::abort();
    } catch (const mc::InputError &) {
    }
    return 0;
}
