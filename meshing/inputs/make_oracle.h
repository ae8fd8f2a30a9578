#pragma once
//! \file make_oracle.h
//! The one place where an input becomes the SurfaceOracle the mesher samples (meshing/core/surface_oracle.h):
//! an implicit surface E = 0 in a box becomes an ImplicitOracle after validate_input proves it
//! smooth and inside the box; a closed triangle mesh, already read and validated
//! (meshing/inputs/input_mesh.h), becomes a MeshOracle at unit scale (meshing/inputs/unit_scale.h).
//! Each kind also describes itself for the run's statistics.  A new kind of input is one
//! SurfaceOracle class, one alternative of MesherInput and one case in make_oracle().

#include <memory>
#include <string>
#include <variant>

#include <nlohmann/json.hpp>

#include "meshing/core/surface_oracle.h"
#include "meshing/inputs/input_mesh.h"
#include "solvers/solver_backend.h"
#include "symbolic/surface.h"

namespace delmesh {

class ImplicitOracle;

//! Σ = {E = 0} ⊂ interior(box), answered by `solver`.
struct ImplicitInput {
  std::string name = "surface";  //!< the catalog name, or "surface" for an expression
  Surface surface;
  Box3 box;
  SolverBackend solver = SolverBackend::subdivision;
};

//! A closed triangle mesh to remesh (§7).  The oracle keeps a scaled copy of `mesh`; the
//! PreparedInput keeps the pointer, which del_mesh() reads for the closed-ball check, so the mesh
//! must outlive the run.
struct TriangleMeshInput {
  std::string file;                  //!< where it was read from, for the statistics
  const InputMesh* mesh = nullptr;   //!< read and validated (read_input_mesh, validate_input_mesh)
};

using MesherInput = std::variant<ImplicitInput, TriangleMeshInput>;

//! An input made ready for the mesher.
struct PreparedInput {
  std::unique_ptr<SurfaceOracle> oracle;
  //! The input as given (an ImplicitInput's E and box serve the distance certificate).
  MesherInput input;
  //! The oracle as an ImplicitOracle (its compiled ∇E gives the output's normals), or null.
  const ImplicitOracle* implicit = nullptr;
  //! The statistics' key for the input ("surface" or "input_mesh") and its object.
  std::string statistics_key;
  nlohmann::json statistics;
  double seconds_validation = 0;   //!< validate_input's seconds (0 for a mesh, validated when read)
  int scale_exponent = 0;          //!< the oracle's unit-scale exponent k (0 for an implicit surface)

  //! The implicit surface, or null for a triangle mesh.
  const ImplicitInput* implicit_input() const { return std::get_if<ImplicitInput>(&input); }
};

//! Builds the oracle of `input`.  An implicit surface: validate_input(surface, box) first, which
//! throws InvalidInput if Σ is empty in the box, meets its boundary or is singular, and
//! RunStopped under a command's limits (common/run_limits.h); statistics "surface": {name,
//! equation, box}.  A triangle mesh: statistics "input_mesh": the file, what the reader did,
//! the checker's counts, box, diagonal, median edge, folded vertices, sharp features at the
//! default angle (meshing/inputs/sharp_features.h) and seconds_oracle_build.  Throws
//! PreconditionViolation if a TriangleMeshInput has no mesh.
[[nodiscard]] PreparedInput make_oracle(MesherInput input);

}  // namespace delmesh
