// Repair of self-intersecting input meshes.  See self_intersection_repair.h.
#include "meshing/inputs/self_intersection_repair.h"

#include <chrono>
#include <cerrno>
#include <csignal>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <utility>

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_mesh_to_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair.h>
#include <CGAL/Polygon_mesh_processing/repair_self_intersections.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/Polygon_mesh_processing/triangulate_faces.h>

#include "common/errors.h"
#include "common/run_limits.h"
#include "meshing/inputs/mesh_io.h"

namespace delmesh {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
using Polygons = std::vector<std::vector<std::size_t>>;

//! The closed, triangulated, outward-oriented mesh of the soup, or nothing when the soup fails one
//! of checks 1–6 of input_mesh.h (not a polygon mesh, open, degenerate).
std::optional<SurfaceMesh> closed_triangle_mesh(const std::vector<Point3>& points, const Polygons& polygons) {
  if (polygons.empty() || !PMP::is_polygon_soup_a_polygon_mesh(polygons)) return std::nullopt;
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  PMP::remove_isolated_vertices(mesh);
  mesh.collect_garbage();
  if (!CGAL::is_closed(mesh)) return std::nullopt;
  if (!CGAL::is_triangle_mesh(mesh) && !PMP::triangulate_faces(mesh)) return std::nullopt;
  for (SurfaceMesh::Face_index f : mesh.faces())
    if (PMP::is_degenerate_triangle_face(f, mesh)) return std::nullopt;
  PMP::orient(mesh);
  return mesh;
}

//! validate_input_mesh of the mesh's triangles; a defect becomes the refusal of the header.
InputMesh validate_repaired(SurfaceMesh mesh, const std::string& source, const std::string& method) {
  mesh.collect_garbage();
  std::vector<Point3> points;
  Polygons triangles;
  PMP::polygon_mesh_to_polygon_soup(mesh, points, triangles);
  try {
    return validate_input_mesh(points, triangles, source);
  } catch (const InvalidInput& e) {
    throw InvalidInput("input mesh '" + source + "': --repair could not remove the self-intersections: the mesh " +
                       method + " gave is not valid: " + e.what());
  }
}

//! A CGAL repair run in a child process: whether it finished, CGAL's verdict and its mesh, or
//! why it did not finish.
struct Attempt {
  bool finished = false;
  bool fixed = false;
  SurfaceMesh mesh;
  std::string failure;
};

bool write_all(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return false;
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

template <class T>
void append(std::string& buffer, const T& value) {
  buffer.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

template <class T>
bool take(const std::string& buffer, std::size_t& at, T& value) {
  if (buffer.size() - at < sizeof(T)) return false;
  std::memcpy(&value, buffer.data() + at, sizeof(T));
  at += sizeof(T);
  return true;
}

// The child's message: CGAL's verdict, then the repaired mesh as a triangle soup (the points'
// coordinates, then each face's size and vertex indices).
std::string encode_attempt(bool fixed, SurfaceMesh& mesh) {
  mesh.collect_garbage();
  std::vector<Point3> points;
  Polygons faces;
  PMP::polygon_mesh_to_polygon_soup(mesh, points, faces);
  std::string buffer;
  append(buffer, std::uint8_t(fixed));
  append(buffer, std::uint64_t(points.size()));
  for (const Point3& p : points)
    for (double x : {p.x(), p.y(), p.z()}) append(buffer, x);
  append(buffer, std::uint64_t(faces.size()));
  for (const auto& face : faces) {
    append(buffer, std::uint64_t(face.size()));
    for (std::size_t v : face) append(buffer, std::uint64_t(v));
  }
  return buffer;
}

// Decodes encode_attempt()'s message into the verdict and the soup; false if it is malformed.
bool decode_attempt(const std::string& buffer, std::uint8_t& fixed, std::vector<Point3>& points, Polygons& faces) {
  std::size_t at = 0;
  std::uint64_t count = 0;
  bool ok = take(buffer, at, fixed) && take(buffer, at, count);
  for (std::uint64_t i = 0; ok && i < count; ++i) {
    double x = 0, y = 0, z = 0;
    ok = take(buffer, at, x) && take(buffer, at, y) && take(buffer, at, z);
    points.emplace_back(x, y, z);
  }
  ok = ok && take(buffer, at, count);
  for (std::uint64_t i = 0; ok && i < count; ++i) {
    std::uint64_t size = 0;
    ok = take(buffer, at, size) && size <= points.size();
    std::vector<std::size_t> face;
    for (std::uint64_t k = 0; ok && k < size; ++k) {
      std::uint64_t v = 0;
      ok = take(buffer, at, v) && v < points.size();
      face.push_back(static_cast<std::size_t>(v));
    }
    faces.push_back(std::move(face));
  }
  return ok && at == buffer.size();
}

// The child process: runs `repair` on a copy of `input` and writes the result to `fd`; exits 0
// when it was written, 2 when the write failed and 1 on an exception.
[[noreturn]] void repair_in_child(int fd, const SurfaceMesh& input, bool (*repair)(SurfaceMesh&)) {
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // A crash ends the child as a crash, whatever handlers the parent installed (a test
  // framework's would report it as the parent's failure).
  for (int signal : {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT}) std::signal(signal, SIG_DFL);
  int code = 0;
  try {
    SurfaceMesh mesh = input;
    const bool fixed = repair(mesh);
    const std::string buffer = encode_attempt(fixed, mesh);
    code = write_all(fd, buffer.data(), buffer.size()) ? 0 : 2;
  } catch (...) {
    code = 1;
  }
  ::close(fd);
  ::_exit(code);
}

// Everything readable from fd until its end.
std::string read_all(int fd) {
  std::string buffer;
  char chunk[1 << 16];
  while (true) {
    const ssize_t n = ::read(fd, chunk, sizeof chunk);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    buffer.append(chunk, static_cast<std::size_t>(n));
  }
  return buffer;
}

//! Runs `repair` on a copy of `input` in a forked child process, so that a crash of CGAL's
//! experimental code (autorefinement dies with SIGSEGV on CGAL's diplodocus.off) becomes a
//! failed attempt instead of the end of the program.  The child sends back CGAL's verdict and the
//! mesh as a triangle soup through a pipe; it dies with its parent (PR_SET_PDEATHSIG).
Attempt run_isolated(const SurfaceMesh& input, const char* name, bool (*repair)(SurfaceMesh&)) {
  Attempt attempt;
  int fds[2];
  if (::pipe(fds) != 0) {
    attempt.failure = std::string(name) + " could not start (pipe: " + std::strerror(errno) + ")";
    return attempt;
  }
  const pid_t pid = ::fork();
  if (pid < 0) {
    ::close(fds[0]);
    ::close(fds[1]);
    attempt.failure = std::string(name) + " could not start (fork: " + std::strerror(errno) + ")";
    return attempt;
  }
  if (pid == 0) {
    ::close(fds[0]);
    repair_in_child(fds[1], input, repair);
  }
  ::close(fds[1]);
  const std::string buffer = read_all(fds[0]);
  ::close(fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    attempt.failure = std::string(name) + " crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
    return attempt;
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    attempt.failure = std::string(name) + " failed (an exception in CGAL)";
    return attempt;
  }
  std::uint8_t fixed = 0;
  std::vector<Point3> points;
  Polygons faces;
  if (!decode_attempt(buffer, fixed, points, faces) || !PMP::is_polygon_soup_a_polygon_mesh(faces)) {
    attempt.failure = std::string(name) + " returned a mesh that is not a polygon mesh";
    return attempt;
  }
  PMP::polygon_soup_to_polygon_mesh(points, faces, attempt.mesh);
  attempt.finished = true;
  attempt.fixed = fixed != 0;
  return attempt;
}

bool autorefine(SurfaceMesh& mesh) { return PMP::experimental::autorefine_and_remove_self_intersections(mesh); }

bool remove_locally(SurfaceMesh& mesh) {
  return PMP::experimental::remove_self_intersections(mesh, CGAL::parameters::preserve_genus(true));
}

std::size_t components_of(const SurfaceMesh& mesh) {
  std::vector<std::size_t> component(mesh.num_faces());
  return PMP::connected_components(
      mesh, CGAL::make_property_map(component),
      CGAL::parameters::face_index_map(get(boost::face_index, mesh)));
}

//! Why the autorefined mesh is not kept although CGAL fixed it ("" when it is kept): it has more
//! components than the input, or less than half its area (autorefinement keeps a part of the
//! input surface; losing most of it means the inside/outside classification went wrong).
std::string implausible(const SurfaceMesh& input, const SurfaceMesh& refined) {
  const std::size_t before = components_of(input), after = components_of(refined);
  if (after > before)
    return "autorefinement split the mesh into " + std::to_string(after) + " components (the input has " +
           std::to_string(before) + ")";
  const double area_before = PMP::area(input), area_after = PMP::area(refined);
  if (!(area_after >= 0.5 * area_before))
    return "autorefinement kept " + std::to_string(area_after / area_before * 100) + "% of the area only";
  return "";
}

// Autorefinement (exact, keeps the outer surface) of the closed mesh: true with result.input
// validated when it worked, else false with why in `failure`.
bool try_autorefinement(const SurfaceMesh& mesh, const std::string& source, RepairedInput& result,
                        std::string& failure) {
  Attempt attempt = run_isolated(mesh, "autorefinement", autorefine);
  RunLimits::current().check("repairing the input mesh", true);
  SurfaceMesh& refined = attempt.mesh;
  const bool fixed = attempt.fixed;
  if (!attempt.finished) {
    failure = attempt.failure;
    return false;
  }
  if (!(fixed && !refined.is_empty() && CGAL::is_closed(refined))) {
    failure = fixed ? "autorefinement left an open or empty mesh" : "autorefinement could not fix every "
                                                                    "self-intersection";
    return false;
  }
  refined.collect_garbage();
  failure = implausible(mesh, refined);
  if (!failure.empty()) return false;
  try {
    result.input = validate_repaired(refined, source, "autorefinement");
  } catch (const InvalidInput& e) {
    failure = e.what();
    return false;
  }
  return true;
}

// Local removal (moves the surface near the intersections) of the closed mesh: true with
// result.input validated when it worked, else false with why appended to `failure`.
bool try_local_removal(const SurfaceMesh& mesh, const std::string& source, RepairedInput& result,
                       std::string& failure) {
  Attempt attempt = run_isolated(mesh, "local remeshing", remove_locally);
  RunLimits::current().check("repairing the input mesh", true);
  SurfaceMesh& local = attempt.mesh;
  const bool fixed = attempt.fixed;
  if (!attempt.finished) {
    failure += "; " + attempt.failure;
    return false;
  }
  if (!(fixed && !local.is_empty() && CGAL::is_closed(local))) {
    failure += fixed ? "; local remeshing left an open or empty mesh"
                     : "; local remeshing could not fix every self-intersection";
    return false;
  }
  try {
    result.input = validate_repaired(local, source, "local remeshing");
  } catch (const InvalidInput& e) {
    failure += "; " + std::string(e.what());
    return false;
  }
  return true;
}

// The refusal when neither repair worked.  A refusal from validate_repaired already names the
// mesh and the option; the message keeps one of each.
std::string repair_refusal(const std::string& source, std::size_t intersecting_pairs, const std::string& failure) {
  const std::string prefix = "input mesh '" + source + "': --repair could not remove the self-intersections: ";
  std::string reasons;
  for (std::size_t at = 0; at < failure.size();) {
    const std::size_t found = failure.find(prefix, at);
    reasons += failure.substr(at, found == std::string::npos ? std::string::npos : found - at);
    if (found == std::string::npos) break;
    at = found + prefix.size();
  }
  return prefix + std::to_string(intersecting_pairs) + " pairs of triangles intersect; " + reasons;
}

}  // namespace

std::string RepairReport::summary(const std::string& source) const {
  if (!changed()) return source + ": no self-intersections, nothing to repair";
  return source + ": " + std::to_string(intersecting_pairs) + " pairs of intersecting triangles removed by " +
         (method == "autorefine" ? "autorefinement" : "local remeshing") + "; " + std::to_string(faces_before) +
         " triangles and " + std::to_string(vertices_before) + " vertices before, " + std::to_string(faces_after) +
         " and " + std::to_string(vertices_after) + " after";
}

RepairedInput repair_input_mesh(const std::vector<Point3>& points, const Polygons& polygons, const std::string& source) {
  const auto start = std::chrono::steady_clock::now();
  const RunLimits& limits = RunLimits::current();
  const char* const phase = "repairing the input mesh";
  RepairedInput result;
  RepairReport& report = result.report;
  const auto finish = [&] {
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  std::optional<SurfaceMesh> mesh;
  try {
    result.input = validate_input_mesh(points, polygons, source);
    report.faces_before = report.faces_after = result.input.mesh.number_of_faces();
    report.vertices_before = report.vertices_after = result.input.mesh.number_of_vertices();
    finish();
    return result;
  } catch (const InvalidInput&) {
    // Only a closed triangle mesh that intersects itself is repaired; any other defect is
    // refused with validate_input_mesh's own message.
    mesh = closed_triangle_mesh(points, polygons);
    if (!mesh || !PMP::does_self_intersect(*mesh)) throw;
  }
  limits.check(phase, true);
  std::vector<std::pair<SurfaceMesh::Face_index, SurfaceMesh::Face_index>> pairs;
  PMP::self_intersections(*mesh, std::back_inserter(pairs));
  report.intersecting_pairs = pairs.size();
  report.faces_before = mesh->number_of_faces();
  report.vertices_before = mesh->number_of_vertices();
  limits.check(phase, true);
  std::string failure;
  if (try_autorefinement(*mesh, source, result, failure))
    report.method = "autorefine";
  else if (try_local_removal(*mesh, source, result, failure))
    report.method = "local";
  else
    throw InvalidInput(repair_refusal(source, report.intersecting_pairs, failure));
  report.faces_after = result.input.mesh.number_of_faces();
  report.vertices_after = result.input.mesh.number_of_vertices();
  finish();
  return result;
}

RepairedInput read_and_repair_input_mesh(const std::string& path) {
  const PolygonSoup soup = read_polygon_soup(path);
  return repair_input_mesh(soup.points, soup.polygons(), path);
}

}  // namespace delmesh
