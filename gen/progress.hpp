// Progress on a terminal for steps that take over a second; silent when stderr is not a terminal.
#pragma once
#include <chrono>
#include <cstdio>
#include <string>
#include <unistd.h>

namespace mc {

class Progress {
public:
    explicit Progress(bool quiet) : enabled_(!quiet && isatty(STDERR_FILENO)) {}
    // Starts a named step; its first report shows only once the step has run for a second.
    void step(const std::string &name) {
        finish();
        name_ = name;
        start_ = last_ = Clock::now();
        shown_ = false;
    }
    // done / total of the current step; cheap enough to call per item (prints at most 10 times a second).
    void update(double done, double total) {
        if (!enabled_) return;
        auto now = Clock::now();
        if (now - start_ < std::chrono::seconds(1) || now - last_ < std::chrono::milliseconds(100)) return;
        last_ = now;
        shown_ = true;
        std::fprintf(stderr, "\rmodelc: %s %3.0f%%", name_.c_str(), total > 0 ? 100.0 * done / total : 0.0);
        std::fflush(stderr);
    }
    void finish() {
        if (shown_) std::fprintf(stderr, "\rmodelc: %s done\n", name_.c_str());
        shown_ = false;
    }
    ~Progress() { finish(); }

private:
    using Clock = std::chrono::steady_clock;
    bool enabled_, shown_ = false;
    std::string name_;
    Clock::time_point start_, last_;
};

}  // namespace mc
