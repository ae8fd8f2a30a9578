#pragma once
//! \file del_mesh.h
//! DelMesh (§6.2): SampleTopology, then Quality and Smooth with Topology re-run locally after
//! every insertion, until nothing changes.  Theorem 6.1: for 0 < λ ≤ 0.06 the output Tri S|Σ is
//! homeomorphic to Σ, every triangle has radius-edge ratio ≤ 1+λ and every edge roughness ≤ 2β(λ).

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "meshing/core/mesh_status.h"
#include "meshing/core/surface_mesh.h"
#include "meshing/driver/mesh_options.h"
#include "symbolic/surface.h"

namespace delmesh {

struct [[nodiscard]] DelMeshResult {
  MeshStatus status = MeshStatus::complete;
  SurfaceMesh mesh;              //!< Tri S|Σ, consistently outward oriented
  nlohmann::json statistics;     //!< the run's statistics (the JSON of `delmesh mesh --stats`, built in del_mesh.cpp)
  //! Per face of mesh, in index order: the bound that certify_distance()'s certificate proved on
  //! the distance from every point of the face to Σ (gradient_flow_certificate.h,
  //! triangle_distance_bounds), when it certified the mesh; else empty.
  std::vector<double> triangle_distance_bounds;
};

//! Meshes Σ = {E = 0} ⊂ interior(box): make_oracle() on the ImplicitInput (surface, box,
//! options.solver), then del_mesh() on it; the time limit and the statistics' seconds count the
//! validation.  Throws InvalidInput if Σ is empty in the box, meets the box boundary, or is
//! singular (∇E = 0 somewhere on Σ), if the box is empty, or if an option is out of its range
//! (violated_range: "lambda must satisfy 0 < lambda < 1/3"), the options before the surface.
DelMeshResult del_mesh(const Surface& surface, const Box3& box, const DelMeshOptions& options);

struct PreparedInput;
//! Meshes an input made ready by make_oracle() (meshing/inputs/make_oracle.h), of any kind: the
//! run on its oracle, with the options' lengths at the oracle's unit scale and the result brought
//! back (meshing/driver/scaled_run.h); the statistics get the input's description under its key
//! ("surface" or "input_mesh") and its validation seconds; an implicit surface then gets
//! certify_distance() when options.distance_certificate or options.max_distance asks for it.
//! Throws InvalidInput as del_mesh(oracle, …) does.
DelMeshResult del_mesh(PreparedInput& input, const DelMeshOptions& options);

//! The gradient-flow certificate of a run's output (gradient_flow_certificate.h, under the run's
//! time limit counted from `start`, with options.max_distance as its distance radius), if the run
//! ended complete or uncertified: the statistics' "distance" gets that certificate's JSON, or
//! {status: "not attempted", reason} after any other ending, and max_distance (null if not given).
//! With max_distance, a complete run becomes uncertified unless the certificate proves a
//! two-sided Hausdorff bound ≤ δ; that failure is listed under "unsettled" (reason
//! distance_not_certified in by_reason, check "distance" with the certificate's reason in regions).
//! A certificate stopped by the interrupt flag or the time limit makes such a run interrupted or
//! time_limit instead.  Precondition: validate_input(surface, box) succeeded (the run
//! did it).  A caller of del_mesh(oracle, …) on an implicit surface calls this itself.
void certify_distance(DelMeshResult& result, const Surface& surface, const Box3& box, const DelMeshOptions& options,
                      std::chrono::steady_clock::time_point start);

class SurfaceOracle;
//! Meshes the surface of `oracle` (any implementation of meshing/core/surface_oracle.h) in its box.
//! The caller has validated the input (its seconds go to the statistics' seconds_validation);
//! options.solver is not read (the oracle has its own backend).  Throws InvalidInput as above,
//! and if max_distance is given to an oracle without flow_distance().  It does not run
//! certify_distance(): the oracle does not give E.
DelMeshResult del_mesh(SurfaceOracle& oracle, const DelMeshOptions& options, double seconds_validation = 0);

}  // namespace delmesh
