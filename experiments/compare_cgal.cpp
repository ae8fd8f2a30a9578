//! \file compare_cgal.cpp
//! delmesh against CGAL 5.5.1's Surface_mesher (make_surface_mesh) and Mesh_3 (make_mesh_3 with
//! facet criteria only), in one process run, on catalog surfaces given by their compiled E:
//!  1. benchmark: for each case SURFACE:H (default torus and genus2 at 0.05, torus at 0.02),
//!     delmesh (λ = 0.06, size bound H), Surface_mesher (angle 30°, radius H, distance H/10) and
//!     Mesh_3 (facet_angle 30, facet_size H, facet_distance H/10, no perturb, no exude); the ratio
//!     of delmesh's seconds per output vertex to Mesh_3's (target ≤ 3), the growth of delmesh's
//!     seconds per vertex with the mesh, and its solver calls per vertex by primitive.  With
//!     --repeat K each case runs K rounds of Mesh_3 then delmesh (Surface_mesher in the first
//!     only), every run a CSV row with its round; each round's ratio pairs two runs made one
//!     after the other, so a slow phase of a shared machine tends to hit both, and the summary
//!     gives the median, least and greatest ratio over the rounds.  With --threads-compare N each
//!     round also runs delmesh with N threads right after the --threads run: the summary then
//!     gives that run's ratio to Mesh_3, its wall time over the --threads run's (paired per
//!     round: the speed-up of N threads, as a time ratio) and whether the two meshes were
//!     identical in every round (they must be: the output does not depend on the thread count);
//!  2. coarsest: delmesh at λ = 0.06 without size bound against CGAL at the coarsest of a ladder of
//!     settings that still gives the right topology;
//!  3. demo: CGAL at coarse settings on thin_handle / two_blobs / near_sheets, where it loses a
//!     handle or a component, against delmesh without size bound;
//!  4. distance (only when --experiments names it): for each of --surfaces and each relative
//!     distance r of --relative-distances, δ = r · the catalog box's diagonal; delmesh (λ from
//!     --lambda, no size bound) with max_distance δ, so with the gradient-flow certificate, which
//!     must prove a two-sided Hausdorff bound ≤ δ for the run to be complete, against Mesh_3
//!     (facet_angle from --angle, facet_distance δ, no facet size bound).  Both outputs also get
//!     sampled estimates of their two one-sided distances to Σ (sampled_distances(): estimates,
//!     not bounds).  One row per surface and δ in <out-dir>/distance.csv and distance.md.
//!  5. memory (only when --experiments names it): for each benchmark case, Mesh_3 and delmesh each
//!     in a fresh child process of this program (--memory-child), and a child that only compiles
//!     E (the baseline: the program, its libraries and the surface); each child's own peak
//!     resident memory (common/peak_memory.h, reported by the child), and bytes per output vertex
//!     net of the baseline.  One row per child in
//!     <out-dir>/memory.csv; one summary line per case with delmesh's bytes per vertex over
//!     Mesh_3's.
//! CGAL's implicit oracles locate surface points by bisection, stopped when the segment is shorter
//! than a relative error bound times the bounding sphere's diameter.  CGAL's own default, 1e-3,
//! is about 0.005 on the torus's sphere: no finer than the facet distance H/10 at H ≤ 0.05, so
//! Mesh_3's distance criterion then refines on bisection error (at H = 0.02 it made 520 209
//! vertices where 1e-6 gives about 26 000, as many as Surface_mesher and delmesh).  So the
//! benchmark and distance (whose default δ, 1e-3 of the box diagonal, is no larger) run CGAL with
//! --cgal-error-bound (default 1e-6; delmesh's points are certified roots to full double
//! precision); coarsest and demo keep CGAL's default, the setting users meet.
//! Mesh_3 takes its initial points where rays from one centre first cross Σ, so it can miss a
//! whole component (one blob of two_blobs at every size).  --mesh3-seed-components gives every
//! Mesh_3 run initial points on every component as well: CGAL's intersections of Σ with short
//! segments along ∇E through the certified critical points of a generic height function
//! (delmesh's seed solve; at least two per component); its runs say ";seeded_K" (K points).
//! Every mesh is judged by the independent checker (meshing/core/mesh_checker.h) against the catalog's
//! topology.  Output: <out-dir>/compare_cgal.csv, one row per run of every experiment (and the
//! meshes under <out-dir>/meshes/); distance also writes distance.csv and distance.md.

#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Complex_2_in_triangulation_3.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Labeled_mesh_domain_3.h>
#include <CGAL/Mesh_complex_3_in_triangulation_3.h>
#include <CGAL/Mesh_criteria_3.h>
#include <CGAL/Mesh_triangulation_3.h>
#include <CGAL/Surface_mesh_default_criteria_3.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/make_mesh_3.h>
#include <CGAL/make_surface_mesh.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "common/errors.h"
#include "common/huge_page_heap.h"
#include "common/peak_memory.h"
#include "experiments/child_process.h"
#include "experiments/experiment_support.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/implicit_oracle.h"
#include "meshing/inputs/mesh_io.h"
#include "meshing/inputs/seed_solve.h"
#include "solvers/domain.h"
#include "symbolic/catalog.h"

namespace {

using namespace delmesh;
using namespace delmesh::experiments;
namespace fs = std::filesystem;

struct CgalSettings {
  //! radius 0: no size bound, for Mesh_3 only (Mesh_facet_criteria_3 adds no size criterion for a
  //! facet_size of 0, as when it is not given); Surface_mesher needs a positive radius.
  double angle_deg = 30, radius = 0.05, distance = 0.005;
  //! The bisection of CGAL's implicit oracles stops when the segment is shorter than this times
  //! the bounding sphere's diameter; CGAL's default, and named in text() only when it differs.
  static constexpr double cgal_default_error_bound = 1e-3;
  double relative_error_bound = cgal_default_error_bound;
  std::string text() const {
    std::ostringstream out;
    out << "angle=" << angle_deg << ";radius=";
    if (radius > 0) {
      out << radius;
    } else {
      out << "none";
    }
    out << ";distance=" << distance;
    if (relative_error_bound != cgal_default_error_bound) out << ";relative_error_bound=" << relative_error_bound;
    return out.str();
  }
};

//! One mesher run: the output as a soup, how long it took, and how it ended.
struct Run {
  std::string method, parameters, status = "complete";
  TriangleSoup soup;
  double seconds = 0;
  nlohmann::json statistics;  //!< delmesh's statistics record (empty for CGAL)
};

//! Orients every triangle so that its normal agrees with ∇E at its centroid (outward for E < 0
//! inside).  Only for the written files; the checker decides orientability itself.
void orient_by_gradient(TriangleSoup& soup, const CompiledE& E) {
  for (auto& t : soup.triangles) {
    const Point3 &a = soup.points[t[0]], &b = soup.points[t[1]], &c = soup.points[t[2]];
    const Vector3 n = CGAL::cross_product(b - a, c - a);
    const std::array<double, 3> g_at{(a.x() + b.x() + c.x()) / 3, (a.y() + b.y() + c.y()) / 3,
                                     (a.z() + b.z() + c.z()) / 3};
    std::array<double, 3> g{};
    E.value_and_gradient(g_at, g);
    if (n.x() * g[0] + n.y() * g[1] + n.z() * g[2] < 0) std::swap(t[1], t[2]);
  }
}

//! The facets of a CGAL complex as a soup, vertices numbered in order of first appearance.
template <class FacetIterator, class ToPoint>
TriangleSoup soup_of_facets(FacetIterator begin, FacetIterator end, ToPoint to_point) {
  TriangleSoup soup;
  std::unordered_map<const void*, std::size_t> index;
  for (auto it = begin; it != end; ++it) {
    const auto cell = it->first;
    const int opposite = it->second;
    std::array<std::size_t, 3> triangle{};
    for (int k = 0; k < 3; ++k) {
      const auto vertex = cell->vertex((opposite + 1 + k) & 3);
      const auto [at, inserted] = index.emplace(&*vertex, soup.points.size());
      if (inserted) soup.points.push_back(to_point(vertex->point()));
      triangle[k] = at->second;
    }
    soup.triangles.push_back(triangle);
  }
  return soup;
}

// --- CGAL Surface_mesher -------------------------------------------------------------------------
using SmTriangulation = CGAL::Surface_mesh_default_triangulation_3;
using SmComplex = CGAL::Complex_2_in_triangulation_3<SmTriangulation>;
using SmTraits = SmTriangulation::Geom_traits;
using SmSurface = CGAL::Implicit_surface_3<SmTraits, std::function<SmTraits::FT(SmTraits::Point_3)>>;

//! Seed of CGAL's default random generator, reset before every CGAL run so that the runs are
//! reproducible (CGAL seeds it from the clock otherwise; Surface_mesher's initial points use it).
unsigned int cgal_seed = 0;

Run run_surface_mesher(const CompiledE& E, const std::array<double, 3>& centre, double squared_radius,
                       const CgalSettings& s) {
  CGAL::get_default_random() = CGAL::Random(cgal_seed);
  Run run;
  run.method = "surface_mesher";
  run.parameters = s.text() + ";manifold_tag";
  const Stopwatch clock;
  SmTriangulation triangulation;
  SmComplex complex(triangulation);
  SmSurface surface([E](SmTraits::Point_3 p) { return E(p.x(), p.y(), p.z()); },
                    SmTraits::Sphere_3(SmTraits::Point_3(centre[0], centre[1], centre[2]), squared_radius),
                    s.relative_error_bound);
  CGAL::Surface_mesh_default_criteria_3<SmTriangulation> criteria(s.angle_deg, s.radius, s.distance);
  CGAL::make_surface_mesh(complex, surface, criteria, CGAL::Manifold_tag());
  run.soup = soup_of_facets(complex.facets_begin(), complex.facets_end(),
                            [](const SmTraits::Point_3& p) { return Point3(p.x(), p.y(), p.z()); });
  run.seconds = clock.seconds();
  return run;
}

// --- CGAL Mesh_3 ---------------------------------------------------------------------------------
using MeshDomain = CGAL::Labeled_mesh_domain_3<Kernel>;
using M3Triangulation = CGAL::Mesh_triangulation_3<MeshDomain>::type;
using M3Complex = CGAL::Mesh_complex_3_in_triangulation_3<M3Triangulation>;
using M3Criteria = CGAL::Mesh_criteria_3<M3Triangulation>;

//! Mesh_3's domain with more initial points: Labeled_mesh_domain_3's own (where rays from the
//! bounding sphere's centre to random points of its boundary first cross Σ, so a component that no
//! such ray meets first gets none, and Mesh_3 never finds it), then one per seed.  For a seed p
//! with unit gradient direction n, the point is CGAL's own intersection of Σ with the segment
//! [p - r n, p + r n] (r = seed_reach), with its surface patch index; a seed whose segment CGAL
//! does not find crossing Σ is skipped.  Everything else is the wrapped domain's.
class SeededMeshDomain : public MeshDomain {
 public:
  struct Seed {
    Point3 point;
    Vector3 normal;  //!< unit
  };
  SeededMeshDomain(MeshDomain domain, std::vector<Seed> seeds, double seed_reach)
      : MeshDomain(std::move(domain)), seeds_(std::move(seeds)), reach_(seed_reach) {}

  struct Construct_initial_points {
    const SeededMeshDomain& domain;
    //! Writes the wrapped domain's initial points (its default count), then one
    //! std::pair<Point_3, Index> per seed that CGAL finds on Σ.
    template <class OutputIterator>
    OutputIterator operator()(OutputIterator out) const {
      return add_seeds(domain.MeshDomain::construct_initial_points_object()(out));
    }
    //! The same with `n` points of the wrapped domain.
    template <class OutputIterator>
    OutputIterator operator()(OutputIterator out, int n) const {
      return add_seeds(domain.MeshDomain::construct_initial_points_object()(out, n));
    }
    template <class OutputIterator>
    OutputIterator add_seeds(OutputIterator out) const {
      const auto crosses = domain.do_intersect_surface_object();
      const auto intersection = domain.construct_intersection_object();
      for (const Seed& s : domain.seeds_) {
        const Kernel::Segment_3 segment(s.point - domain.reach_ * s.normal, s.point + domain.reach_ * s.normal);
        if (!crosses(segment)) continue;
        const auto hit = intersection(segment);
        *out++ = std::make_pair(std::get<0>(hit), std::get<1>(hit));
      }
      return out;
    }
  };
  Construct_initial_points construct_initial_points_object() const { return Construct_initial_points{*this}; }
  std::size_t seed_count() const { return seeds_.size(); }

 private:
  std::vector<Seed> seeds_;
  double reach_;
};

//! The critical points of a generic height function on Σ (delmesh's seed solve,
//! meshing/inputs/seed_solve.h, certified: each in a box holding exactly one) with the unit
//! direction of ∇E there: at least two (a least and a greatest height) on every component of Σ.
//! Throws InvalidInput when the solve leaves a region undecided or finds no point.
std::vector<SeededMeshDomain::Seed> component_seeds(const CatalogEntry& entry, const CompiledE& E) {
  ImplicitOracle oracle(entry.surface(), entry.box, SolverBackend::subdivision);
  const Box3& b = entry.box;
  const Domain domain = Domain::from_box({{b.lo[0], b.hi[0]}, {b.lo[1], b.hi[1]}, {b.lo[2], b.hi[2]}});
  const SolveResult r = seed_solve(oracle, generic_direction(1, 0), domain);
  if (r.status != SolveStatus::complete || !r.undecided.empty() || r.roots.empty())
    throw InvalidInput("--mesh3-seed-components: the seed solve on " + entry.name + " was not complete");
  std::vector<SeededMeshDomain::Seed> seeds;
  for (const CertifiedRoot& root : r.roots) {
    std::array<double, 3> g{};
    E.value_and_gradient(root.world, g);
    const double length = std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
    seeds.push_back({Point3(root.world[0], root.world[1], root.world[2]),
                     Vector3(g[0] / length, g[1] / length, g[2] / length)});
  }
  return seeds;
}

//! Mesh_3 with CGAL's initial points, and, when `seeds` is not empty, a SeededMeshDomain's seed
//! points too (each seed segment 1e-3 of the bounding sphere's diameter long on either side).
Run run_mesh_3(const CompiledE& E, const std::array<double, 3>& centre, double squared_radius,
               const CgalSettings& s, const std::vector<SeededMeshDomain::Seed>& seeds = {}) {
  CGAL::get_default_random() = CGAL::Random(cgal_seed);
  Run run;
  run.method = "mesh_3";
  run.parameters = s.text() + ";facet_criteria_only;no_perturb;no_exude";
  if (!seeds.empty()) run.parameters += ";seeded_" + std::to_string(seeds.size());
  const Stopwatch clock;
  namespace p = CGAL::parameters;
  MeshDomain domain = MeshDomain::create_implicit_mesh_domain(
      std::function<double(const Point3&)>([E](const Point3& q) { return E(q.x(), q.y(), q.z()); }),
      Kernel::Sphere_3(Point3(centre[0], centre[1], centre[2]), squared_radius),
      p::relative_error_bound = s.relative_error_bound);
  M3Criteria criteria(p::facet_angle = s.angle_deg, p::facet_size = s.radius, p::facet_distance = s.distance);
  M3Complex complex;
  if (seeds.empty()) {
    complex = CGAL::make_mesh_3<M3Complex>(domain, criteria, p::no_perturb(), p::no_exude());
  } else {
    const SeededMeshDomain seeded(std::move(domain), seeds, 2e-3 * std::sqrt(squared_radius));
    complex = CGAL::make_mesh_3<M3Complex>(seeded, criteria, p::no_perturb(), p::no_exude());
  }
  const auto to_point = [](const M3Triangulation::Point& wp) {
    return Point3(wp.point().x(), wp.point().y(), wp.point().z());
  };
  run.soup = soup_of_facets(complex.facets_in_complex_begin(), complex.facets_in_complex_end(), to_point);
  run.seconds = clock.seconds();
  return run;
}

// --- delmesh -------------------------------------------------------------------------------------
//! The number of threads a delmesh run used (its statistics' count; `requested` if it has none).
std::string threads_used(const Run& run, int requested) {
  return field(run.statistics.is_object() ? run.statistics.value("threads", requested) : requested);
}

//! `text` with the characters that would break a CSV field or a Markdown cell (',', '|', newline)
//! replaced by ';'.
std::string cell_text(std::string text) {
  for (char& c : text)
    if (c == ',' || c == '|' || c == '\n') c = ';';
  return text;
}

//! A delmesh run at λ with size bound H and distance bound δ where given.  The gradient-flow
//! certificate runs only with δ (del_mesh runs it then, as the run is complete only if it proves
//! the bound); without δ the run is timed against meshers that certify nothing.
Run run_delmesh(const CatalogEntry& entry, double lambda, std::optional<double> size_bound,
                const DelMeshOptions& base, std::optional<double> max_distance = std::nullopt) {
  Run run;
  run.method = "delmesh";
  std::ostringstream parameters;
  parameters << "lambda=" << lambda << ";size_bound=";
  if (size_bound) {
    parameters << *size_bound;
  } else {
    parameters << "none";
  }
  if (max_distance) parameters << ";max_distance=" << *max_distance;
  parameters << ";seed=" << base.seed;
  run.parameters = parameters.str();
  DelMeshOptions options = base;
  options.lambda = lambda;
  options.size_bound = size_bound;
  options.max_distance = max_distance;
  options.distance_certificate = false;
  const Stopwatch clock;
  try {
    DelMeshResult result = del_mesh(entry.surface(), entry.box, options);
    run.seconds = clock.seconds();
    std::ostringstream status;
    status << result.status;
    run.status = status.str();
    run.statistics = result.statistics;
    mesh_to_soup(result.mesh, run.soup.points, run.soup.triangles);
  } catch (const std::exception& e) {
    run.seconds = clock.seconds();
    run.status = cell_text(std::string("error: ") + e.what());
  }
  run.parameters += ";threads=" + threads_used(run, options.threads);
  return run;
}

struct Context {
  fs::path out_dir;
  bool write_meshes = true;
  CsvWriter* csv = nullptr;
};

std::vector<std::string> csv_columns() {
  std::vector<std::string> columns{"experiment", "surface", "method", "parameters", "round", "status", "seconds",
                                   "seconds_per_vertex", "expected_genus", "topology_correct"};
  append(columns, report_columns());
  return columns;
}

//! Checks, prints, writes the mesh and the CSV row of one run (round `round` of its case);
//! returns the checker's report.
MeshReport record(Context& context, const std::string& experiment, const CatalogEntry& entry, Run& run,
                  const CompiledE& E, int round = 1) {
  MeshReport report;
  if (!run.soup.triangles.empty()) report = check_mesh(run.soup.points, run.soup.triangles);
  const bool correct = report.has_topology(entry.genus_per_component);
  const double per_vertex = report.vertices ? run.seconds / static_cast<double>(report.vertices) : 0.0;
  std::cout << experiment << " " << entry.name << " " << run.method << " [" << run.parameters << "] "
            << run.status << ": " << report.vertices << " vertices, min angle " << report.min_angle_deg
            << " deg, components " << report.components << ", genus " << field(report.genus_per_component)
            << (correct ? " (correct)" : " (WRONG, expected " + field(entry.genus_per_component) + ")") << ", "
            << run.seconds << " s" << std::endl;
  std::vector<std::string> row{experiment, entry.name, run.method, run.parameters, field(round), run.status,
                               field(run.seconds), field(per_vertex), field(entry.genus_per_component),
                               field(correct)};
  append(row, report_fields(report));
  context.csv->row(row);
  if (context.write_meshes && !run.soup.triangles.empty()) {
    if (run.method != "delmesh") orient_by_gradient(run.soup, E);
    std::string settings = run.parameters;
    for (char& c : settings)
      if (c == ';' || c == '=') c = '_';
    const fs::path mesh_dir = context.out_dir / "meshes";
    fs::create_directories(mesh_dir);
    const std::string stem = "compare_" + experiment + "_" + entry.name + "_" + run.method + "_" + settings;
    write_triangle_soup(run.soup, (mesh_dir / (stem + ".off")).string());
    if (!run.statistics.is_null()) std::ofstream(mesh_dir / (stem + ".json")) << run.statistics.dump(1) << '\n';
  }
  return report;
}

double seconds_per_vertex(const Run& run) {
  std::size_t referenced = 0;
  if (!run.soup.triangles.empty()) referenced = check_mesh(run.soup.points, run.soup.triangles).vertices;
  return referenced ? run.seconds / static_cast<double>(referenced) : std::numeric_limits<double>::quiet_NaN();
}

//! The values of a list that are numbers (a run without a mesh has NaN seconds per vertex), sorted.
std::vector<double> sorted_numbers(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values)
    if (!std::isnan(v)) out.push_back(v);
  std::sort(out.begin(), out.end());
  return out;
}

//! The median of the numbers of a list (the mean of the middle two for an even count); NaN if
//! there are none.
double median(const std::vector<double>& values) {
  const std::vector<double> v = sorted_numbers(values);
  const std::size_t n = v.size();
  if (n == 0) return std::numeric_limits<double>::quiet_NaN();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

//! Whether two runs wrote the same mesh: the same points (bit for bit) and triangles, in order.
bool same_mesh(const Run& a, const Run& b) {
  return a.soup.points == b.soup.points && a.soup.triangles == b.soup.triangles;
}

//! " (median of K rounds, least L, greatest G)" for more than one number, else "".
std::string spread(const std::vector<double>& values) {
  const auto range = sorted_numbers(values);
  if (range.size() < 2) return "";
  std::ostringstream out;
  out << " (median of " << range.size() << " rounds, least " << range.front() << ", greatest " << range.back() << ")";
  return out.str();
}

std::string field_list(const std::vector<double>& values) {
  std::string text;
  for (double v : values) text += (text.empty() ? "" : ";") + field(v);
  return text;
}

//! A catalog surface ready for the meshers: its entry, compiled E, and the CGAL meshers' bounding
//! sphere (a centre inside Σ and a squared radius that contains the box).
struct Prepared {
  const CatalogEntry* entry;
  CompiledE E;
  std::array<double, 3> centre;
  double squared_radius;
  std::vector<SeededMeshDomain::Seed> mesh3_seeds;  //!< Mesh_3's initial points; empty: CGAL's
};

//! --mesh3-seed-components: Mesh_3 starts from component_seeds() as well as from its own rays.
bool mesh3_seed_components = false;

Prepared prepare(const std::string& name) {
  const CatalogEntry& entry = catalog_entry(name);
  CompiledE E(entry.surface());
  const auto centre = inside_point(E, entry.box);
  Prepared s{&entry, E, centre, enclosing_squared_radius(centre, entry.box), {}};
  if (mesh3_seed_components) s.mesh3_seeds = component_seeds(entry, s.E);
  return s;
}

// --- sampled distances between a mesh and Σ ------------------------------------------------------
//! Intervals per triangle edge of the barycentric grid of mesh → Σ samples ((n+1)(n+2)/2 points a
//! triangle; n a multiple of 3, so the centroid is one of them).
constexpr int mesh_samples_per_edge = 6;
//! Grid cells along the box's longest side for the Σ → mesh samples.
constexpr int surface_sample_cells = 160;

//! A point of Σ reached from p by Newton steps p ← p − E ∇E/|∇E|² (each at most 0.05 of the
//! box diagonal long), once |E|/|∇E| < 1e-10 of the diagonal; nothing if that takes more than 50
//! steps or ∇E vanishes on the way.
std::optional<std::array<double, 3>> newton_onto_surface(const CompiledE& E, std::array<double, 3> p,
                                                         double diagonal) {
  for (int step = 0; step < 50; ++step) {
    std::array<double, 3> g{};
    const double e = E.value_and_gradient(p, g);
    const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
    if (!(gg > 0) || !std::isfinite(e)) return std::nullopt;
    const double first_order = std::abs(e) / std::sqrt(gg);
    if (first_order < 1e-10 * diagonal) return p;
    const double scale = std::min(1.0, 0.05 * diagonal / first_order) * e / gg;
    for (int k = 0; k < 3; ++k) p[k] -= scale * g[k];
  }
  return std::nullopt;
}

//! Points of Σ independent of any mesh: the nodes of a regular grid of the box
//! (surface_sample_cells cells along its longest side) whose first-order distance |E|/|∇E| is
//! below one cell, moved onto Σ by newton_onto_surface (a node that does not converge is left
//! out).  Their covering radius of Σ is about one cell.
std::vector<Point3> surface_sample(const CompiledE& E, const Box3& box) {
  double longest = 0;
  for (int k = 0; k < 3; ++k) longest = std::max(longest, box.hi[k] - box.lo[k]);
  const double cell = longest / surface_sample_cells;
  std::array<int, 3> nodes{};
  for (int k = 0; k < 3; ++k) nodes[k] = static_cast<int>(std::ceil((box.hi[k] - box.lo[k]) / cell)) + 1;
  std::vector<Point3> sample;
  for (int i = 0; i < nodes[0]; ++i)
    for (int j = 0; j < nodes[1]; ++j)
      for (int k = 0; k < nodes[2]; ++k) {
        const std::array<double, 3> p{box.lo[0] + i * cell, box.lo[1] + j * cell, box.lo[2] + k * cell};
        std::array<double, 3> g{};
        const double e = E.value_and_gradient(p, g);
        if (!(std::abs(e) < cell * std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]))) continue;
        if (const auto q = newton_onto_surface(E, p, box.diagonal())) sample.emplace_back((*q)[0], (*q)[1], (*q)[2]);
      }
  return sample;
}

//! Sampled estimates (not bounds) of the two one-sided distances between a mesh and Σ.
//! mesh_to_surface: the largest |x − p| over the points x of a barycentric grid on every triangle
//! (mesh_samples_per_edge per edge) and p = newton_onto_surface(x), a point of Σ, so each term is
//! at least x's distance to Σ (equal when p is x's nearest point, which the projection along ∇E
//! approximates to second order); x between the grid points is not seen.  surface_to_mesh: the
//! largest exact distance (CGAL AABB tree) from a point of surface_sample() to the mesh: as those
//! points lie on Σ (up to the projection's 1e-10 of the diagonal), a lower bound on the one-sided
//! Hausdorff distance from Σ, short of it by at most about the sample's covering radius.
struct SampledDistance {
  double mesh_to_surface = std::numeric_limits<double>::quiet_NaN();
  double surface_to_mesh = std::numeric_limits<double>::quiet_NaN();
  std::size_t unprojected = 0;  //!< mesh samples whose projection did not converge (left out)
  double hausdorff() const { return std::max(mesh_to_surface, surface_to_mesh); }
};

double sampled_mesh_to_surface(const TriangleSoup& soup, const CompiledE& E, double diagonal,
                               std::size_t& unprojected) {
  constexpr int n = mesh_samples_per_edge;
  double largest = 0;
  for (const auto& t : soup.triangles) {
    const Point3 &a = soup.points[t[0]], &b = soup.points[t[1]], &c = soup.points[t[2]];
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const Point3 x = a + (b - a) * (static_cast<double>(i) / n) + (c - a) * (static_cast<double>(j) / n);
        const auto p = newton_onto_surface(E, {x.x(), x.y(), x.z()}, diagonal);
        if (!p) {
          ++unprojected;
          continue;
        }
        largest = std::max(largest, std::sqrt(CGAL::squared_distance(x, Point3((*p)[0], (*p)[1], (*p)[2]))));
      }
  }
  return largest;
}

SampledDistance sampled_distances(const TriangleSoup& soup, const CompiledE& E, double diagonal,
                                  const std::vector<Point3>& surface_points) {
  SampledDistance d;
  if (soup.triangles.empty()) return d;
  d.mesh_to_surface = sampled_mesh_to_surface(soup, E, diagonal, d.unprojected);
  using Triangles = std::vector<Kernel::Triangle_3>;
  using Primitive = CGAL::AABB_triangle_primitive<Kernel, Triangles::const_iterator>;
  using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
  Triangles triangles;
  triangles.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles)
    triangles.emplace_back(soup.points[t[0]], soup.points[t[1]], soup.points[t[2]]);
  Tree tree(triangles.begin(), triangles.end());
  tree.accelerate_distance_queries();
  d.surface_to_mesh = 0;
  for (const Point3& p : surface_points) d.surface_to_mesh = std::max(d.surface_to_mesh, tree.squared_distance(p));
  d.surface_to_mesh = std::sqrt(d.surface_to_mesh);
  return d;
}

// --- experiment distance -------------------------------------------------------------------------
//! The numbers of a comma-separated list; throws InvalidInput (naming `option`) for an item that
//! is not a positive finite number.
std::vector<double> positive_numbers(const std::string& option, const std::string& text) {
  std::vector<double> values;
  for (const std::string& item : split(text)) {
    std::size_t used = 0;
    double value = std::numeric_limits<double>::quiet_NaN();
    try {
      value = std::stod(item, &used);
    } catch (const std::exception&) {
    }
    if (used != item.size() || !(std::isfinite(value) && value > 0))
      throw InvalidInput(option + ": expected positive numbers, got '" + item + "'");
    values.push_back(value);
  }
  if (values.empty()) throw InvalidInput(option + ": no value given");
  return values;
}

//! The settings of the distance experiment (main() reads them from the command line).
struct DistanceExperiment {
  std::vector<std::string> surfaces;
  std::vector<double> relative_distances;
  double lambda = lambda0;
  DelMeshOptions base;
  double cgal_angle = 30, cgal_error_bound = 1e-6;
  bool skip_delmesh = false;
};

//! One mesher's output in the distance experiment.
struct DistanceMeasure {
  std::string status = "not run";
  std::size_t vertices = 0;
  bool topology_correct = false;
  double seconds = std::numeric_limits<double>::quiet_NaN();
  SampledDistance sampled;
};

//! One row of distance.csv: a surface and δ, both meshers, and delmesh's certificate (its
//! statistics' "distance": status, hausdorff_upper_bound, reason, seconds).
struct DistanceRow {
  std::string surface;
  double relative = 0, delta = 0;
  DistanceMeasure delmesh, mesh_3;
  std::string certificate_status = "not run", certificate_reason;
  double certified_bound = std::numeric_limits<double>::quiet_NaN();
  double certificate_seconds = std::numeric_limits<double>::quiet_NaN();
};

//! A column of distance.csv with its value in full (CSV) and short (Markdown) form; `shown`: also
//! a column of distance.md.
struct Cell {
  std::string name, csv, markdown;
  bool shown;
};

Cell text_cell(const std::string& name, const std::string& value, bool shown) {
  return {name, cell_text(value), cell_text(value), shown};
}
//! Markdown shows `digits` significant digits (6 where a value is compared with δ, so that a bound
//! just below δ does not read as δ).
Cell number_cell(const std::string& name, double value, bool shown, int digits = 4) {
  std::ostringstream brief;
  brief << std::setprecision(digits) << value;
  return {name, field(value), std::isnan(value) ? "–" : brief.str(), shown};
}

void append_measure(std::vector<Cell>& cells, const std::string& prefix, const DistanceMeasure& m) {
  cells.push_back(text_cell(prefix + "_status", m.status, prefix == "delmesh"));
  cells.push_back(text_cell(prefix + "_vertices", field(m.vertices), true));
  cells.push_back(text_cell(prefix + "_topology_correct", field(m.topology_correct), true));
  cells.push_back(number_cell(prefix + "_seconds", m.seconds, true));
  cells.push_back(number_cell(prefix + "_sampled_mesh_to_surface_estimate", m.sampled.mesh_to_surface, true));
  cells.push_back(number_cell(prefix + "_sampled_surface_to_mesh", m.sampled.surface_to_mesh, true));
  cells.push_back(number_cell(prefix + "_sampled_hausdorff_estimate", m.sampled.hausdorff(), false));
  cells.push_back(text_cell(prefix + "_unprojected_samples", field(m.sampled.unprojected), false));
}

//! The cells of a row, in column order (the column names are those of any row).
std::vector<Cell> distance_cells(const DistanceRow& r) {
  std::vector<Cell> cells{text_cell("surface", r.surface, true), number_cell("relative_distance", r.relative, true),
                          number_cell("delta", r.delta, true, 6)};
  append_measure(cells, "delmesh", r.delmesh);
  cells.push_back(text_cell("certificate_status", r.certificate_status, true));
  cells.push_back(number_cell("certified_hausdorff_bound", r.certified_bound, true, 6));
  cells.push_back(number_cell("certified_bound_over_delta", r.certified_bound / r.delta, true, 6));
  cells.push_back(number_cell("certificate_seconds", r.certificate_seconds, false));
  cells.push_back(text_cell("certificate_reason", r.certificate_reason, false));
  append_measure(cells, "mesh_3", r.mesh_3);
  const double vertices_ratio = r.mesh_3.vertices ? static_cast<double>(r.delmesh.vertices) / r.mesh_3.vertices
                                                  : std::numeric_limits<double>::quiet_NaN();
  cells.push_back(number_cell("vertices_ratio", vertices_ratio, true));
  cells.push_back(number_cell("seconds_ratio", r.delmesh.seconds / r.mesh_3.seconds, true));
  return cells;
}

std::vector<std::string> distance_columns() {
  std::vector<std::string> names;
  for (const Cell& c : distance_cells(DistanceRow{})) names.push_back(c.name);
  return names;
}

//! Records a run (record()) and measures its sampled distances.
DistanceMeasure measure(Context& context, const Prepared& s, Run& run, const std::vector<Point3>& surface_points) {
  const MeshReport report = record(context, "distance", *s.entry, run, s.E);
  DistanceMeasure m;
  m.status = run.status;
  m.vertices = report.vertices;
  m.topology_correct = report.has_topology(s.entry->genus_per_component);
  m.seconds = run.seconds;
  m.sampled = sampled_distances(run.soup, s.E, s.entry->box.diagonal(), surface_points);
  return m;
}

DistanceRow distance_row(Context& context, const DistanceExperiment& x, const Prepared& s,
                         const std::vector<Point3>& surface_points, double relative) {
  DistanceRow row;
  row.surface = s.entry->name;
  row.relative = relative;
  row.delta = relative * s.entry->box.diagonal();
  if (!x.skip_delmesh) {
    Run dm = run_delmesh(*s.entry, x.lambda, std::nullopt, x.base, row.delta);
    row.delmesh = measure(context, s, dm, surface_points);
    const nlohmann::json none = nlohmann::json::object();
    const nlohmann::json certificate = dm.statistics.is_object() ? dm.statistics.value("distance", none) : none;
    row.certificate_status = certificate.value("status", std::string("none"));
    row.certificate_reason = certificate.value("reason", std::string());
    row.certified_bound = certificate.value("hausdorff_upper_bound", std::numeric_limits<double>::quiet_NaN());
    row.certificate_seconds = certificate.value("seconds", std::numeric_limits<double>::quiet_NaN());
  }
  const CgalSettings settings{x.cgal_angle, 0, row.delta, x.cgal_error_bound};
  Run m3 = run_mesh_3(s.E, s.centre, s.squared_radius, settings, s.mesh3_seeds);
  row.mesh_3 = measure(context, s, m3, surface_points);
  std::cout << "distance " << row.surface << " delta=" << row.delta << ": delmesh " << row.delmesh.status << ", "
            << row.delmesh.vertices << " vertices, " << row.delmesh.seconds << " s, certificate "
            << row.certificate_status << " bound " << row.certified_bound << " (" << row.certified_bound / row.delta
            << " delta)" << (row.certificate_reason.empty() ? "" : ", reason: " + row.certificate_reason)
            << ", sampled " << row.delmesh.sampled.hausdorff() << "; Mesh_3 " << row.mesh_3.vertices << " vertices, "
            << row.mesh_3.seconds << " s, sampled " << row.mesh_3.sampled.hausdorff() << std::endl;
  // The sampled surface-to-mesh distance is a lower bound up to the projection tolerance.
  if (row.certificate_status == "certified" &&
      row.delmesh.sampled.surface_to_mesh > row.certified_bound + 1e-9 * s.entry->box.diagonal())
    std::cout << "distance " << row.surface << " delta=" << row.delta << ": UNSOUND? the sampled surface-to-mesh "
              << "distance " << row.delmesh.sampled.surface_to_mesh << " exceeds the certified bound" << std::endl;
  return row;
}

//! distance.md: a title, a line on the settings, and the rows' shown cells as a table.
void write_distance_markdown(const fs::path& path, const DistanceExperiment& x, const std::vector<DistanceRow>& rows) {
  std::ofstream out(path);
  out << "# compare_cgal distance (git " << git_revision() << ", CGAL " << CGAL_VERSION_STR << ", " << utc_now()
      << ")\n\n"
      << "delta = relative_distance x the box diagonal. delmesh: lambda=" << x.lambda
      << ", max_distance=delta (complete only if the gradient-flow certificate proves a two-sided Hausdorff "
         "bound <= delta), seconds including the certificate. Mesh_3: facet_angle="
      << x.cgal_angle << ", facet_distance=delta, no facet size bound, relative_error_bound=" << x.cgal_error_bound
      << ", no perturb, no exude. Sampled distances (compare_cgal.cpp, sampled_distances): "
         "*_sampled_mesh_to_surface_estimate from Newton projections of a grid on every triangle, an estimate; "
         "*_sampled_surface_to_mesh the largest exact distance from sampled points of the surface to the mesh, a "
         "lower bound on the two-sided Hausdorff distance. Ratios: delmesh over Mesh_3.\n\n";
  std::string header, rule;
  for (const Cell& c : distance_cells(DistanceRow{}))
    if (c.shown) {
      header += "| " + c.name + " ";
      rule += "|---";
    }
  out << header << "|\n" << rule << "|\n";
  for (const DistanceRow& row : rows) {
    for (const Cell& c : distance_cells(row))
      if (c.shown) out << "| " << c.markdown << " ";
    out << "|\n";
  }
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

void run_distance_experiment(Context& context, const DistanceExperiment& x) {
  CsvWriter csv(context.out_dir / "distance.csv", "compare_cgal",
                {{"experiment", "distance"},
                 {"lambda", field(x.lambda)},
                 {"cgal_angle", field(x.cgal_angle)},
                 {"cgal_error_bound", field(x.cgal_error_bound)},
                 {"mesh_samples_per_edge", field(mesh_samples_per_edge)},
                 {"surface_sample_cells", field(surface_sample_cells)},
                 {"seed", field(static_cast<long long>(x.base.seed))},
                 {"cgal_seed", field(static_cast<long long>(cgal_seed))},
                 {"time_limit", field(x.base.time_limit_seconds)},
                 {"cgal", CGAL_VERSION_STR}},
                distance_columns());
  std::vector<DistanceRow> rows;
  for (const std::string& name : x.surfaces) {
    const Prepared s = prepare(name);
    const std::vector<Point3> surface_points = surface_sample(s.E, s.entry->box);
    std::cout << "distance " << name << ": " << surface_points.size() << " points of the surface sample" << std::endl;
    for (double relative : x.relative_distances) {
      rows.push_back(distance_row(context, x, s, surface_points, relative));
      std::vector<std::string> fields;
      for (const Cell& c : distance_cells(rows.back())) fields.push_back(c.csv);
      csv.row(fields);
    }
  }
  csv.close();
  write_distance_markdown(context.out_dir / "distance.md", x, rows);
  std::cout << "wrote " << csv.path().string() << " and " << (context.out_dir / "distance.md").string() << std::endl;
}

//! SURFACE:H of --cases: the catalog name and the size bound.  Throws InvalidInput otherwise.
std::pair<std::string, double> parse_case(const std::string& item) {
  const auto colon = item.find(':');
  if (colon == std::string::npos) throw InvalidInput("--cases: expected SURFACE:H, got '" + item + "'");
  const std::vector<double> h = positive_numbers("--cases", item.substr(colon + 1));
  if (h.size() != 1) throw InvalidInput("--cases: expected one positive H in '" + item + "'");
  return {item.substr(0, colon), h.front()};
}

// --- memory --------------------------------------------------------------------------------------
//! The mesher settings a memory child runs with (the parent's, passed on its command line).
struct MemorySettings {
  double lambda, cgal_angle, cgal_error_bound;
  DelMeshOptions base;
};

//! The child's side: runs `method` (mesh_3, delmesh, or none: only compile E) on one case and
//! prints "vertices N", "seconds S", "status X" and "peak_bytes B" (its own peak resident memory,
//! common/peak_memory.h) on stdout.
void run_memory_child(const std::string& method, const std::string& item, const MemorySettings& m) {
  const auto [name, h] = parse_case(item);
  const Prepared s = prepare(name);
  Run run;
  if (method == "mesh_3") {
    run = run_mesh_3(s.E, s.centre, s.squared_radius, CgalSettings{m.cgal_angle, h, h / 10, m.cgal_error_bound},
                     s.mesh3_seeds);
  } else if (method == "delmesh") {
    run = run_delmesh(*s.entry, m.lambda, h, m.base);
  } else if (method != "none") {
    throw InvalidInput("--memory-child: expected mesh_3, delmesh or none, got '" + method + "'");
  }
  std::cout << "vertices " << run.soup.points.size() << "\nseconds " << field(run.seconds) << "\nstatus "
            << (method == "none" ? std::string("none") : run.status) << "\npeak_bytes "
            << field(static_cast<long long>(peak_resident_bytes())) << std::endl;
}

//! One memory child's report.
struct MemoryRun {
  std::string method, status;
  std::size_t vertices = 0;
  double seconds = 0;
  std::uint64_t peak_bytes = 0;
};

//! Starts this program as a memory child and reads its report.  Throws std::runtime_error when
//! the child fails.
MemoryRun memory_child(const std::string& method, const std::string& item, const MemorySettings& m) {
  const std::vector<std::string> arguments{
      "--memory-child", method, "--cases", item, "--lambda", field(m.lambda), "--angle", field(m.cgal_angle),
      "--cgal-error-bound", field(m.cgal_error_bound), "--cgal-seed", field(static_cast<long long>(cgal_seed)),
      "--seed", field(static_cast<long long>(m.base.seed)), "--threads", field(m.base.threads),
      "--time-limit", field(m.base.time_limit_seconds), "--max-points", field(m.base.max_points)};
  const ChildResult child = run_child(fs::read_symlink("/proc/self/exe").string(), arguments);
  if (child.exit_code != 0)
    throw std::runtime_error("memory child " + method + " " + item + " exited with " + std::to_string(child.exit_code));
  MemoryRun run;
  run.method = method;
  std::istringstream lines(child.out);
  std::string key;
  while (lines >> key) {
    if (key == "vertices") lines >> run.vertices;
    else if (key == "seconds") lines >> run.seconds;
    else if (key == "status") lines >> run.status;
    else if (key == "peak_bytes") lines >> run.peak_bytes;
  }
  return run;
}

void run_memory_experiment(const Context& context, const std::vector<std::string>& cases, const MemorySettings& m) {
  CsvWriter csv(context.out_dir / "memory.csv", "compare_cgal",
                {{"experiment", "memory"},
                 {"lambda", field(m.lambda)},
                 {"threads", field(m.base.threads)},
                 {"cgal_angle", field(m.cgal_angle)},
                 {"cgal_error_bound", field(m.cgal_error_bound)},
                 {"seed", field(static_cast<long long>(m.base.seed))},
                 {"cgal_seed", field(static_cast<long long>(cgal_seed))},
                 {"cgal", CGAL_VERSION_STR}},
                {"surface", "size_bound", "method", "status", "vertices", "seconds", "peak_bytes", "baseline_bytes",
                 "bytes_per_vertex"});
  for (const std::string& item : cases) {
    const auto [name, h] = parse_case(item);
    const MemoryRun baseline = memory_child("none", item, m);
    std::map<std::string, double> per_vertex;
    for (const std::string method : {"mesh_3", "delmesh"}) {
      const MemoryRun run = memory_child(method, item, m);
      const double net = static_cast<double>(run.peak_bytes) - static_cast<double>(baseline.peak_bytes);
      per_vertex[method] = run.vertices ? net / static_cast<double>(run.vertices) : std::nan("");
      csv.row({name, field(h), method, run.status, field(run.vertices), field(run.seconds),
               field(static_cast<long long>(run.peak_bytes)), field(static_cast<long long>(baseline.peak_bytes)),
               field(per_vertex[method])});
      std::cout << "memory " << name << " H=" << h << ": " << method << " " << run.vertices << " vertices, peak "
                << static_cast<double>(run.peak_bytes) / 1048576 << " MiB (baseline "
                << static_cast<double>(baseline.peak_bytes) / 1048576 << " MiB), " << per_vertex[method]
                << " bytes/vertex" << std::endl;
    }
    std::cout << "memory " << name << " H=" << h << ": delmesh bytes per vertex / Mesh_3's = "
              << per_vertex["delmesh"] / per_vertex["mesh_3"] << std::endl;
  }
  csv.close();
  std::cout << "wrote " << csv.path().string() << std::endl;
}

// --- the command line and the three table experiments ---------------------------------------------
// The comparison's command line.
struct CompareOptions {
  std::string surfaces = "torus,genus2", demo_surfaces = "thin_handle,two_blobs,near_sheets";
  std::string experiments_to_run = "benchmark,coarsest,demo";
  double lambda = lambda0;
  std::string cases = "torus:0.05,genus2:0.05,torus:0.02";
  double cgal_angle = 30;
  double cgal_error_bound = 1e-6;
  std::string relative_distances = "1e-3";
  std::vector<double> coarse_radii{0.5, 1.0};
  std::vector<double> ladder{0.8, 0.4, 0.2, 0.1, 0.05};
  std::string out_dir = "out";
  bool no_meshes = false, skip_delmesh = false;
  int repeat = 1;
  DelMeshOptions base;
  std::string memory_child_method;
  std::optional<int> threads_compare;

  CompareOptions() {
    base.progress = nullptr;
    base.threads = 1;
  }
};

// The options of the comparison's command line, into `o` (and the globals mesh3_seed_components
// and cgal_seed).
void add_compare_options(CLI::App& app, CompareOptions& o) {
  app.add_option("--surfaces", o.surfaces, "surfaces of coarsest and distance (catalog names, comma separated)")
      ->capture_default_str();
  app.add_option("--demo-surfaces", o.demo_surfaces, "demo surfaces")->capture_default_str();
  app.add_option("--experiments", o.experiments_to_run, "any of benchmark,coarsest,demo,distance,memory")
      ->capture_default_str();
  app.add_option("--memory-child", o.memory_child_method,
                 "internal (the memory experiment's child): run mesh_3, delmesh or none on the one case of --cases "
                 "and print its vertices, seconds and status")
      ->group("");
  app.add_option("--lambda", o.lambda, "delmesh lambda")->capture_default_str();
  app.add_option("--cases", o.cases,
                 "benchmark cases SURFACE:H, comma separated: delmesh with size bound H against CGAL with "
                 "facet size H and facet distance H/10")
      ->capture_default_str();
  app.add_option("--repeat", o.repeat,
                 "benchmark rounds per case: Mesh_3 then delmesh, K times (Surface_mesher once); the summary "
                 "gives the median, least and greatest ratio")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  app.add_option("--relative-distances", o.relative_distances,
                 "distance: the distance bounds, comma separated, each times the surface's box diagonal: delmesh's "
                 "max_distance and Mesh_3's facet_distance")
      ->capture_default_str();
  app.add_option("--angle", o.cgal_angle, "CGAL facet angle bound (deg)")->capture_default_str();
  app.add_option("--cgal-error-bound", o.cgal_error_bound,
                 "benchmark and distance only: relative error bound of CGAL's implicit-surface bisection (times "
                 "the bounding sphere's diameter; CGAL's own default 1e-3, which coarsest and demo keep, exceeds "
                 "the facet distance H/10 on the catalog boxes for H <= 0.05, and is about distance's default "
                 "delta)")
      ->capture_default_str()
      ->check(CLI::Range(1e-15, 1e-1));
  app.add_option("--coarse-radii", o.coarse_radii, "CGAL radius bounds of the demo (distance = radius/10)")
      ->capture_default_str();
  app.add_option("--ladder", o.ladder, "CGAL radius bounds tried by 'coarsest' (distance = radius/10), coarse first")
      ->capture_default_str();
  app.add_option("--seed", o.base.seed, "delmesh seed")->capture_default_str();
  app.add_option("--threads", o.base.threads, "delmesh threads (0: every hardware thread)")->capture_default_str();
  app.add_option("--threads-compare", o.threads_compare,
                 "benchmark only: in each round also run delmesh with N threads (0: every hardware thread) right "
                 "after the --threads run, and report its ratio to Mesh_3, its wall time over the --threads run's "
                 "(the speed-up, paired per round) and whether the two meshes are identical")
      ->check(CLI::Range(0, 1024));
  app.add_flag("--mesh3-seed-components", mesh3_seed_components,
               "Mesh_3's initial points on every component of the surface: CGAL's intersections with it near the "
               "certified critical points of a generic height function (delmesh's seed solve), instead of CGAL's "
               "rays from one centre");
  app.add_option("--cgal-seed", cgal_seed, "seed of CGAL's default random generator")->capture_default_str();
  app.add_option("--time-limit", o.base.time_limit_seconds, "delmesh time limit per run (s), 0 none")
      ->capture_default_str();
  app.add_option("--max-points", o.base.max_points, "delmesh point limit per run")->capture_default_str();
  app.add_option("--out-dir", o.out_dir, "output directory")->capture_default_str();
  app.add_flag("--no-meshes", o.no_meshes, "do not write the meshes");
  app.add_flag("--skip-delmesh", o.skip_delmesh, "run only the CGAL meshers");
}

// The parameters compare_cgal.csv's metadata records.
std::vector<std::pair<std::string, std::string>> compare_parameters(const CompareOptions& o) {
  return {{"lambda", field(o.lambda)},
          {"benchmark_cases", o.cases},
          {"threads", field(o.base.threads)},
          {"threads_compare", o.threads_compare ? field(*o.threads_compare) : std::string("none")},
          {"repeat", field(o.repeat)},
          {"cgal_angle", field(o.cgal_angle)},
          {"cgal_error_bound", field(o.cgal_error_bound)},
          {"demo_radii", field_list(o.coarse_radii)},
          {"ladder_radii", field_list(o.ladder)},
          {"relative_distances", o.relative_distances},
          {"seed", field(static_cast<long long>(o.base.seed))},
          {"cgal_seed", field(static_cast<long long>(cgal_seed))},
          {"time_limit", field(o.base.time_limit_seconds)},
          {"cgal", CGAL_VERSION_STR}};
}

// The rounds of one benchmark case: per round Mesh_3's and delmesh's seconds per vertex and their
// ratio; with --threads-compare the other thread count's ratios to Mesh_3, its wall time over the
// --threads run's, and the rounds whose two meshes were identical; the last delmesh run's
// statistics and vertices.
struct BenchmarkRounds {
  std::vector<double> m3_per_vertex, dm_per_vertex, ratios;
  std::vector<double> other_per_vertex, other_ratios, time_ratios;
  int identical_rounds = 0;
  std::string base_threads, other_threads;
  nlohmann::json statistics;
  std::size_t vertices = 0;
};

// --threads-compare in one round: delmesh again with the other thread count, against the round's
// run `dm` and Mesh_3.
void compare_threads(Context& context, const CompareOptions& o, const Prepared& s, double h, const Run& dm, int round,
                     BenchmarkRounds& b) {
  DelMeshOptions other = o.base;
  other.threads = *o.threads_compare;
  Run dt = run_delmesh(*s.entry, o.lambda, h, other);
  record(context, "benchmark", *s.entry, dt, s.E, round);
  b.base_threads = threads_used(dm, o.base.threads);
  b.other_threads = threads_used(dt, other.threads);
  b.other_per_vertex.push_back(seconds_per_vertex(dt));
  b.other_ratios.push_back(b.other_per_vertex.back() / b.m3_per_vertex.back());
  b.time_ratios.push_back(dt.seconds / dm.seconds);
  b.identical_rounds += same_mesh(dm, dt) ? 1 : 0;
}

// The --repeat rounds of one benchmark case: Mesh_3 then delmesh, each recorded.
BenchmarkRounds benchmark_rounds(Context& context, const CompareOptions& o, const Prepared& s, const std::string& name,
                                 double h, const CgalSettings& settings) {
  BenchmarkRounds b;
  for (int round = 1; round <= o.repeat; ++round) {
    Run m3 = run_mesh_3(s.E, s.centre, s.squared_radius, settings, s.mesh3_seeds);
    record(context, "benchmark", *s.entry, m3, s.E, round);
    if (o.skip_delmesh) continue;
    Run dm = run_delmesh(*s.entry, o.lambda, h, o.base);
    const MeshReport report = record(context, "benchmark", *s.entry, dm, s.E, round);
    b.m3_per_vertex.push_back(seconds_per_vertex(m3));
    b.dm_per_vertex.push_back(seconds_per_vertex(dm));
    b.ratios.push_back(b.dm_per_vertex.back() / b.m3_per_vertex.back());
    if (o.repeat > 1)
      std::cout << "benchmark " << name << " H=" << h << " round " << round << ": ratio " << b.ratios.back()
                << std::endl;
    // The same input and seed give the same mesh: a round that differs is reported.
    if (round > 1 && report.vertices != b.vertices)
      std::cout << "benchmark " << name << " H=" << h << " round " << round << ": delmesh made " << report.vertices
                << " vertices, round 1 " << b.vertices << " (not reproducible)" << std::endl;
    if (o.threads_compare) compare_threads(context, o, s, h, dm, round, b);
    b.statistics = std::move(dm.statistics);
    b.vertices = report.vertices;
  }
  return b;
}

// The summary lines of one benchmark case: medians of the rounds, delmesh's seconds per vertex
// relative to the surface's first case (`first_per_vertex`), and its solver calls per vertex.
void print_benchmark_summary(const CompareOptions& o, const std::string& name, double h, BenchmarkRounds& b,
                             std::map<std::string, double>& first_per_vertex) {
  const double per_vertex = median(b.dm_per_vertex);
  const auto [first, inserted] = first_per_vertex.emplace(name, per_vertex);
  std::cout << "benchmark " << name << " H=" << h << ": delmesh " << per_vertex * 1e6
            << " us/vertex, Mesh_3 " << median(b.m3_per_vertex) * 1e6 << " us/vertex, ratio " << median(b.ratios)
            << spread(b.ratios) << " (seconds per vertex: medians; target <= 3)";
  if (!inserted) std::cout << ", delmesh us/vertex relative to the first " << name << " case " << per_vertex / first->second;
  std::cout << std::endl;
  if (o.threads_compare)
    std::cout << "benchmark " << name << " H=" << h << " threads=" << b.other_threads << ": delmesh "
              << median(b.other_per_vertex) * 1e6 << " us/vertex, ratio to Mesh_3 " << median(b.other_ratios)
              << spread(b.other_ratios) << "; wall time over the threads=" << b.base_threads
              << " run's " << median(b.time_ratios) << spread(b.time_ratios) << "; identical meshes in "
              << b.identical_rounds << " of " << o.repeat << " rounds" << std::endl;
  if (!b.statistics.is_null() && b.vertices) {
    const double n = static_cast<double>(b.vertices);
    std::cout << "  solver calls per vertex:";
    for (const auto& [primitive, p] : b.statistics["solver"]["per_primitive"].items())
      std::cout << " " << primitive << " " << p["calls"].get<double>() / n;
    const auto& cone = b.statistics["solver"]["cone_certificates"];
    std::cout << "; cone certificates per vertex " << cone["attempts"].get<double>() / n << " ("
              << cone["proved"].get<double>() / n << " proved)" << std::endl;
  }
}

// benchmark: seconds per vertex of delmesh over Mesh_3's per case, and how delmesh's seconds per
// vertex grow with the mesh (relative to the surface's first case).
void run_benchmark(Context& context, const CompareOptions& o) {
  std::map<std::string, double> first_per_vertex;
  for (const std::string& item : split(o.cases)) {
    const auto [name, h] = parse_case(item);
    const Prepared s = prepare(name);
    const CgalSettings settings{o.cgal_angle, h, h / 10, o.cgal_error_bound};
    Run sm = run_surface_mesher(s.E, s.centre, s.squared_radius, settings);
    record(context, "benchmark", *s.entry, sm, s.E);
    BenchmarkRounds b = benchmark_rounds(context, o, s, name, h, settings);
    if (o.skip_delmesh) continue;
    print_benchmark_summary(o, name, h, b, first_per_vertex);
  }
}

// coarsest: delmesh without a size bound against the coarsest Mesh_3 setting of the ladder that
// has the right topology.
void run_coarsest(Context& context, const CompareOptions& o) {
  for (const std::string& name : split(o.surfaces)) {
    const Prepared s = prepare(name);
    std::optional<Run> coarsest_m3;
    for (double radius : o.ladder) {
      const CgalSettings settings{o.cgal_angle, radius, radius / 10};
      Run sm = run_surface_mesher(s.E, s.centre, s.squared_radius, settings);
      record(context, "coarsest", *s.entry, sm, s.E);
      Run m3 = run_mesh_3(s.E, s.centre, s.squared_radius, settings, s.mesh3_seeds);
      const MeshReport r = record(context, "coarsest", *s.entry, m3, s.E);
      if (!coarsest_m3 && r.has_topology(s.entry->genus_per_component)) coarsest_m3 = m3;
    }
    if (o.skip_delmesh) continue;
    Run dm = run_delmesh(*s.entry, o.lambda, std::nullopt, o.base);
    record(context, "coarsest", *s.entry, dm, s.E);
    if (coarsest_m3) {
      std::cout << "coarsest " << name << ": delmesh (no size bound) seconds per vertex / Mesh_3's at ["
                << coarsest_m3->parameters
                << "] = " << seconds_per_vertex(dm) / seconds_per_vertex(*coarsest_m3) << std::endl;
    } else {
      std::cout << "coarsest " << name << ": no Mesh_3 setting of the ladder had the right topology" << std::endl;
    }
  }
}

// demo: the CGAL meshers at the coarse radii and delmesh without a size bound on the demo surfaces.
void run_demo(Context& context, const CompareOptions& o) {
  for (const std::string& name : split(o.demo_surfaces)) {
    const Prepared s = prepare(name);
    for (double radius : o.coarse_radii) {
      const CgalSettings coarse{o.cgal_angle, radius, radius / 10};
      Run sm = run_surface_mesher(s.E, s.centre, s.squared_radius, coarse);
      record(context, "demo", *s.entry, sm, s.E);
      Run m3 = run_mesh_3(s.E, s.centre, s.squared_radius, coarse, s.mesh3_seeds);
      record(context, "demo", *s.entry, m3, s.E);
    }
    if (!o.skip_delmesh) {
      Run dm = run_delmesh(*s.entry, o.lambda, std::nullopt, o.base);
      record(context, "demo", *s.entry, dm, s.E);
    }
  }
}

// The experiments of --experiments, in the order benchmark, coarsest, demo, distance, memory;
// compare_cgal.csv gets the rows of the first three.
void run_comparison(const CompareOptions& o, const MemorySettings& memory_settings) {
  Context context;
  context.out_dir = o.out_dir;
  context.write_meshes = !o.no_meshes;
  CsvWriter csv(fs::path(o.out_dir) / "compare_cgal.csv", "compare_cgal", compare_parameters(o), csv_columns());
  context.csv = &csv;
  const auto wanted = split(o.experiments_to_run);
  auto wants = [&wanted](const std::string& name) {
    return std::find(wanted.begin(), wanted.end(), name) != wanted.end();
  };
  if (wants("benchmark")) run_benchmark(context, o);
  if (wants("coarsest")) run_coarsest(context, o);
  if (wants("demo")) run_demo(context, o);
  if (wants("distance"))
    run_distance_experiment(context, {split(o.surfaces), positive_numbers("--relative-distances", o.relative_distances),
                                      o.lambda, o.base, o.cgal_angle, o.cgal_error_bound, o.skip_delmesh});
  if (wants("memory")) run_memory_experiment(context, split(o.cases), memory_settings);
  csv.close();
  std::cout << "wrote " << csv.path().string() << std::endl;
}

}  // namespace

int main(int argc, char** argv) {
  delmesh::back_heap_with_huge_pages();
  CLI::App app{"delmesh vs CGAL Surface_mesher and Mesh_3 (seconds-per-vertex benchmark, coarsest-topology "
               "comparison, the topology demo, and on request the distance comparison: delmesh's certified "
               "--max-distance against Mesh_3's facet_distance); writes <out-dir>/compare_cgal.csv, and for "
               "distance <out-dir>/distance.csv and distance.md"};
  CompareOptions o;
  add_compare_options(app, o);
  if (const auto code = parse_command_line(app, argc, argv)) return *code;
  const MemorySettings memory_settings{o.lambda, o.cgal_angle, o.cgal_error_bound, o.base};
  if (!o.memory_child_method.empty())
    return run_guarded([&] { run_memory_child(o.memory_child_method, o.cases, memory_settings); });
  return run_guarded([&] { run_comparison(o, memory_settings); });
}
