// Reading an input file once, front to back, knowing where we are.
//
// Promise: ByteReader reads a file in 64 KiB blocks and always knows the byte offset of the next
// byte; TextReader splits it into lines (1-based numbers, '\n' ends a line, a '\r' before it is
// whitespace) and whitespace-separated tokens, optionally cutting '#' comments. Neither holds more
// than one block and one line (at most kMaxLine bytes) in memory, whatever the file says. Every
// error they raise is an InputError at the current place (line or byte offset).
#pragma once
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "input/limits.hpp"
#include "model.hpp"

namespace mc::input {

using Tokens = std::vector<std::string_view>;

[[noreturn]] void fail_none(const std::string &path, const std::string &msg);
[[noreturn]] void fail_line(const std::string &path, long long line, const std::string &msg);
[[noreturn]] void fail_byte(const std::string &path, uint64_t at, const std::string &msg);

class ByteReader {
public:
    explicit ByteReader(const std::string &path);
    uint64_t offset() const { return offset_; }
    bool at_end() { return !fill(); }
    // Copies up to N bytes to DST; returns how many (fewer only at the end of the file).
    size_t read(char *dst, size_t n);
    // Next line without its '\n'; false at the end of the file. Sets TOO_LONG rather than reading
    // more than kMaxLine bytes (a binary file given a text extension).
    bool line(std::string &out, bool &too_long);

private:
    bool fill();
    std::string path_;
    std::ifstream in_;
    std::vector<char> buf_ = std::vector<char>(1 << 16);
    size_t pos_ = 0, end_ = 0;
    uint64_t offset_ = 0;
};

inline bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// At the end of the file line() stays on the last line, which is where a truncated file is reported.
class TextReader {
public:
    TextReader(ByteReader &in, const std::string &path, bool comments) : in_(in), path_(path), comments_(comments) {}

    bool next();          // the next physical line; false at the end of the file
    bool next_content();  // on to the next line that has tokens; false at the end of the file

    const Tokens &tok() const { return tok_; }
    const std::string &raw() const { return raw_; }
    long long line() const { return line_; }
    const std::string &path() const { return path_; }

    [[noreturn]] void fail(const std::string &msg) const { fail_line(path_, line_, msg); }

    // A coordinate token: a finite number within float range, else an error at this line.
    double coordinate(std::string_view t) const;
    // The same, rounded once to float as a float-based mesh library stores it.
    float coordinate_f(std::string_view t) const;
    // Any other number (normal, colour, texture coordinate): finite, within float range.
    double number(std::string_view t) const;

private:
    void split();
    ByteReader &in_;
    std::string path_;
    bool comments_;
    long long line_ = 0;
    std::string raw_;
    Tokens tok_;
};

}  // namespace mc::input
