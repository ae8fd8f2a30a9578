#include "meshing/checks/topo_disk.h"

#include <algorithm>
#include <array>
#include <iterator>
#include <limits>
#include <utility>

#include "meshing/checks/detail/candidates.h"
#include "meshing/core/detail/key_order.h"

namespace delmesh {

bool is_topological_disk(const std::vector<TriangleKey>& star, VertexId p) {
  if (star.empty()) return false;
  // The link as directed half-edges (q, r) and (r, q) of each triangle pqr, sorted by q: every
  // link vertex must have exactly two entries, which are then its two link neighbours.
  thread_local std::vector<std::pair<VertexId, VertexId>> link;
  link.clear();
  for (const auto& t : star) {
    std::array<VertexId, 2> others{};
    std::size_t count = 0;
    for (VertexId v : t)
      if (v != p && count++ < 2) others[count - 1] = v;
    if (count != 2) return false;
    link.emplace_back(others[0], others[1]);
    link.emplace_back(others[1], others[0]);
  }
  std::sort(link.begin(), link.end(), [](const std::pair<VertexId, VertexId>& a, const std::pair<VertexId, VertexId>& b) {
    return detail::pair_word(a.first, a.second) < detail::pair_word(b.first, b.second);
  });
  for (std::size_t i = 0; i < link.size(); i += 2) {
    const bool twice = link[i + 1].first == link[i].first;
    const bool thrice = i + 2 < link.size() && link[i + 2].first == link[i].first;
    if (!twice || thrice) return false;
  }
  const std::size_t vertices = link.size() / 2;
  // One cycle: walk from the smallest link vertex.
  auto neighbours_of = [&](VertexId v) {
    const auto it = std::lower_bound(link.begin(), link.end(), std::make_pair(v, std::numeric_limits<VertexId>::min()));
    return std::make_pair(it->second, std::next(it)->second);
  };
  const VertexId start = link.front().first;
  VertexId previous = -1, current = start;
  std::size_t steps = 0;
  do {
    const auto [a, b] = neighbours_of(current);
    const VertexId next = a != previous ? a : b;
    previous = current;
    current = next;
    ++steps;
  } while (current != start && steps <= vertices);
  return current == start && steps == vertices;
}

CheckResult topo_disk_witness(RestrictedDelaunay& restricted, VertexId p) {
  if (is_topological_disk(restricted.star_unordered(p), p)) return {};
  detail::WitnessCollector collector(CheckKind::topo_disk, p, restricted.delaunay().point(p));
  for (const auto& t : restricted.delaunay().incident_triangles(p))
    for (const auto& x : restricted.voronoi_edge_record(t).crossings()) collector.add(x);
  if (collector.points() == 0) collector.add_unsettled(UnsettledReason::no_witness, restricted.delaunay().point(p));
  return collector.take();
}

}  // namespace delmesh
