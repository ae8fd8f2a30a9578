#include "meshing/topology.h"

#include <algorithm>
#include <sstream>

#include "common/tolerances.h"
#include "meshing/facet_contact.h"
#include "meshing/facet_cycle.h"
#include "meshing/silhouette.h"
#include "meshing/topo_disk.h"
#include "meshing/vor_edge.h"

namespace delmesh {

std::ostream& operator<<(std::ostream& out, TopologyStatus status) {
  switch (status) {
    case TopologyStatus::complete: return out << "complete";
    case TopologyStatus::point_limit: return out << "point_limit";
    case TopologyStatus::time_limit: return out << "time_limit";
  }
  return out << "unknown";
}

Topology::Topology(SurfaceOracle& oracle, std::uint64_t seed, TopologyLimits limits)
    : oracle_(oracle), seed_(seed), limits_(std::move(limits)), restricted_(del_, oracle, seed),
      last_progress_(std::chrono::steady_clock::now()) {}

std::optional<VertexId> Topology::insert(const Witness& w) {
  InsertionRecord record;
  record.point = w.point;
  record.kind = w.kind;
  record.from_undecided = w.from_undecided;
  if (del_.size() > 0) {
    const auto [nearest, d] = del_.nearest(w.point);
    record.nearest = nearest;
    record.nearest_distance = d;
    if (d <= tolerances::duplicate_sample_relative_distance * oracle_.diagonal()) {
      ++rejected_;
      return std::nullopt;
    }
  }
  const auto id = del_.insert(w.point, w.kind == CheckKind::seed);
  if (!id) {
    ++rejected_;
    return std::nullopt;
  }
  record.id = *id;
  log_.push_back(record);
  ++insertions_[static_cast<int>(w.kind)];
  std::vector<VertexId> around = del_.neighbours(*id);
  around.push_back(*id);
  std::sort(around.begin(), around.end());
  restricted_.invalidate(around);
  dirty(around);
  return id;
}

void Topology::remove(VertexId p) {
  std::vector<VertexId> around = del_.neighbours(p);
  del_.remove(p);
  ++seeds_deleted_;
  std::vector<VertexId> with_p = around;
  with_p.push_back(p);
  std::sort(with_p.begin(), with_p.end());
  restricted_.invalidate(with_p);
  dirty(around);
}

void Topology::dirty_all() {
  const auto all = del_.vertices();
  restricted_.invalidate(all);
  dirty(all);
}

void Topology::dirty(const std::vector<VertexId>& vs) {
  auto in = [&](VertexId v) { return std::binary_search(vs.begin(), vs.end(), v); };
  for (VertexId v : vs) {
    if (!del_.contains(v)) continue;
    for (const auto& t : del_.incident_triangles(v))
      if (t[0] == v && in(t[1]) && in(t[2])) {
        queue_a_.insert(t);
        changed_.insert(t);
      }
    for (VertexId w : del_.neighbours(v))
      if (v < w && in(w)) {
        queue_b_.insert({v, w});
        queue_d_.insert({v, w});
      }
    queue_c_.insert(v);
    queue_e_.insert(v);
  }
}

std::set<TriangleKey> Topology::take_changed_triangles() {
  std::set<TriangleKey> out;
  out.swap(changed_);
  return out;
}

std::optional<TopologyStatus> Topology::limit_reached(const std::string& phase) {
  const auto now = std::chrono::steady_clock::now();
  if (limits_.progress &&
      std::chrono::duration<double>(now - last_progress_).count() >= tolerances::progress_interval_seconds) {
    last_progress_ = now;
    std::ostringstream s;
    s << phase << ": points " << del_.size() << ", queues a=" << queue_a_.size() << " b=" << queue_b_.size()
      << " c=" << queue_c_.size() << " d=" << queue_d_.size() << " e=" << queue_e_.size();
    limits_.progress(s.str());
  }
  if (del_.size() >= limits_.max_points) return TopologyStatus::point_limit;
  if (limits_.deadline && now >= *limits_.deadline) return TopologyStatus::time_limit;
  return std::nullopt;
}

namespace {
template <class Set>
typename Set::value_type pop(Set& s) {
  auto v = *s.begin();
  s.erase(s.begin());
  return v;
}
}  // namespace

TopologyStatus Topology::run() {
  while (true) {
    if (auto status = limit_reached("topology")) return *status;
    std::optional<Witness> w;
    CheckKind kind;
    const auto start = std::chrono::steady_clock::now();
    if (!queue_a_.empty()) {
      kind = CheckKind::vor_edge;
      const auto t = pop(queue_a_);
      if (del_.is_triangle(t)) w = vor_edge_witness(restricted_, t);
    } else if (!queue_b_.empty()) {
      kind = CheckKind::facet_contact;
      const auto e = pop(queue_b_);
      if (del_.is_edge(e)) w = facet_contact_witness(restricted_, e);
    } else if (!queue_c_.empty()) {
      kind = CheckKind::topo_disk;
      const auto p = pop(queue_c_);
      if (del_.contains(p)) w = topo_disk_witness(restricted_, p);
    } else if (!queue_d_.empty()) {
      kind = CheckKind::facet_cycle;
      const auto e = pop(queue_d_);
      if (del_.is_edge(e)) w = facet_cycle_witness(restricted_, e);
    } else if (!queue_e_.empty()) {
      kind = CheckKind::silhouette;
      const auto p = pop(queue_e_);
      if (del_.contains(p)) w = silhouette_witness(restricted_, p, /*facets_clean=*/true);
    } else {
      return TopologyStatus::complete;
    }
    add_seconds(kind, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (w) insert(*w);
  }
}

nlohmann::json Topology::insertions_json() const {
  nlohmann::json j = nlohmann::json::object();
  for (int k = 0; k < check_kind_count; ++k) {
    std::ostringstream name;
    name << static_cast<CheckKind>(k);
    j[name.str() == "seed" ? "seeds" : name.str()] = insertions_[k];
  }
  j["seeds_deleted"] = seeds_deleted_;
  j["rejected_witnesses"] = rejected_;
  return j;
}

}  // namespace delmesh
