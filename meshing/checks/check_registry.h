#pragma once
//! \file check_registry.h
//! The registry of checks: one row (CheckInfo) per check carries everything the refinement
//! driver (meshing/driver/refinement.h) and the certificate (meshing/verify/certificate.h) need to run it — its
//! name (the key of its counts in the statistics), the kind of Delaunay simplex its queue holds,
//! when such a face is dirtied, its phase and the function itself.  Neither the driver nor the
//! certificate names a check: both iterate over this registry, the driver as its table (one
//! work queue per row, the rows' order is the priority), the certificate over the topology rows.
//!
//! The registry holds, in order, the rows of builtin_checks() (meshing/checks/checks.cpp: VorEdge,
//! FacetContact, TopoDisk, FacetCycle, Silhouette of §5.3, then Quality (with the size bound) and
//! Smooth of §6.1) and then the rows registered by CheckRegistration objects of the program
//! (examples/extending: one file holds a check function and its registration).
//!
//! Adding a check = one function and one row.  A row of builtin_checks() names the CheckKind
//! enumerator of its paper's check; every other row gets the next CheckKind after
//! CheckKind::distance, named by the row (operator<< on CheckKind reads the registry).

#include <array>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "common/enum_names.h"
#include "meshing/core/witness.h"
#include "meshing/voronoi/delaunay.h"
#include "meshing/voronoi/restricted_delaunay.h"

namespace delmesh {

class FlowDistance;  // flow_distance.h

//! A face of Del S, as the driver queues it: a vertex {v, −1, −1}, an edge {p, q, −1} or a
//! triangle {p, q, r}, ids ascending.  Its dual Voronoi face is a cell, a facet or an edge.
using DelaunayFace = std::array<VertexId, 3>;

//! The kind of Delaunay simplex a check examines (its dual: a cell, a facet, a Voronoi edge).
enum class FaceKind { vertex, edge, triangle };
constexpr auto enum_names(FaceKind) {
  return name_table<FaceKind>("FaceKind", {{FaceKind::vertex, "vertex"}, {FaceKind::edge, "edge"},
                                           {FaceKind::triangle, "triangle"}});
}
inline std::ostream& operator<<(std::ostream& out, FaceKind kind) { return write_enum(out, kind); }

//! When a face must be checked again after an insertion of x (the lemma in refinement.h; a
//! deletion re-queues every face within the deleted sample's neighbours for every row).
enum class Dirtied {
  //! The faces dual to simplices containing x: the triangles xqr, the edges xq, the vertex x.
  //! Sound for a check whose witness set is monotone under shrinking of its Voronoi face and
  //! whose generic choices depend only on the face's sites (lemma, part 2).  Any FaceKind.
  new_faces,
  //! Vertex rows: x and the vertices of every triangle that entered or left Tri S|Σ (a function
  //! of the restricted star of the vertex, lemma part 4).
  restricted_star,
  //! Triangle rows: the triangles of Tri S|Σ that are new or whose restricted status or dual
  //! point changed (a function of the triangle's VoronoiEdgeRecord, lemma part 4).
  restricted_triangles
};
constexpr auto enum_names(Dirtied) {
  return name_table<Dirtied>("Dirtied", {{Dirtied::new_faces, "new_faces"},
                                         {Dirtied::restricted_star, "restricted_star"},
                                         {Dirtied::restricted_triangles, "restricted_triangles"}});
}
inline std::ostream& operator<<(std::ostream& out, Dirtied dirtied) { return write_enum(out, dirtied); }

//! Topology rows run from the start (SampleTopology, §5.4) and are what the certificate runs;
//! geometry rows run after Refinement::enable_geometry (DelMesh step 2, §6.2).
enum class CheckPhase { topology, geometry };
constexpr auto enum_names(CheckPhase) {
  return name_table<CheckPhase>("CheckPhase", {{CheckPhase::topology, "topology"},
                                               {CheckPhase::geometry, "geometry"}});
}
inline std::ostream& operator<<(std::ostream& out, CheckPhase phase) { return write_enum(out, phase); }

//! What a check sees besides its face.
struct CheckContext {
  RestrictedDelaunay& restricted;  //!< Del S, its records and facets, the oracle (restricted.oracle())
  CheckKind kind;                  //!< the row's own kind, for its witnesses and unsettled findings
  double lambda = 0;               //!< geometry rows: λ of Refinement::enable_geometry
  std::optional<double> size_bound;  //!< geometry rows: the size bound H, if given
  //! Geometry rows: the distance bound δ of `--max-distance`, if given, with the surface's flow
  //! distance bound (flow_distance.h; not null when max_distance is given).
  std::optional<double> max_distance;
  const FlowDistance* flow_distance = nullptr;
  //! Vertex rows: whether the topology checks that ran before this one came out clean on every
  //! face of the vertex's cell (its Voronoi edges, facets and the cell itself).  The driver
  //! always says true: a row runs only when the queues of the rows before it are empty.  The
  //! certificate says whether its own checks of those faces were clean.
  bool cell_faces_clean = true;
  //! Rows with a generic choice (CheckInfo::generic_choice): 0 for the face's seeded choice, k > 0
  //! for the k-th alternative (attempt_seed()).  Other rows ignore it.
  int attempt = 0;
};

//! One row of the registry.
struct CheckInfo {
  //! The row's function.
  using Function = std::function<CheckResult(const CheckContext& context, const DelaunayFace& face)>;
  CheckInfo() = default;
  //! The six fields every row gives; the optional ones are set afterwards.
  CheckInfo(std::string name, std::string summary, FaceKind face, Dirtied dirtied, CheckPhase phase, Function check)
      : name(std::move(name)), summary(std::move(summary)), face(face), dirtied(dirtied), phase(phase),
        check(std::move(check)) {}

  //! The check's key in the statistics (insertions, checks, seconds_per_check, unsettled), e.g.
  //! "vor_edge"; a registered row's CheckKind prints as this name.
  std::string name;
  std::string summary;  //!< one line: the condition checked and the witness (docs/extending.md, --help)
  FaceKind face = FaceKind::triangle;
  Dirtied dirtied = Dirtied::new_faces;
  CheckPhase phase = CheckPhase::topology;
  //! The check on a face that is in Del S (the driver and the certificate test that first): its
  //! witnesses, points of Σ, in order of preference, and what it could not settle.  Witnesses
  //! are labelled with context.kind (Quality labels its size-bound witnesses CheckKind::size and
  //! its distance-bound ones CheckKind::distance).
  Function check;
  //! Triangle rows, optional: a check that is a function of the triangle's VoronoiEdgeRecord alone may
  //! say from the record that it cannot fire; the driver then does not queue the triangle.
  std::function<bool(const VoronoiEdgeRecord& record)> may_fire;
  //! Edge rows, optional: the check has no witness on a facet F with F ∩ Σ = ∅ (FacetContact,
  //! FacetCycle); the driver then does not queue a new edge whose facet is proved to miss Σ
  //! (RestrictedDelaunay::facet_misses_surface), nor build that facet for it.
  bool silent_off_surface = false;
  //! Geometry rows, optional: whether the row runs at this λ (Smooth: only for λ < 1/6, where
  //! β(λ) is defined).  Default: always.
  std::function<bool(double lambda)> runs_at;
  //! The certificate runs the row on a face only where the earlier rows of the same FaceKind
  //! came out clean on it (FacetCycle's precondition: FacetContact found nothing).  The driver
  //! gives the same by the table's order.
  bool after_clean_predecessors = false;
  //! The row's witness relies on the restricted status of the triangles containing its face
  //! (VorEdge, TopoDisk): the certificate counts it as proved only if none of their records has
  //! an unresolved region.
  bool reads_restricted_status = false;
  //! The row's witnesses depend on a seeded generic choice that CheckContext::attempt varies
  //! (FacetCycle's in-plane direction, Silhouette's d′).  When every witness of the row on a face
  //! is rejected (a duplicate of a sample, or below the termination floor), the driver runs it
  //! again on the face with the next attempt, up to tolerances::generic_choice_attempts choices,
  //! before it leaves the face unsettled.  Any attempt's clean answer is a proof: the lemmas hold
  //! for every direction outside a measure-zero set, and the seeded choices avoid it alike.
  bool generic_choice = false;
  //! Set by the registry: the paper's enumerator for a row of builtin_checks(), the next kind
  //! after CheckKind::distance for any other row.
  CheckKind kind = CheckKind::seed;
};

//! The rows of the paper's checks (meshing/checks/checks.cpp), in the driver's order: VorEdge,
//! FacetContact, TopoDisk, FacetCycle, Silhouette (topology), Quality with the size and distance
//! bounds, Smooth (geometry).
const std::vector<CheckInfo>& builtin_checks();

//! Registers one more row, after the built-in rows of its phase in the order of registration
//! (the table's order is the driver's priority: see check_registry()).  Meant for a namespace-scope
//! object in a file compiled into the program's executable (a file in a static library is linked
//! only if something else in it is used).  Throws PreconditionViolation if the registry has already
//! been read, the name is taken, the row has no check, or `dirtied` does not fit `face`
//! (restricted_star needs vertex rows, restricted_triangles triangle rows).
class CheckRegistration {
 public:
  explicit CheckRegistration(CheckInfo row);
  //! The CheckKind the row will get.
  CheckKind kind() const { return kind_; }

 private:
  CheckKind kind_;
};

//! Every check, each with its kind set: the topology rows (the built-in ones, then the registered
//! ones), then the geometry rows (likewise), so that a topology witness goes in before any
//! geometric one.  Fixed
//! after the first call (which must come after static initialisation, i.e. from main() on).
//! Throws PreconditionViolation if a built-in row does not name a CheckKind enumerator of its own
//! (seed and size are not a row's).
const std::vector<CheckInfo>& check_registry();
//! The row called name; throws InvalidInput listing the known names otherwise.
const CheckInfo& find_check(const std::string& name);

//! The number of CheckKind values: the paper's (seed … size) and one per registered row.
int check_kind_count();
//! The statistics name of a kind ("vor_edge", …; a registered row's name).
std::string check_kind_name(CheckKind kind);

}  // namespace delmesh
