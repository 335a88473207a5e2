#pragma once
/// \file edge_key.h
/// The key of an undirected edge {a, b} of vertex indices, shared by every stage that hashes edges.
#include <cstdint>
#include <utility>

namespace ctmap {

/// Key of the undirected edge {a, b}: the smaller index in the high 32 bits. \pre a, b >= 0.
inline std::uint64_t edge_key(int a, int b) {
    if (a > b) std::swap(a, b);
    return (std::uint64_t(std::uint32_t(a)) << 32) | std::uint32_t(b);
}
/// The smaller vertex of an edge key.
inline int key_lo(std::uint64_t k) { return int(k >> 32); }
/// The larger vertex of an edge key.
inline int key_hi(std::uint64_t k) { return int(k & 0xffffffffu); }

}  // namespace ctmap
