#include "input/source.hpp"

#include <algorithm>
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstring>

#include "input/numbers.hpp"

namespace mc::input {

using Where = InputError::Where;

void fail_none(const std::string &path, const std::string &msg) { throw InputError(path, Where::none, 0, msg); }

void fail_line(const std::string &path, long long line, const std::string &msg) {
    throw InputError(path, Where::line, line, msg);
}

void fail_byte(const std::string &path, uint64_t at, const std::string &msg) {
    throw InputError(path, Where::byte, static_cast<long long>(at), msg);
}

ByteReader::ByteReader(const std::string &path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) fail_none(path, std::string("cannot open: ") + std::strerror(errno));
}

size_t ByteReader::read(char *dst, size_t n) {
    size_t done = 0;
    while (done < n && fill()) {
        size_t k = std::min(n - done, end_ - pos_);
        std::memcpy(dst + done, buf_.data() + pos_, k);
        pos_ += k;
        offset_ += k;
        done += k;
    }
    return done;
}

bool ByteReader::line(std::string &out, bool &too_long) {
    out.clear();
    too_long = false;
    if (!fill()) return false;
    while (fill()) {
        const char *b = buf_.data() + pos_;
        const char *nl = static_cast<const char *>(std::memchr(b, '\n', end_ - pos_));
        size_t k = nl ? static_cast<size_t>(nl - b) : end_ - pos_;
        if (out.size() + k > kMaxLine) {
            too_long = true;
            return true;
        }
        out.append(b, k);
        pos_ += k + (nl ? 1 : 0);
        offset_ += k + (nl ? 1 : 0);
        if (nl) break;
    }
    return true;
}

bool ByteReader::fill() {
    if (pos_ < end_) return true;
    in_.read(buf_.data(), static_cast<std::streamsize>(buf_.size()));
    pos_ = 0;
    end_ = static_cast<size_t>(in_.gcount());
    if (in_.bad()) fail_none(path_, std::string("cannot read: ") + std::strerror(errno));
    return end_ > 0;
}

bool TextReader::next() {
    bool too_long = false;
    if (!in_.line(raw_, too_long)) return false;
    ++line_;
    if (too_long) fail("line is longer than " + num(kMaxLine) + " bytes (not a text file?)");
    split();
    return true;
}

bool TextReader::next_content() {
    while (next())
        if (!tok_.empty()) return true;
    return false;
}

void TextReader::split() {
    tok_.clear();
    std::string_view s(raw_);
    if (comments_) s = s.substr(0, s.find('#'));
    size_t i = 0;
    for (;;) {
        while (i < s.size() && is_space(s[i])) ++i;
        if (i == s.size()) break;
        size_t j = i;
        while (j < s.size() && !is_space(s[j])) ++j;
        tok_.push_back(s.substr(i, j - i));
        i = j;
    }
}

double TextReader::coordinate(std::string_view t) const {
    double v = 0;
    Num n = parse_double(t, v);
    if (n == Num::bad) fail("not a number: " + quote(t));
    if (n == Num::range) v = HUGE_VAL;
    if (const char *why = bad_coordinate(v)) fail(std::string(why) + ": " + quote(t));
    return v;
}

float TextReader::coordinate_f(std::string_view t) const {
    coordinate(t);  // the checks and their messages
    float f = 0;
    if (parse_float(t, f) != Num::ok) fail("coordinate is out of range (beyond float): " + quote(t));
    return f;
}

double TextReader::number(std::string_view t) const {
    double v = 0;
    Num n = parse_double(t, v);
    if (n == Num::bad) fail("not a number: " + quote(t));
    if (n == Num::range || !std::isfinite(v)) fail("value is not finite: " + quote(t));
    if (std::fabs(v) > FLT_MAX) fail("value is out of range (beyond float): " + quote(t));
    return v;
}

}  // namespace mc::input
