#include "meshing/mesh_io.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <sstream>
#include <filesystem>
#include <fstream>
#include <locale>
#include <new>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>

#include "common/errors.h"
#include "meshing/mesh_checker.h"

namespace delmesh {
namespace {

namespace fs = std::filesystem;

enum class Format { off, ply, obj };

//! Significant digits that make every double round-trip through text.
constexpr int full_double_precision = 17;

Format format_of(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  if (ext == ".off") return Format::off;
  if (ext == ".ply") return Format::ply;
  if (ext == ".obj") return Format::obj;
  throw InvalidInput("mesh file '" + path + "': unknown extension '" + ext +
                     "' (expected .off, .ply or .obj)");
}

[[noreturn]] void corrupt(const std::string& path, const std::string& why) {
  throw InvalidInput("mesh file '" + path + "': " + why);
}

//! A word of the file as it may appear in a message: at most 32 characters, bytes that are not
//! printable ASCII shown as '?'.
std::string printable(const std::string& word) {
  std::string out;
  for (std::size_t i = 0; i < word.size() && i < 32; ++i) {
    const unsigned char c = static_cast<unsigned char>(word[i]);
    out += (c >= 32 && c < 127) ? static_cast<char>(c) : '?';
  }
  if (word.size() > 32) out += "...";
  return out;
}

//! "the file has N vertices (numbered FIRST to LAST)", or "the file has no vertices".
std::string vertex_range(std::uintmax_t n, std::uintmax_t first) {
  if (n == 0) return "the file has no vertices";
  return "the file has " + std::to_string(n) + " vertices (numbered " + std::to_string(first) + " to " +
         std::to_string(first + n - 1) + ")";
}

//! A count of the header: a whole number of at most 19 digits (no sign).
std::uintmax_t header_count(const std::string& path, const std::string& word, const char* what) {
  if (!word.empty() && word[0] == '-') corrupt(path, std::string("the header declares a negative ") + what + " (" + printable(word) + ")");
  const bool digits = !word.empty() && word.size() <= 19 &&
                      std::all_of(word.begin(), word.end(), [](unsigned char c) { return std::isdigit(c) != 0; });
  if (!digits) corrupt(path, std::string("the header's ") + what + " '" + printable(word) + "' is not a whole number below 10^19");
  return std::stoull(word);
}

//! The reason CGAL's reader refused an OFF file, found by reading it again token by token (the
//! first problem met), or "" if none is found.
std::string diagnose_off(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  in.imbue(std::locale::classic());
  std::vector<std::vector<std::string>> lines;  // non-empty lines, comments removed
  std::string line;
  while (std::getline(in, line)) {
    const auto hash = line.find('#');
    if (hash != std::string::npos) line.resize(hash);
    std::istringstream fields(line);
    std::vector<std::string> words;
    for (std::string w; fields >> w;) words.push_back(w);
    if (!words.empty()) lines.push_back(std::move(words));
  }
  // A cursor over the words, line after line, for the header and the vertices.
  std::size_t row = 0, column = 0;
  const auto next_word = [&](std::string& w) {
    while (row < lines.size() && column >= lines[row].size()) ++row, column = 0;
    if (row >= lines.size()) return false;
    w = lines[row][column++];
    return true;
  };
  const auto number = [](const std::string& w, double& value) {
    char* end = nullptr;
    value = std::strtod(w.c_str(), &end);
    return !w.empty() && end == w.c_str() + w.size();
  };
  std::string w;
  if (!next_word(w)) return "is empty";
  if (w.find("OFF") == std::string::npos) --column;
  std::string v_text, f_text;
  if (!next_word(v_text) || !next_word(f_text)) return "the OFF header has no vertex and face counts";
  const std::uintmax_t nv = header_count(path, v_text, "vertex count");
  const std::uintmax_t nf = header_count(path, f_text, "face count");
  ++row, column = 0;  // the rest of the counts' line is the edge count
  for (std::uintmax_t v = 0; v < nv; ++v)
    for (int k = 0; k < 3; ++k) {
      double value = 0;
      if (!next_word(w))
        return "truncated: the file ends in vertex " + std::to_string(v) + " of the " + std::to_string(nv) + " declared";
      if (!number(w, value)) return "vertex " + std::to_string(v) + ": '" + printable(w) + "' is not a number";
      if (!std::isfinite(value)) return "vertex " + std::to_string(v) + " has a non-finite coordinate";
    }
  if (column > 0) ++row;  // faces start on the line after the last vertex
  for (std::uintmax_t f = 0; f < nf; ++f, ++row) {
    if (row >= lines.size())
      return "truncated: the file ends before face " + std::to_string(f) + " of the " + std::to_string(nf) + " declared";
    const std::vector<std::string>& face = lines[row];
    double count = 0;
    if (!number(face[0], count) || count < 1 || count != std::floor(count))
      return "face " + std::to_string(f) + ": '" + printable(face[0]) + "' is not a vertex count";
    if (count > static_cast<double>(face.size() - 1))  // compared as doubles: count may be 1e308
      return "face " + std::to_string(f) + " lists fewer vertices than its count " + printable(face[0]) +
             (f + 1 == nf ? " (truncated?)" : "");
    for (std::size_t k = 1; k <= static_cast<std::size_t>(count); ++k) {
      double index = 0;
      if (!number(face[k], index) || index != std::floor(index))
        return "face " + std::to_string(f) + ": '" + printable(face[k]) + "' is not a vertex index";
      if (index < 0 || index >= static_cast<double>(nv))
        return "face " + std::to_string(f) + " refers to vertex " + printable(face[k]) + ", but " + vertex_range(nv, 0);
    }
  }
  return "";
}

//! The reason CGAL's reader refused an OBJ file, found by reading its v and f lines again (the
//! first problem met), or "" if none is found.  Indices are quoted as in the file (1-based,
//! negative ones relative to the last vertex defined).
std::string diagnose_obj(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  in.imbue(std::locale::classic());
  std::string line;
  long long vertices = 0, faces = 0;
  for (std::size_t number = 1; std::getline(in, line); ++number) {
    std::istringstream fields(line);
    std::string keyword;
    fields >> keyword;
    const std::string where = "line " + std::to_string(number) + ": ";
    if (keyword == "v") {
      for (int k = 0; k < 3; ++k) {
        std::string w;
        if (!(fields >> w)) return where + "a vertex needs three coordinates";
        char* end = nullptr;
        const double value = std::strtod(w.c_str(), &end);
        if (end != w.c_str() + w.size()) return where + "'" + printable(w) + "' is not a number";
        if (!std::isfinite(value)) return where + "a vertex has a non-finite coordinate";
      }
      ++vertices;
    } else if (keyword == "f") {
      std::string w;
      int corners = 0;
      while (fields >> w) {
        const std::string head = w.substr(0, w.find('/'));
        char* end = nullptr;
        const long long index = std::strtoll(head.c_str(), &end, 10);
        if (head.empty() || end != head.c_str() + head.size()) return where + "'" + printable(w) + "' is not a vertex index";
        const long long resolved = index < 0 ? vertices + index + 1 : index;
        if (index == 0 || resolved < 1 || resolved > vertices)
          return where + "a face refers to vertex " + head + ", but " +
                 (vertices == 0 ? std::string("no vertex is defined before it")
                                : std::to_string(vertices) + " vertices are defined before it (indices 1 to " +
                                      std::to_string(vertices) + ", or -1 to -" + std::to_string(vertices) +
                                      " counting back)");
        ++corners;
      }
      if (corners < 3) return where + "a face needs at least three vertices";
      ++faces;
    }
  }
  if (faces == 0) return "has no faces";
  return "";
}

//! A loose upper bound on the element counts a file of this size can hold, so that a header that
//! claims billions of elements is rejected before the CGAL readers allocate for them.
void check_declared_counts(const std::string& path, Format format, std::uintmax_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::vector<std::uintmax_t> counts;
  if (format == Format::off) {
    // Header: optional "[ST][C][N][4][n]OFF" keyword, then "V F E" on the first non-comment line.
    std::string word;
    while (in >> word) {
      if (word[0] == '#') {
        std::getline(in, line);
        continue;
      }
      if (word.find("OFF") != std::string::npos) continue;
      counts.push_back(header_count(path, word, counts.empty() ? "vertex count" : "face count"));
      if (counts.size() == 2) break;
    }
    if (counts.size() != 2) corrupt(path, "OFF header has no vertex and face counts");
  } else if (format == Format::ply) {
    // "element NAME COUNT" lines until end_header.
    bool ended = false;
    for (int i = 0; i < 10000 && std::getline(in, line); ++i) {
      if (line.rfind("end_header", 0) == 0) {
        ended = true;
        break;
      }
      if (line.rfind("element", 0) == 0) {
        std::istringstream fields(line);
        std::string keyword, name, count;
        fields >> keyword >> name >> count;
        counts.push_back(header_count(path, count, ("number of " + printable(name) + " elements").c_str()));
      }
    }
    if (!ended) corrupt(path, "PLY header has no end_header");
  }
  // Every vertex and every face takes at least 3 bytes in any of the encodings.
  for (std::uintmax_t count : counts) {
    if (count > bytes / 3 + 1) {
      corrupt(path, "the header declares " + std::to_string(count) + " elements but the file has only " +
                        std::to_string(bytes) + " bytes (truncated, or a corrupt count)");
    }
  }
}

}  // namespace

void write_triangle_soup(const TriangleSoup& soup, const std::string& path) {
  const Format format = format_of(path);
  for (const auto& t : soup.triangles)
    for (std::size_t v : t)
      if (v >= soup.points.size()) throw InvalidInput("write_mesh: vertex index out of range");

  const fs::path target(path);
  const fs::path temporary =
      target.parent_path() / (target.filename().string() + ".tmp" + std::to_string(::getpid()));
  bool ok = false;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write '" + path + "': " + std::strerror(errno));
    out.imbue(std::locale::classic());
    out.precision(full_double_precision);
    const auto np = CGAL::parameters::stream_precision(full_double_precision);
    switch (format) {
      case Format::off:
        ok = CGAL::IO::write_OFF(out, soup.points, soup.triangles, np);
        break;
      case Format::ply:
        CGAL::IO::set_mode(out, CGAL::IO::ASCII);
        ok = CGAL::IO::write_PLY(out, soup.points, soup.triangles, np);
        break;
      case Format::obj:
        ok = CGAL::IO::write_OBJ(out, soup.points, soup.triangles, np);
        break;
    }
    out.flush();
    ok = ok && out.good();
  }
  std::error_code ignored;
  if (!ok) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': the write failed (disk full?)");
  }
  std::error_code error;
  fs::rename(temporary, target, error);
  if (error) {
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write '" + path + "': " + error.message());
  }
}

void write_mesh(const SurfaceMesh& mesh, const std::string& path) {
  format_of(path);  // reject an unknown extension before any work
  TriangleSoup soup;
  mesh_to_soup(mesh, soup.points, soup.triangles);
  write_triangle_soup(soup, path);
}

TriangleSoup read_triangle_soup(const std::string& path) {
  const Format format = format_of(path);
  std::error_code error;
  if (fs::is_directory(path, error)) corrupt(path, "is a directory, not a mesh file");
  if (!fs::exists(path, error)) corrupt(path, "no such file");
  if (!fs::is_regular_file(path, error)) corrupt(path, "is not a regular file");
  const std::uintmax_t bytes = fs::file_size(path, error);
  if (error) corrupt(path, "cannot read its size: " + error.message());
  if (bytes == 0) corrupt(path, "is empty");
  {
    std::ifstream probe(path, std::ios::binary);
    if (!probe) corrupt(path, "cannot be opened for reading");
  }
  check_declared_counts(path, format, bytes);

  std::vector<Point3> points;
  std::vector<std::vector<std::size_t>> polygons;
  bool ok = false;
  try {
    switch (format) {
      case Format::off:
        ok = CGAL::IO::read_OFF(path, points, polygons);
        break;
      case Format::ply:
        ok = CGAL::IO::read_PLY(path, points, polygons);
        break;
      case Format::obj:
        ok = CGAL::IO::read_OBJ(path, points, polygons);
        break;
    }
  } catch (const std::bad_alloc&) {
    corrupt(path, "out of memory while reading (corrupt element counts?)");
  } catch (const std::exception& e) {
    corrupt(path, std::string("the reader failed: ") + e.what());
  }
  if (!ok) {
    std::string reason;
    if (format == Format::off) reason = diagnose_off(path);
    if (format == Format::obj) reason = diagnose_obj(path);
    corrupt(path, reason.empty() ? std::string("cannot be parsed (truncated or corrupt)") : reason);
  }
  if (polygons.empty()) corrupt(path, "has no faces");

  TriangleSoup soup;
  soup.points = std::move(points);
  soup.triangles.reserve(polygons.size());
  for (std::size_t f = 0; f < polygons.size(); ++f) {
    const auto& polygon = polygons[f];
    if (polygon.size() != 3) {
      corrupt(path, "face " + std::to_string(f) + " has " + std::to_string(polygon.size()) +
                        " vertices; only triangle meshes are supported");
    }
    for (std::size_t v : polygon) {
      if (v >= soup.points.size()) {
        // The readers store a negative index of the file as its wrapped-around unsigned value.
        const std::string index = v > std::numeric_limits<std::size_t>::max() / 2
                                      ? "-" + std::to_string(std::numeric_limits<std::size_t>::max() - v + 1)
                                      : std::to_string(format == Format::obj ? v + 1 : v);
        corrupt(path, "face " + std::to_string(f) + " refers to vertex " + index + ", but " +
                          vertex_range(soup.points.size(), format == Format::obj ? 1 : 0));
      }
    }
    if (polygon[0] == polygon[1] || polygon[1] == polygon[2] || polygon[0] == polygon[2]) {
      corrupt(path, "face " + std::to_string(f) + " repeats a vertex");
    }
    soup.triangles.push_back({polygon[0], polygon[1], polygon[2]});
  }
  for (std::size_t i = 0; i < soup.points.size(); ++i) {
    const Point3& p = soup.points[i];
    if (!(std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()))) {
      corrupt(path, "vertex " + std::to_string(i) + " has a non-finite coordinate");
    }
  }
  return soup;
}

SurfaceMesh read_mesh(const std::string& path) {
  TriangleSoup soup = read_triangle_soup(path);
  std::vector<std::vector<std::size_t>> polygons;
  polygons.reserve(soup.triangles.size());
  for (const auto& t : soup.triangles) polygons.push_back({t[0], t[1], t[2]});
  namespace PMP = CGAL::Polygon_mesh_processing;
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    corrupt(path, "the triangles do not form a consistently oriented 2-manifold (with or without "
                  "boundary); read it with read_triangle_soup to check it");
  }
  SurfaceMesh mesh;
  PMP::polygon_soup_to_polygon_mesh(soup.points, polygons, mesh);
  return mesh;
}

}  // namespace delmesh
