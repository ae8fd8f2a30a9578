#pragma once
//! \file id_marks.h
//! Internal: distinct vertex ids of a list without sorting it whole.  An insertion gathers the
//! neighbours of the new vertex from its Delaunay cells (each neighbour once per cell, about six
//! times), and the vertices of the triangles that entered or left the restricted Delaunay
//! triangulation (each vertex several times); sorting those lists to drop the repeats costs
//! O(n log n) comparisons on n entries, marking each id costs one load and one store per entry.

#include <algorithm>
#include <cstdint>
#include <vector>

#include "meshing/core/simplex_keys.h"

namespace delmesh::detail {

//! A set of vertex ids ≥ −1 (−1: the infinite vertex) that empties in constant time: an id is in
//! the set when its entry holds the current round.  drop_repeated_ids() keeps one per thread.
class IdMarks {
 public:
  //! Empties the set.
  void clear() {
    if (++round_ == 0) {  // the rounds wrapped: old entries could match again
      std::fill(marks_.begin(), marks_.end(), 0);
      round_ = 1;
    }
  }
  //! Adds id ≥ −1; true when it was not in the set.
  bool insert(VertexId id) {
    const auto k = static_cast<std::size_t>(id + 1);
    if (k >= marks_.size()) marks_.resize(std::max(k + 1, 2 * marks_.size()), 0);
    if (marks_[k] == round_) return false;
    marks_[k] = round_;
    return true;
  }

 private:
  std::vector<std::uint32_t> marks_;
  std::uint32_t round_ = 0;
};

//! Drops the repeats of `ids` (ids ≥ −1), keeping the first occurrence of each, in order.
inline void drop_repeated_ids(std::vector<VertexId>& ids) {
  thread_local IdMarks marks;
  marks.clear();
  ids.erase(std::remove_if(ids.begin(), ids.end(), [](VertexId v) { return !marks.insert(v); }), ids.end());
}

//! Sorts `ids` (ids ≥ −1) ascending and drops repeats: what std::sort then std::unique give.
inline void sort_distinct_ids(std::vector<VertexId>& ids) {
  drop_repeated_ids(ids);
  std::sort(ids.begin(), ids.end());
}

}  // namespace delmesh::detail
