// How much a file may ask the readers to hold.
//
// Promise: no reader stores more than kMaxElements vertices, points or faces, reads a text line
// longer than kMaxLine, or reserves memory for more records than the bytes left in the file can
// hold (reserve_for): a declared count is a claim, the file's size is a fact.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

namespace mc::input {

constexpr uint64_t kMaxElements = 50'000'000;
constexpr size_t kMaxLine = size_t(1) << 24;  // no sane model file has a longer text line
inline const std::string kLimit = std::to_string(kMaxElements);

// How many records to reserve for COUNT declared records of at least MIN_BYTES each when
// BYTES_LEFT bytes remain: never more than the file can hold (and never more than COUNT).
inline uint64_t reserve_for(uint64_t count, uint64_t min_bytes, uint64_t bytes_left) {
    const uint64_t can_hold = min_bytes ? bytes_left / min_bytes : bytes_left;
    return count < can_hold ? count : can_hold;
}

}  // namespace mc::input
