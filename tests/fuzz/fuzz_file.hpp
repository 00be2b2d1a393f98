// The temporary directory a fuzz target writes each input to, as input.EXT because the generator
// chooses the reader by the extension: one per process (libFuzzer's -jobs/-fork workers each get
// their own), removed at exit.
#pragma once
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

namespace mc_fuzz {

class TempInput {
public:
    TempInput() {
        const char *t = std::getenv("TMPDIR");
        dir_ = std::string(t && *t ? t : "/tmp") + "/modelc-fuzz." + std::to_string(getpid());
        std::filesystem::create_directories(dir_);
    }
    ~TempInput() {
        std::error_code ec;
        std::filesystem::remove_all(dir_, ec);
    }
    const std::string &dir() const { return dir_; }
    // Writes DIR/input.EXT and returns its path.
    std::string write(const std::string &ext, const uint8_t *data, size_t size) const {
        std::string path = dir_ + "/input." + ext;
        FILE *f = std::fopen(path.c_str(), "wb");
        if (!f || (size && std::fwrite(data, 1, size, f) != size) || std::fclose(f) != 0) {
            std::perror(path.c_str());
            std::abort();  // the harness itself failed: not the generator's fault, but never silent
        }
        return path;
    }

private:
    std::string dir_;
};

}  // namespace mc_fuzz
