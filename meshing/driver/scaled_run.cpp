#include "meshing/driver/scaled_run.h"

#include <cmath>

namespace delmesh {

namespace {

//! Every number of a JSON value (arrays and objects recursively) times 2^k.
void scale_numbers(nlohmann::json& j, int k) {
  if (j.is_number()) {
    j = std::ldexp(j.get<double>(), k);
  } else if (j.is_array() || j.is_object()) {
    for (auto& item : j) scale_numbers(item, k);
  }
}

//! The lengths and locations of a termination-floor record (Refinement::floor_json) times 2^k.
void scale_floor(nlohmann::json& floor, int k) {
  if (!floor.is_object()) return;
  for (const char* key : {"value", "topology_value", "locations"})
    if (floor.contains(key)) scale_numbers(floor[key], k);
}

}  // namespace

DelMeshOptions unit_scale_options(DelMeshOptions options, int k) {
  options.min_spacing = std::ldexp(options.min_spacing, -k);
  if (options.size_bound) options.size_bound = std::ldexp(*options.size_bound, -k);
  if (options.max_distance) options.max_distance = std::ldexp(*options.max_distance, -k);
  return options;
}

void restore_scale(DelMeshResult& result, int k) {
  auto& j = result.statistics;
  j["unit_scale_exponent"] = k;
  if (k == 0) return;
  scale_mesh(result.mesh, k);
  if (j.contains("clip_box")) scale_numbers(j["clip_box"], k);
  if (j.contains("unsettled") && j["unsettled"].contains("regions"))
    for (auto& region : j["unsettled"]["regions"])
      if (region.contains("location")) scale_numbers(region["location"], k);
  if (j.contains("min_spacing")) scale_floor(j["min_spacing"], k);
  if (j.contains("topology_phase") && j["topology_phase"].contains("min_spacing"))
    scale_floor(j["topology_phase"]["min_spacing"], k);
  if (j.contains("closed_ball")) {
    auto& c = j["closed_ball"];
    if (c.contains("violations"))
      for (auto& entry : c["violations"]["first"]) {
        scale_numbers(entry["witness"], k);
        scale_numbers(entry["witness_distance"], k);
      }
    if (c.contains("non_generic"))
      for (auto& entry : c["non_generic"]["first"]) scale_numbers(entry["location"], k);
  }
}

}  // namespace delmesh
