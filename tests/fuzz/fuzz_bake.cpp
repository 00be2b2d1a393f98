// libFuzzer target for the whole bake on tiny inputs: reader, normalisation, voxelization at a
// small depth, visibility, octree and emit into a temporary directory, through the generator's
// own command line (gen/main.cpp compiled with its main renamed mc_fuzz_modelc_main, so this
// target follows however the stages are split into functions).
//
// Input layout: byte 0 chooses the format (kExt[(byte & 63) % 6]; a new format goes at the end, so
// bytes 0..4 keep theirs); with bit 6 set, --as both (the progressive mesh: OpenMesh's decimation
// of whatever topology the file has); with bit 7 set, --views front:40 (the visibility pass); the
// rest is the file. tests/fuzz/fuzz.sh stores a finding as regress/bake/NAME[.views][.mesh].EXT
// (the byte turned into the name), which tests/fuzz/suite.sh replays with the same options.
//
// Promise: the reader answers with the value or an InputError only (as in fuzz_reader.cpp), and
// the bake returns 0 or 1; a crash, sanitizer report, abort, allocation over -malloc_limit_mb or
// input over -timeout is a finding.
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz_file.hpp"
#include "model.hpp"

int mc_fuzz_modelc_main(int argc, char **argv);

namespace {
const char *const kExt[6] = {"off", "obj", "ply", "stl", "xyz", "cao"};
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    if (size < 1) return 0;
    static const mc_fuzz::TempInput tmp;
    const std::string path = tmp.write(kExt[(data[0] & 63) % 6], data + 1, size - 1);
    try {
        mc::load_model(path);
    } catch (const mc::InputError &) {
        return 0;  // the reader fuzzers cover what is wrong with the file
    }
    const std::string out = tmp.dir() + "/out";
    std::error_code ec;
    std::filesystem::remove_all(out, ec);
    std::vector<std::string> args = {"modelc", path, "-o", out, "--name", "m", "--depth", "5", "-q"};
    if (data[0] & 0x80) args.insert(args.end(), {"--views", "front:40"});
    if (data[0] & 0x40) args.insert(args.end(), {"--as", "both"});
    std::vector<char *> argv;
    for (auto &a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    int rc = mc_fuzz_modelc_main(static_cast<int>(args.size()), argv.data());
    if (rc != 0 && rc != 1) std::abort();  // 2 is a usage error: the harness is wrong
    if (rc == 1 && std::filesystem::exists(out + "/m")) std::abort();  // a failed bake leaves nothing
    return 0;
}
