#include "input/numbers.hpp"

#include <cctype>
#include <cfloat>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace mc::input {
namespace {

// iostreams accept a leading '+'; std::from_chars does not.
std::string_view skip_plus(std::string_view s) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
    return s;
}

template <class T>
Num parse_real(std::string_view s, T &v) {
    s = skip_plus(s);
    const char *end = s.data() + s.size();
    auto [p, ec] = std::from_chars(s.data(), end, v);
    if (ec == std::errc::invalid_argument || p != end) return Num::bad;
    if (ec == std::errc::result_out_of_range) {
        // from_chars also reports underflow (1e-400), which is harmless: only overflow is an error.
        const std::string z(s);
        v = static_cast<T>(sizeof(T) == sizeof(float) ? std::strtof(z.c_str(), nullptr) : std::strtod(z.c_str(), nullptr));
        if (std::isinf(v)) return Num::range;
    }
    return Num::ok;
}

}  // namespace

Num parse_int(std::string_view s, long long &v) {
    s = skip_plus(s);
    const char *end = s.data() + s.size();
    auto [p, ec] = std::from_chars(s.data(), end, v);
    if (ec == std::errc::invalid_argument || p != end) return Num::bad;
    return ec == std::errc::result_out_of_range ? Num::range : Num::ok;
}

Num parse_double(std::string_view s, double &v) { return parse_real(s, v); }
Num parse_float(std::string_view s, float &v) { return parse_real(s, v); }

const char *bad_coordinate(double v) {
    if (!std::isfinite(v)) return "coordinate is not finite";
    if (std::fabs(v) > FLT_MAX) return "coordinate is out of range (beyond float)";
    return nullptr;
}

std::string quote(std::string_view s) {
    std::string r = "'";
    for (size_t i = 0; i < s.size() && i < 40; ++i) {
        unsigned char c = static_cast<unsigned char>(s[i]);
        if (c >= 32 && c < 127 && c != '\\') {
            r += static_cast<char>(c);
        } else {
            char b[8];
            std::snprintf(b, sizeof b, "\\x%02x", c);
            r += b;
        }
    }
    return r + (s.size() > 40 ? "...'" : "'");
}

std::string lower(std::string_view s) {
    std::string r(s);
    for (char &c : r) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return r;
}

std::string num(uint64_t n) { return std::to_string(n); }

std::string show(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.9g", v);
    return b;
}

std::string plural(const std::string &element) { return element == "vertex" ? "vertices" : element + "s"; }

}  // namespace mc::input
