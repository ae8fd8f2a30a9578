#include "meshing/topo_disk.h"

#include <map>

#include "meshing/detail/candidates.h"

namespace delmesh {

bool is_topological_disk(const std::vector<TriangleKey>& star, VertexId p) {
  if (star.empty()) return false;
  std::map<VertexId, std::vector<VertexId>> link;
  for (const auto& t : star) {
    std::vector<VertexId> others;
    for (VertexId v : t)
      if (v != p) others.push_back(v);
    if (others.size() != 2) return false;
    link[others[0]].push_back(others[1]);
    link[others[1]].push_back(others[0]);
  }
  for (const auto& [v, adj] : link)
    if (adj.size() != 2) return false;
  // One cycle: walk from the first link vertex.
  const VertexId start = link.begin()->first;
  VertexId previous = -1, current = start;
  std::size_t steps = 0;
  do {
    const auto& adj = link[current];
    const VertexId next = adj[0] != previous ? adj[0] : adj[1];
    previous = current;
    current = next;
    ++steps;
  } while (current != start && steps <= link.size());
  return current == start && steps == link.size();
}

CheckResult topo_disk_witness(RestrictedDelaunay& restricted, VertexId p) {
  if (is_topological_disk(restricted.star(p), p)) return {};
  detail::WitnessCollector collector(CheckKind::topo_disk, p, restricted.delaunay().point(p));
  for (const auto& t : restricted.delaunay().incident_triangles(p))
    for (const auto& x : restricted.voronoi_edge_record(t).crossings) collector.add(x);
  if (collector.points() == 0) collector.add_unsettled(UnsettledReason::no_witness, restricted.delaunay().point(p));
  return collector.take();
}

}  // namespace delmesh
