#include "meshing/inputs/input_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <iterator>
#include <limits>
#include <map>
#include <sstream>
#include <utility>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include "common/errors.h"
#include "common/run_limits.h"
#include "common/tolerances.h"
#include "meshing/inputs/folded_vertices.h"
#include "meshing/inputs/mesh_io.h"

namespace delmesh {
namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Triangle = std::array<std::size_t, 3>;
using Polygon = std::vector<std::size_t>;

//! "(x, y, z)" with 9 significant digits.
std::string coordinates(const Point3& p) {
  std::ostringstream s;
  s.precision(9);
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

//! Messages about one mesh: every one starts with its source and ends up as InvalidInput.
class Complaint {
 public:
  Complaint(const std::string& source, const std::vector<Point3>& points) : source_(source), points_(points) {}
  [[noreturn]] void operator()(const std::string& why) const {
    throw InvalidInput("input mesh '" + source_ + "': " + why);
  }
  //! "vertex 12 (x, y, z)": an index of the file and its point.
  std::string vertex(std::size_t i) const { return "vertex " + std::to_string(i) + " " + coordinates(points_[i]); }
  std::string edge(const std::array<std::size_t, 2>& e) const {
    return "the edge from " + vertex(e[0]) + " to " + vertex(e[1]);
  }

 private:
  const std::string& source_;
  const std::vector<Point3>& points_;
};

//! |(a, b, c)|: the plain square root of the sum of squares where that sum is a normal double,
//! std::hypot (which scales before squaring) where it overflows or underflows (a mesh of size
//! 1e-200 or 1e160).
double length_of(double a, double b, double c) {
  const double sum = a * a + b * b + c * c;
  if (std::isfinite(sum) && sum >= std::numeric_limits<double>::min()) return std::sqrt(sum);
  return std::hypot(a, b, c);
}

//! "1 edge", "3 edges".
std::string count_of(std::size_t n, const std::string& singular, const std::string& plural) {
  return std::to_string(n) + " " + (n == 1 ? singular : plural);
}

//! Step 1: the soup is well formed (indices in range, at least three distinct vertices per face,
//! finite referenced coordinates of magnitude at most tolerances::input_mesh_max_coordinate) and
//! not empty.
void check_soup(const std::vector<Point3>& points, const std::vector<Polygon>& polygons, const Complaint& fail) {
  if (polygons.empty()) fail("the mesh is empty (it has no faces)");
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const Polygon& polygon = polygons[f];
    if (polygon.size() < 3) fail("face " + std::to_string(f) + " has fewer than three vertices");
    for (std::size_t v : polygon)
      if (v >= points.size())
        fail("face " + std::to_string(f) + " refers to vertex " + std::to_string(v) + ", but there are " +
             std::to_string(points.size()) + " vertices");
    Polygon sorted = polygon;
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
      fail("face " + std::to_string(f) + " repeats a vertex");
    for (std::size_t v : polygon) {
      const Point3& p = points[v];
      if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z())))
        fail("vertex " + std::to_string(v) + " has a non-finite coordinate");
      if (std::max({std::abs(p.x()), std::abs(p.y()), std::abs(p.z())}) > tolerances::input_mesh_max_coordinate)
        fail(fail.vertex(v) + " has a coordinate too large: above 1e100 in magnitude, products of three "
             "coordinates would overflow double precision; rescale the mesh");
    }
  }
}

//! Steps 2–5 on the faces of the file, each polygon split into a fan (its boundary edges and the
//! fans around its vertices are those of the polygon, so the counts are the polygon mesh's).
void check_combinatorics(const std::vector<Point3>& points, const std::vector<Polygon>& polygons,
                         const Complaint& fail) {
  std::vector<Triangle> fans;
  for (const Polygon& polygon : polygons)
    for (std::size_t k = 1; k + 1 < polygon.size(); ++k) fans.push_back({polygon[0], polygon[k], polygon[k + 1]});
  const MeshReport r = check_mesh(points, fans);
  if (r.first_nonmanifold_edge)
    fail("not a manifold: " + count_of(r.nonmanifold_edges, "edge lies", "edges lie") +
         " in three or more faces, e.g. " + fail.edge(*r.first_nonmanifold_edge));
  if (r.first_boundary_edge)
    fail("not closed: " + count_of(r.boundary_edges, "boundary edge", "boundary edges") + " in " +
         count_of(r.boundary_loops, "loop", "loops") + ", e.g. " + fail.edge(*r.first_boundary_edge) +
         " lies in one face only");
  if (r.first_nonmanifold_vertex)
    fail("not a manifold: " + count_of(r.nonmanifold_vertices, "vertex is", "vertices are") +
         " shared by separate fans of faces, e.g. " + fail.vertex(*r.first_nonmanifold_vertex));
  if (!r.orientable)
    fail("the surface is not orientable (e.g. " + fail.edge(*r.first_misoriented_edge) +
         " is traversed in the same direction by both of its faces, and no reorientation avoids that)");
  if (r.first_misoriented_edge)
    fail("the faces are not consistently oriented: " +
         count_of(r.misoriented_edges, "edge is", "edges are") +
         " traversed in the same direction by both of their faces, e.g. " + fail.edge(*r.first_misoriented_edge) +
         " (the surface is orientable: reorient the faces, e.g. with CGAL's orient_polygon_soup)");
}

//! The referenced points in the order of the file, the polygons renumbered to them, and for each
//! kept point its index in the file.
struct CompactSoup {
  std::vector<Point3> points;
  std::vector<Polygon> polygons;
  std::vector<std::size_t> file_index;
};

CompactSoup compact(const std::vector<Point3>& points, const std::vector<Polygon>& polygons) {
  constexpr std::size_t unused = std::numeric_limits<std::size_t>::max();
  std::vector<std::size_t> new_index(points.size(), unused);
  for (const Polygon& polygon : polygons)
    for (std::size_t v : polygon) new_index[v] = 0;
  CompactSoup soup;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (new_index[i] == unused) continue;
    new_index[i] = soup.points.size();
    soup.points.push_back(points[i]);
    soup.file_index.push_back(i);
  }
  soup.polygons = polygons;
  for (Polygon& polygon : soup.polygons)
    for (std::size_t& v : polygon) v = new_index[v];
  return soup;
}

double lower_median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>((values.size() - 1) / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

//! Reverses the components of mesh that do not bound a volume with outward normals; returns how
//! many were reversed (a face keeps its index, so a face whose first directed edge was turned
//! around marks its component).
std::size_t orient_outward(SurfaceMesh& mesh) {
  using Vertex = SurfaceMesh::Vertex_index;
  std::vector<std::pair<Vertex, Vertex>> first_edge;
  first_edge.reserve(mesh.number_of_faces());
  for (SurfaceMesh::Face_index f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    first_edge.emplace_back(mesh.source(h), mesh.target(h));
  }
  PMP::orient_to_bound_a_volume(mesh);
  auto component = mesh.add_property_map<SurfaceMesh::Face_index, std::size_t>("f:input_component", 0).first;
  const std::size_t components = PMP::connected_components(mesh, component);
  std::vector<char> reversed(components, 0);
  std::size_t k = 0;
  for (SurfaceMesh::Face_index f : mesh.faces()) {
    const auto [a, b] = first_edge[k++];
    bool kept = false;
    for (auto h : CGAL::halfedges_around_face(mesh.halfedge(f), mesh))
      kept = kept || (mesh.source(h) == a && mesh.target(h) == b);
    if (!kept) reversed[component[f]] = 1;
  }
  mesh.remove_property_map(component);
  return static_cast<std::size_t>(std::count(reversed.begin(), reversed.end(), 1));
}

// "vertex 3 (x, y, z), vertex 7 (...), ...": the corners of face f by their indices in the file.
std::string face_corners(const SurfaceMesh& mesh, SurfaceMesh::Face_index f, const Complaint& fail,
                         const CompactSoup& soup) {
  std::string corners;
  for (auto v : CGAL::vertices_around_face(mesh.halfedge(f), mesh))
    corners += (corners.empty() ? "" : ", ") + fail.vertex(soup.file_index[static_cast<std::size_t>(v)]);
  return corners;
}

// Step 6: no degenerate triangle (exact collinearity test).
void check_no_degenerate_triangle(const SurfaceMesh& mesh, const Complaint& fail, const CompactSoup& soup) {
  for (SurfaceMesh::Face_index f : mesh.faces()) {
    if (!PMP::is_degenerate_triangle_face(f, mesh)) continue;
    fail("a triangle is degenerate (its vertices are collinear): " + face_corners(mesh, f, fail, soup));
  }
}

// Step 7: no self-intersection (exact predicates); the first pair found is named.
void check_no_self_intersection(const SurfaceMesh& mesh, const Complaint& fail, const CompactSoup& soup) {
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> crossing;
  PMP::self_intersections(mesh, std::back_inserter(crossing), CGAL::parameters::maximum_number(1));
  if (crossing.empty()) return;
  fail("the surface intersects itself, e.g. the triangle of " + face_corners(mesh, crossing.front().first, fail, soup) +
       " meets the triangle of " + face_corners(mesh, crossing.front().second, fail, soup));
}

// Step 8: a mesh far from the origin is resolved finely enough by its coordinates.
void check_resolution(const CGAL::Bbox_3& bounds, double diagonal, const Complaint& fail) {
  const double largest = std::max({std::abs(bounds.xmin()), std::abs(bounds.xmax()), std::abs(bounds.ymin()),
                                   std::abs(bounds.ymax()), std::abs(bounds.zmin()), std::abs(bounds.zmax())});
  const double unit = largest - std::nextafter(largest, 0.0);  // a unit in the last place there
  if (largest >= tolerances::input_mesh_far_ratio * diagonal &&
      !(diagonal >= tolerances::input_mesh_min_resolution * unit))
    fail("the mesh lies too far from the origin for its size: its bounding-box diagonal spans only " +
         std::to_string(static_cast<long long>(diagonal / unit)) +
         " units in the last place of its coordinates (at least " +
         std::to_string(static_cast<long long>(tolerances::input_mesh_min_resolution)) +
         " are needed); translate it towards the origin");
}

// The domain box: the bounding box enlarged by the margin, and by at least one step of double
// outward (a margin below half a unit in the last place of a (subnormal) bound rounds away).
void enlarge_to_domain(const CGAL::Bbox_3& bounds, double diagonal, Box3& box) {
  const double margin = tolerances::input_mesh_box_margin * diagonal;
  for (int i = 0; i < 3; ++i) {
    box.lo[i] = std::min(bounds.min(i) - margin, std::nextafter(bounds.min(i), -HUGE_VAL));
    box.hi[i] = std::max(bounds.max(i) + margin, std::nextafter(bounds.max(i), HUGE_VAL));
  }
}

// The lower median of the mesh's edge lengths.
double median_edge_length(const SurfaceMesh& mesh) {
  std::vector<double> lengths;
  lengths.reserve(mesh.number_of_edges());
  for (SurfaceMesh::Edge_index e : mesh.edges()) {
    const Point3 &p = mesh.point(mesh.vertex(e, 0)), &q = mesh.point(mesh.vertex(e, 1));
    lengths.push_back(length_of(q.x() - p.x(), q.y() - p.y(), q.z() - p.z()));
  }
  return lower_median(std::move(lengths));
}

}  // namespace

InputMesh validate_input_mesh(const std::vector<Point3>& points, const std::vector<std::vector<std::size_t>>& polygons,
                              const std::string& source) {
  const Complaint fail(source, points);
  // 1. A well-formed, non-empty soup; 2–5. manifold, closed, consistently oriented.
  check_soup(points, polygons, fail);
  check_combinatorics(points, polygons, fail);
  const RunLimits& limits = RunLimits::current();
  const char* const phase = "validating the input mesh";
  limits.check(phase, true);

  InputMesh input;
  input.faces_read = polygons.size();
  input.polygons_triangulated = static_cast<std::size_t>(
      std::count_if(polygons.begin(), polygons.end(), [](const Polygon& p) { return p.size() > 3; }));

  // The polygon mesh of the referenced points, then its polygons triangulated.
  const CompactSoup soup = compact(points, polygons);
  input.unreferenced_vertices = points.size() - soup.points.size();
  if (!PMP::is_polygon_soup_a_polygon_mesh(soup.polygons))
    fail("the faces do not form a polygon mesh");  // excluded by steps 2-5; kept as a guard
  PMP::polygon_soup_to_polygon_mesh(soup.points, soup.polygons, input.mesh);
  if (input.polygons_triangulated > 0 && !PMP::triangulate_faces(input.mesh))
    fail("a face with more than three vertices could not be triangulated (a degenerate polygon)");
  limits.check(phase, true);
  // 6. No degenerate triangle; 7. no self-intersection.
  check_no_degenerate_triangle(input.mesh, fail, soup);
  limits.check(phase, true);
  check_no_self_intersection(input.mesh, fail, soup);

  // Outward orientation, the domain box and the measures.
  limits.check(phase, true);
  input.components_reversed = orient_outward(input.mesh);
  limits.check(phase, true);
  input.report = check_mesh(input.mesh);
  limits.check(phase, true);
  const CGAL::Bbox_3 bounds = CGAL::bbox_3(soup.points.begin(), soup.points.end());
  input.bounding_box_diagonal =
      length_of(bounds.xmax() - bounds.xmin(), bounds.ymax() - bounds.ymin(), bounds.zmax() - bounds.zmin());
  // 8. Coordinates fine enough for the mesh's size.
  check_resolution(bounds, input.bounding_box_diagonal, fail);
  enlarge_to_domain(bounds, input.bounding_box_diagonal, input.box);
  input.median_edge_length = median_edge_length(input.mesh);
  input.folded_vertices = folded_vertices(input.mesh);
  return input;
}

InputMesh read_input_mesh(const std::string& path) {
  const PolygonSoup soup = read_polygon_soup(path);
  return validate_input_mesh(soup.points, soup.polygons(), path);
}

}  // namespace delmesh
