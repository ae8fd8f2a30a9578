#pragma once
//! \file commands.h
//! The computations behind the subcommands of `delmesh`, callable without a command line: the
//! program and the Python module (python/delmesh_module.cpp) share them, so both accept the same
//! inputs, refuse bad ones with the same InvalidInput message (the text of the program's
//! `error:` line) and give the same results.  Each is implemented next to its subcommand's
//! command-line code, apps/<name>_command.cpp; printing and output files stay there.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "common/tolerances.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/input_mesh.h"
#include "meshing/verify/certificate.h"
#include "meshing/verify/gradient_flow_certificate.h"
#include "solvers/solve_result.h"

namespace delmesh::app {

// ---------------------------------------------------------------------------------------------
// delmesh mesh (mesh_command.cpp)
// ---------------------------------------------------------------------------------------------

//! The options of `delmesh mesh` that describe the run (not its output files), as values.
struct MeshRequest {
  SurfaceArguments surface;               //!< --surface | --expr with --box
  std::optional<std::string> input_mesh;  //!< --input-mesh
  //! The run's options, each field bound to its flag: --lambda, --phase, --solver, --size-bound,
  //! --max-distance, --max-points, --time-limit (time_limit_seconds), --seed, --threads,
  //! --min-spacing.  progress and interrupt are the caller's.
  DelMeshOptions options;
  //! --min-spacing was given.  Otherwise options.min_spacing is replaced by the input's default:
  //! 0 (no floor) for an implicit surface, tolerances::min_spacing_median_edge_fraction times the
  //! median edge length for --input-mesh.
  bool min_spacing_given = false;
};

//! A validated request: the surface and the options of del_mesh (without progress and
//! interrupt, which belong to the caller), and the warnings to show once the caller has
//! validated its own options.
struct MeshPlan {
  SurfaceInput input;
  DelMeshOptions options;
  std::vector<std::string> warnings;  //!< e.g. λ > 0.06 is not covered by Theorem 6.1
};

//! Validates a request in the program's order: the options' ranges (DelMeshOptions::validate(),
//! a violation given as "FLAG must RANGE, got VALUE"), --input-mesh, the surface's presence,
//! --max-distance with --phase, then the surface itself.  Throws InvalidInput with the program's
//! message on the first invalid option.  A request with --input-mesh is validated as
//! plan_mesh_input() does and then refused: its plan is a MeshInputPlan.
MeshPlan plan_mesh(const MeshRequest& request);

//! A validated --input-mesh request: the mesh to remesh (meshing/inputs/input_mesh.h) and the options.
struct MeshInputPlan {
  std::string name;  //!< <stem>_remeshed for the file <stem>.<ext>: the default outputs <name>.off, <name>.json
  std::string path;
  InputMesh mesh;
  DelMeshOptions options;
  std::vector<std::string> warnings;
};

//! Validates an --input-mesh request in plan_mesh()'s order, then reads and validates the mesh
//! (read_input_mesh: one InvalidInput naming the defect).  options.solver is not used.  The
//! minimum spacing defaults to tolerances::min_spacing_median_edge_fraction times the mesh's
//! median edge.
MeshInputPlan plan_mesh_input(const MeshRequest& request);
//! The same for a mesh already read and validated (validate_input_mesh), named `name` (the
//! plan's name, and its path when the request has no --input-mesh); request.input_mesh is not
//! read.
MeshInputPlan plan_mesh_input(const MeshRequest& request, InputMesh mesh, const std::string& name);

//! DelMesh on the plan's mesh through a MeshOracle (meshing/inputs/mesh_oracle.h), with `options`
//! (the plan's, plus progress and interrupt).  The statistics are del_mesh's, with "input_mesh":
//! {file, vertices, triangles, components, genus_per_component, box, bounding_box_diagonal,
//! median_edge_length, components_reversed, folded_vertices {count, locations}}.  A plan whose
//! mesh has folded vertices (meshing/inputs/folded_vertices.h) carries a warning that the run cannot
//! end complete.
DelMeshResult remesh(const MeshInputPlan& plan, const DelMeshOptions& options);

//! The statistics record of a run as `delmesh mesh --input-mesh` writes it: del_mesh's (or
//! remesh()'s) statistics with the status and the seed, and "mesh_file" if a file is named.
nlohmann::json run_statistics(const DelMeshResult& result, std::uint64_t seed, const std::optional<std::string>& mesh_file);

//! The statistics record of a run as `delmesh mesh` writes it: run_statistics() and the surface
//! (name, equation, box).
nlohmann::json mesh_statistics(const DelMeshResult& result, const SurfaceInput& input, std::uint64_t seed,
                               const std::optional<std::string>& mesh_file);

// ---------------------------------------------------------------------------------------------
// delmesh check (check_command.cpp)
// ---------------------------------------------------------------------------------------------

//! Throws InvalidInput unless 0 < λ < 1/6, the range of the bounds of Theorem 6.1.
void require_bounds_lambda(double lambda);

//! The checker's report on a mesh and, with λ, the bounds of Theorem 6.1 and which of them hold
//! (a bound fails on a mesh without triangles).
struct CheckVerdict {
  MeshReport report;
  std::optional<double> lambda;
  TheoremBounds bounds{};
  bool angle_ok = true, ratio_ok = true, roughness_ok = true;
  std::vector<std::string> warnings;  //!< e.g. λ > 0.06 is outside Theorem 6.1

  bool all_pass() const { return angle_ok && ratio_ok && roughness_ok; }
  //! The report of to_json(MeshReport), then with λ also "lambda", "bounds" and "pass".
  nlohmann::ordered_json to_json() const;
};

//! The verdict on `report` for the optional λ.  Precondition (checked by
//! require_bounds_lambda, throws InvalidInput): λ, if given, lies in (0, 1/6).
CheckVerdict check_verdict(const MeshReport& report, std::optional<double> lambda);

//! Which certificates `check --certify` runs: automatic ("auto") runs the restricted-Delaunay
//! certificate, then the gradient-flow certificate unless the first certified the mesh as
//! Tri S|Σ of its vertices; both runs the two, and the verdict is certified only if each is.
enum class CertifyMethod { automatic, restricted_delaunay, gradient_flow, both };
constexpr auto enum_names(CertifyMethod) {
  return name_table<CertifyMethod>("CertifyMethod", {{CertifyMethod::automatic, "auto"},
                                                     {CertifyMethod::restricted_delaunay, "restricted-delaunay"},
                                                     {CertifyMethod::gradient_flow, "gradient-flow"},
                                                     {CertifyMethod::both, "both"}});
}

//! The certificates that ran and what they prove together.
struct TopologyCertificates {
  std::optional<Certificate> delaunay;    //!< meshing/verify/certificate.h
  std::optional<FlowCertificate> flow;    //!< meshing/verify/gradient_flow_certificate.h
  std::string verdict = "undecided";      //!< certified, refuted (only by the flow's proof) or undecided
  std::string method;                     //!< the method that decided the verdict ("" when none did)
  std::string reason;                     //!< why, in one phrase
  bool interrupted() const;               //!< a certificate stopped at the interrupt flag
  bool time_limited() const;              //!< a certificate stopped at the deadline
  //! {"certificate": …} and {"gradient_flow": …} for those that ran (the latter with the
  //! per-triangle bounds), and "topology": {verdict, method, reason, hausdorff_upper_bound}.
  nlohmann::ordered_json to_json() const;
};

//! The certificates of the soup for the surface by `method` (a stopped certificate ends the
//! sequence).  Throws InvalidInput as certify_mesh and certify_gradient_flow do (bad indices,
//! a surface that fails validation).
TopologyCertificates certify_topology(const std::vector<Point3>& points,
                                      const std::vector<std::array<std::size_t, 3>>& triangles,
                                      const SurfaceInput& input, CertifyMethod method, std::uint64_t seed,
                                      const std::atomic<bool>* interrupt,
                                      std::optional<std::chrono::steady_clock::time_point> deadline);

// ---------------------------------------------------------------------------------------------
// delmesh solve (solve_command.cpp)
// ---------------------------------------------------------------------------------------------

//! The parameter options of the primitives: --direction, --direction2, --point, --plane-origin,
//! --plane-normal.
const std::vector<std::string>& solve_parameter_options();

//! The options of `delmesh solve`, as values.
struct SolveRequest {
  SurfaceArguments surface;
  std::string primitive;
  //! The parameter options given, e.g. "--direction" → "0,0,1" (see solve_parameter_options()).
  std::map<std::string, std::string> parameters;
  std::string solver = "subdivision";      //!< subdivision or homotopy
  std::string taylor_forms = "automatic";  //!< automatic, always or never
  std::size_t max_boxes = tolerances::default_box_budget;
  double time_limit = 0;                   //!< seconds; 0: none
};

//! A world bounding box [x0,x1] × [y0,y1] × [z0,z1].
using WorldBox = std::array<std::array<double, 2>, 3>;

//! The answer of one solve, in world coordinates.
struct SolveOutcome {
  SurfaceInput input;
  std::string description;  //!< the primitive's parameters as used (unit vectors, frames)
  std::string solver;       //!< "subdivision", "homotopy" or "univariate isolator"
  SolveResult result;       //!< status, roots (with world points), undecided regions, counters
  std::vector<WorldBox> undecided;  //!< the world bounding box of each result.undecided region
  double seconds = 0;

  //! The `--json` output: status, roots, undecided (world boxes), boxes, seconds.
  nlohmann::ordered_json to_json() const;
};

//! Solves one primitive of §5.2 as `delmesh solve` does.  Throws InvalidInput with the
//! program's message for an unknown primitive, a parameter it does not take or lacks, a bad
//! vector, solver or surface.
SolveOutcome solve_primitive(const SolveRequest& request);

// ---------------------------------------------------------------------------------------------
// delmesh surfaces (surfaces_command.cpp)
// ---------------------------------------------------------------------------------------------

//! The catalog as `delmesh surfaces --json` prints it: an array of {name, equation, box,
//! components, genus_per_component, description, analytic_lfs}.
nlohmann::ordered_json catalog_json();

}  // namespace delmesh::app
