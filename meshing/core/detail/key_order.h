#pragma once
//! \file key_order.h
//! Internal: the lexicographic order of vertex-id tuples (simplex keys, link half-edges) computed
//! on packed words.  Every insertion sorts the keys of its cavity and of the new vertex's star;
//! comparing two ids at once as one 64-bit word costs one integer comparison where std::array's
//! and std::tie's operators compare entry by entry (and std::array's == calls memcmp).
//!
//! Exactness: order_word() maps int32 onto uint32 monotonically (adding 2³¹ modulo 2³², i.e.
//! flipping the sign bit), so pair_word(a, b) < pair_word(c, d) iff (a, b) < (c, d)
//! lexicographically, for all ids, −1 for the infinite vertex included.  Each comparator below
//! therefore returns what the operator it replaces returns on every pair, and std::sort, which
//! only branches on comparison results, performs the same steps with it: the sorted sequences
//! (and whatever order they fix downstream) are those of the standard operators.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshing/core/simplex_keys.h"

namespace delmesh::detail {

//! The sign bit of a flipped: a < b iff order_word(a) < order_word(b).
inline std::uint64_t order_word(VertexId a) { return static_cast<std::uint32_t>(a) ^ 0x80000000u; }

//! (a, b) packed so that the order of the words is the lexicographic order of the pairs.
inline std::uint64_t pair_word(VertexId a, VertexId b) { return order_word(a) << 32 | order_word(b); }

//! std::array's operator< on edge and triangle keys.
struct KeyLess {
  bool operator()(const EdgeKey& x, const EdgeKey& y) const { return pair_word(x[0], x[1]) < pair_word(y[0], y[1]); }
  bool operator()(const TriangleKey& x, const TriangleKey& y) const {
    const std::uint64_t a = pair_word(x[0], x[1]), b = pair_word(y[0], y[1]);
    return a < b || (a == b && x[2] < y[2]);
  }
};

//! std::array's operator== on tuples of ids (edge and triangle keys, cells, hash-table keys):
//! the entries' differences (xor) are combined and tested once, without a memcmp call or a branch
//! per entry.
struct KeyEqual {
  template <std::size_t N>
  bool operator()(const std::array<VertexId, N>& x, const std::array<VertexId, N>& y) const {
    VertexId differ = 0;
    for (std::size_t k = 0; k < N; ++k) differ |= x[k] ^ y[k];
    return differ == 0;
  }
};

//! Sorts keys ascending and drops repeats.
template <class Key>
void sort_unique(std::vector<Key>& keys) {
  std::sort(keys.begin(), keys.end(), KeyLess{});
  keys.erase(std::unique(keys.begin(), keys.end(), KeyEqual{}), keys.end());
}

}  // namespace delmesh::detail
