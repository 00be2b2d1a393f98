// Number and token helpers shared by the readers.
//
// Promise: every parse is whole-token and locale-independent (std::from_chars), accepts the leading
// '+' that iostreams-based exporters write, and reports "not a number" apart from "out of range"
// so a reader can say which. Floats are parsed as float directly (one correct rounding), doubles
// as double; neither ever goes through the other.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>

namespace mc::input {

enum class Num { ok, bad, range };

Num parse_int(std::string_view s, long long &v);
Num parse_double(std::string_view s, double &v);  // underflow is ok (rounds to 0 or a denormal)
Num parse_float(std::string_view s, float &v);    // range: beyond float (an overflow to inf)

// Why a coordinate value is unusable, or nullptr. Later stages store floats, hence the float range.
const char *bad_coordinate(double v);

std::string quote(std::string_view s);  // 'token' for a message: control bytes escaped, cut at 40
std::string lower(std::string_view s);
std::string num(uint64_t n);
std::string show(double v);             // %.9g
std::string plural(const std::string &element);  // vertex -> vertices, face -> faces

}  // namespace mc::input
