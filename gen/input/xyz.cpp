// XYZ reader: "x y z" or "x y z nx ny nz" per line, the same on every line, '#' comments, blank
// lines, and an optional point count alone on the first line, checked against the points that
// follow.
//
// Promise: reads the file once into a point set (see readers.hpp): coordinates and normals as
// double, in file order. A count on line 1 is a claim: it is checked, never used to reserve.
#include "input/numbers.hpp"
#include "input/readers.hpp"
#include "input/source.hpp"

namespace mc::input {
namespace {

class XyzReader {
public:
    XyzReader(ByteReader &in, const std::string &path) : path_(path), r_(in, path, true) {}

    Model run() {
        m_.is_mesh = false;
        while (r_.next_content()) {
            if (r_.line() == 1 && r_.tok().size() == 1 && announce()) continue;
            point();
        }
        if (announced_ >= 0 && m_.points.size() < static_cast<uint64_t>(announced_))
            r_.fail("file ends after " + num(m_.points.size()) + " of " + std::to_string(announced_) + " points");
        if (m_.points.empty()) fail_none(path_, "point set has no points");
        return std::move(m_);
    }

private:
    bool announce() {
        long long n = 0;
        const Num ok = parse_int(r_.tok()[0], n);
        if (ok == Num::bad) return false;
        if (ok == Num::range || n > static_cast<long long>(kMaxElements))
            r_.fail(std::string(r_.tok()[0]) + " points exceed the limit of " + kLimit);
        if (n < 0) r_.fail("negative point count " + std::string(r_.tok()[0]));
        announced_ = n;
        return true;
    }

    void point() {
        const Tokens &t = r_.tok();
        if (t.size() != 3 && t.size() != 6) r_.fail("expected 3 or 6 numbers (x y z [nx ny nz]), found " + num(t.size()));
        if (columns_ && t.size() != columns_)
            r_.fail("line has " + num(t.size()) + " numbers but earlier points have " + num(columns_));
        columns_ = t.size();
        if (announced_ >= 0 && m_.points.size() >= static_cast<uint64_t>(announced_))
            r_.fail("more points than the " + std::to_string(announced_) + " announced on line 1");
        if (m_.points.size() >= kMaxElements) r_.fail("more than " + kLimit + " points");
        std::array<double, 3> p, n;
        for (int k = 0; k < 3; ++k) p[k] = r_.coordinate(t[k]);
        m_.points.push_back(p);
        if (columns_ == 6) {
            for (int k = 0; k < 3; ++k) n[k] = r_.number(t[k + 3]);
            m_.normals.push_back(n);
        }
    }

    std::string path_;
    TextReader r_;
    Model m_;
    size_t columns_ = 0;
    long long announced_ = -1;
};

}  // namespace

Model read_xyz(const std::string &path, uint64_t) {
    ByteReader in(path);
    return XyzReader(in, path).run();
}

}  // namespace mc::input
