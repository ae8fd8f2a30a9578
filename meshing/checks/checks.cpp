// The rows of the paper's checks (check_registry.h: builtin_checks()), in the driver's order.
// Topology(S), §5.4 steps (a)–(e); then Quality (§6.1) with the size bound beyond the paper, and
// Smooth (§6.2).  Each row's function is the check of its own file; `dirtied` is the lemma of
// refinement.h for that check.
#include "meshing/checks/check_registry.h"

#include "meshing/checks/facet_contact.h"
#include "meshing/checks/facet_cycle.h"
#include "meshing/checks/quality.h"
#include "meshing/checks/silhouette.h"
#include "meshing/checks/smooth.h"
#include "meshing/checks/topo_disk.h"
#include "meshing/checks/vor_edge.h"
#include "meshing/core/theorem_bounds.h"

namespace delmesh {

namespace {

TriangleKey as_triangle(const DelaunayFace& f) { return f; }
EdgeKey as_edge(const DelaunayFace& f) { return {f[0], f[1]}; }

CheckResult from_optional(const std::optional<Witness>& w) {
  CheckResult result;
  if (w) result.witnesses.push_back(*w);
  return result;
}

}  // namespace

const std::vector<CheckInfo>& builtin_checks() {
  static const std::vector<CheckInfo> rows = [] {
    std::vector<CheckInfo> r;
    // (a) VorEdge is a function of the triangle's record: it can fire only on a tangency
    // candidate or two crossings.
    CheckInfo vor_edge{"vor_edge", "VorEdge (Lemma 4.7): the dual Voronoi edge meets Σ at most once, transversally",
                       FaceKind::triangle, Dirtied::new_faces, CheckPhase::topology,
                       [](const CheckContext& c, const DelaunayFace& f) {
                         return vor_edge_witness(c.restricted, as_triangle(f));
                       }};
    vor_edge.may_fire = [](const VoronoiEdgeRecord& rec) {
      return !rec.candidates().empty() || rec.crossings().size() >= 2;
    };
    vor_edge.reads_restricted_status = true;
    vor_edge.kind = CheckKind::vor_edge;
    r.push_back(vor_edge);

    CheckInfo facet_contact{"facet_contact",
                            "FacetContact (Lemma 4.8): Σ is nowhere tangent to the dual Voronoi facet",
                            FaceKind::edge, Dirtied::new_faces, CheckPhase::topology,
                            [](const CheckContext& c, const DelaunayFace& f) {
                              return facet_contact_witness(c.restricted, as_edge(f));
                            }};
    facet_contact.silent_off_surface = true;
    facet_contact.kind = CheckKind::facet_contact;
    r.push_back(facet_contact);

    CheckInfo topo_disk{"topo_disk", "TopoDisk (Lemmas 4.10, 4.12): the restricted star of the sample is a disk",
                        FaceKind::vertex, Dirtied::restricted_star, CheckPhase::topology,
                        [](const CheckContext& c, const DelaunayFace& f) {
                          return topo_disk_witness(c.restricted, f[0]);
                        }};
    topo_disk.reads_restricted_status = true;
    topo_disk.kind = CheckKind::topo_disk;
    r.push_back(topo_disk);

    CheckInfo facet_cycle{"facet_cycle",
                          "FacetCycle (Lemma 4.9): Σ ∩ (dual Voronoi facet) contains no closed curve",
                          FaceKind::edge, Dirtied::new_faces, CheckPhase::topology,
                          [](const CheckContext& c, const DelaunayFace& f) {
                            return facet_cycle_witness(c.restricted, as_edge(f), c.attempt);
                          }};
    facet_cycle.generic_choice = true;
    facet_cycle.after_clean_predecessors = true;
    facet_cycle.silent_off_surface = true;
    facet_cycle.kind = CheckKind::facet_cycle;
    r.push_back(facet_cycle);

    // (e) runs only once (a)–(d) have nothing queued: the faces of V_p are then clean.
    CheckInfo silhouette{"silhouette", "Silhouette (Lemmas 4.13, 4.14): the cell misses the silhouette J_{n_p}",
                         FaceKind::vertex, Dirtied::new_faces, CheckPhase::topology,
                         [](const CheckContext& c, const DelaunayFace& f) {
                           return silhouette_witness(c.restricted, f[0], c.cell_faces_clean, c.attempt);
                         }};
    silhouette.generic_choice = true;
    silhouette.kind = CheckKind::silhouette;
    r.push_back(silhouette);

    CheckInfo quality{"quality",
                      "Quality (§6.1): radius-edge ratio ≤ 1 + λ; with --size-bound H, surface Delaunay "
                      "ball radius ≤ H (witnesses of kind size); with --max-distance δ, the triangle proved "
                      "within δ of Σ (witnesses of kind distance)",
                      FaceKind::triangle, Dirtied::restricted_triangles, CheckPhase::geometry,
                      [](const CheckContext& c, const DelaunayFace& f) {
                        const TriangleKey t = as_triangle(f);
                        auto w = quality_witness(c.restricted, t, c.lambda);
                        if (!w && c.size_bound) w = size_witness(c.restricted, t, *c.size_bound);
                        if (!w && c.max_distance)
                          w = distance_witness(c.restricted, t, *c.max_distance, *c.flow_distance);
                        return from_optional(w);
                      }};
    quality.kind = CheckKind::quality;
    r.push_back(quality);

    // Smooth reads the neighbours across the edges of a restricted triangle; a neighbour whose
    // record changes is re-queued itself.
    CheckInfo smooth{"smooth", "Smooth (§6.2): the roughness of each edge of the restricted triangle is ≤ 2β(λ)",
                     FaceKind::triangle, Dirtied::restricted_triangles, CheckPhase::geometry,
                     [](const CheckContext& c, const DelaunayFace& f) {
                       return smooth_check(c.restricted, as_triangle(f), 2 * beta(c.lambda));
                     }};
    smooth.runs_at = [](double lambda) { return lambda < beta_lambda_bound; };
    smooth.kind = CheckKind::smooth;
    r.push_back(smooth);
    return r;
  }();
  return rows;
}

}  // namespace delmesh
