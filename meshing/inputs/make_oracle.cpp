#include "meshing/inputs/make_oracle.h"

#include <chrono>

#include "common/errors.h"
#include "common/tolerances.h"
#include "meshing/inputs/implicit_oracle.h"
#include "meshing/inputs/input_validation.h"
#include "meshing/inputs/mesh_oracle.h"
#include "meshing/inputs/sharp_features.h"

namespace delmesh {

namespace {

nlohmann::json box_json(const Box3& b) { return {b.lo[0], b.hi[0], b.lo[1], b.hi[1], b.lo[2], b.hi[2]}; }

//! The input's folded vertices: {count, locations (the first tolerances::floor_locations_listed)}.
nlohmann::json folded_vertices_json(const InputMesh& m) {
  nlohmann::json locations = nlohmann::json::array();
  for (std::size_t i = 0; i < m.folded_vertices.size() && i < tolerances::floor_locations_listed; ++i) {
    const Point3& x = m.mesh.point(m.folded_vertices[i]);
    locations.push_back({x.x(), x.y(), x.z()});
  }
  return {{"count", m.folded_vertices.size()}, {"locations", locations}};
}

//! The input's sharp features at the default feature angle: counts only (a run replaces them by
//! those at its own feature angle).
nlohmann::json features_json(const InputMesh& m) {
  return features_json(detect_features(m.mesh, default_feature_angle_deg, m.folded_vertices));
}

void prepare(PreparedInput& p, const ImplicitInput& in) {
  p.seconds_validation = validate_input(in.surface, in.box).seconds;
  auto oracle = std::make_unique<ImplicitOracle>(in.surface, in.box, in.solver);
  p.implicit = oracle.get();
  p.oracle = std::move(oracle);
  p.statistics_key = "surface";
  p.statistics = {{"name", in.name}, {"equation", in.surface.text()}, {"box", box_json(in.box)}};
}

void prepare(PreparedInput& p, const TriangleMeshInput& in) {
  if (!in.mesh) throw PreconditionViolation("make_oracle: a TriangleMeshInput without its mesh");
  const InputMesh& m = *in.mesh;
  const auto start = std::chrono::steady_clock::now();
  auto oracle = std::make_unique<MeshOracle>(m.mesh, m.box);
  const double seconds_oracle = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  p.scale_exponent = oracle->scale_exponent();
  p.oracle = std::move(oracle);
  p.statistics_key = "input_mesh";
  p.statistics = {{"file", in.file},
                  {"faces_read", m.faces_read},
                  {"polygons_triangulated", m.polygons_triangulated},
                  {"vertices", m.report.vertices},
                  {"triangles", m.report.triangles},
                  {"components", m.report.components},
                  {"genus_per_component", m.report.genus_per_component},
                  {"box", box_json(m.box)},
                  {"bounding_box_diagonal", m.bounding_box_diagonal},
                  {"median_edge_length", m.median_edge_length},
                  {"components_reversed", m.components_reversed},
                  {"folded_vertices", folded_vertices_json(m)},
                  {"features", features_json(m)},
                  {"seconds_oracle_build", seconds_oracle}};
}

}  // namespace

PreparedInput make_oracle(MesherInput input) {
  PreparedInput p{nullptr, std::move(input)};
  std::visit([&](const auto& in) { prepare(p, in); }, p.input);
  return p;
}

}  // namespace delmesh
