//! \file remesh.cpp
//! Fig. 13 by experiment (§7 of the paper): DelMesh remeshes closed triangle meshes.  Each input
//! goes the way of `delmesh mesh --input-mesh FILE`: read_input_mesh (meshing/inputs/input_mesh.h:
//! triangulated, validated, oriented outward; the box is its bounding box plus the margin), then
//! del_mesh on a MeshOracle of it with the termination floor --min-spacing-fraction times the
//! input's median edge length.  It runs twice per input with the same seed: with phase topology
//! (SampleTopology: the middle column of Fig. 13) and with phase all (Quality and Smooth: the
//! right column).
//!
//! Output in <out-dir>/remesh/, per input NAME (the file's stem):
//!   NAME_input.off                  the validated input (outward oriented), the left column;
//!   NAME_topology.off, NAME_final.off  the two outputs;
//!   NAME_{input,topology,final}_check.json  the independent checker's report on each file as
//!                                   written (meshing/core/mesh_checker.h; the keys of delmesh check --json);
//!   NAME_{topology,final}_stats.json  the statistics record of each run;
//! and <out-dir>/remesh.csv, one row per input and phase: status, vertices, seconds, insertions
//! per check, the floor, the checker's quality and topology of input and output, Theorem 6.1's
//! bounds for λ, and the largest distance of an output vertex to the input surface (AABB tree).
//!
//! Without paths it remeshes --names (default elephant, eight, knot1) from CGAL's data archive
//! (--archive, package libcgal-demo), extracted into <out-dir>/remesh/inputs/.

#include <CLI/CLI.hpp>

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "common/errors.h"
#include "common/huge_page_heap.h"
#include "common/tolerances.h"
#include "experiments/experiment_support.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/core/theorem_bounds.h"
#include "meshing/driver/del_mesh.h"
#include "meshing/inputs/input_mesh.h"
#include "meshing/inputs/make_oracle.h"
#include "meshing/inputs/mesh_io.h"

using namespace delmesh;
using namespace delmesh::experiments;
namespace fs = std::filesystem;

namespace {

//! The checks whose insertions are reported, in the order of the statistics contract.
const std::vector<std::string> insertion_keys = {"seeds",       "seeds_deleted", "vor_edge", "facet_contact",
                                                 "topo_disk",   "facet_cycle",   "silhouette", "quality",
                                                 "smooth",      "size",          "rejected_witnesses"};

void write_json(const fs::path& path, const nlohmann::json& json) {
  std::ofstream out(path);
  out << json.dump(2) << '\n';
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

//! The independent checker on a mesh file as written (read back as a soup).
MeshReport check_file(const fs::path& path) {
  const TriangleSoup soup = read_triangle_soup(path.string());
  return check_mesh(soup.points, soup.triangles);
}

//! The largest distance from a vertex of `mesh` to the surface of `input` (its AABB tree).
class DistanceToInput {
 public:
  explicit DistanceToInput(const SurfaceMesh& input) : tree_(faces(input).first, faces(input).second, input) {
    tree_.accelerate_distance_queries();
  }
  double max_distance(const SurfaceMesh& mesh) const {
    double largest = 0;
    for (SurfaceMesh::Vertex_index v : mesh.vertices())
      largest = std::max(largest, std::sqrt(tree_.squared_distance(mesh.point(v))));
    return largest;
  }

 private:
  using Primitive = CGAL::AABB_face_graph_triangle_primitive<SurfaceMesh>;
  CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>> tree_;
};

std::string json_field(const nlohmann::json& j, const std::string& key) {
  if (!j.is_object() || !j.contains(key) || j[key].is_null()) return "";
  if (j[key].is_boolean()) return field(j[key].get<bool>());
  if (j[key].is_number_integer()) return field(j[key].get<long long>());
  if (j[key].is_number()) return field(j[key].get<double>());
  return j[key].is_string() ? j[key].get<std::string>() : j[key].dump();
}

//! Extracts data/meshes/NAME.off of the archive into directory; returns the paths.
std::vector<std::string> extract_inputs(const std::string& archive, const std::vector<std::string>& names,
                                        const fs::path& directory) {
  if (!fs::exists(archive)) throw InvalidInput("the archive " + archive + " does not exist (install libcgal-demo)");
  fs::create_directories(directory);
  std::vector<std::string> paths;
  for (const std::string& name : names) {
    const std::string member = "data/meshes/" + name + ".off";
    const std::string command = "tar -xzf '" + archive + "' -C '" + directory.string() + "' '" + member + "'";
    if (std::system(command.c_str()) != 0) throw InvalidInput("cannot extract " + member + " from " + archive);
    paths.push_back((directory / member).string());
  }
  return paths;
}

}  // namespace

int main(int argc, char** argv) {
  delmesh::back_heap_with_huge_pages();
  CLI::App app{"Remesh closed triangle meshes with DelMesh (Fig. 13): topology-phase and final meshes, the "
               "checker's reports and <out-dir>/remesh.csv"};
  std::vector<std::string> paths;
  std::string names = "elephant,eight,knot1";
  std::string archive = "/usr/share/doc/libcgal-dev/data.tar.gz";
  std::string out_dir = "out";
  double min_spacing_fraction = tolerances::min_spacing_median_edge_fraction;
  DelMeshOptions base;
  base.lambda = lambda0;
  base.threads = 1;
  app.add_option("meshes", paths, "closed triangle meshes (.off, .ply, .obj); default: --names from --archive");
  app.add_option("--names", names, "meshes of the archive's data/meshes/ (comma separated)")->capture_default_str();
  app.add_option("--archive", archive, "CGAL's data archive")->capture_default_str();
  app.add_option("--lambda", base.lambda, "lambda")->capture_default_str();
  app.add_option("--min-spacing-fraction", min_spacing_fraction,
                 "termination floor as a fraction of the input's median edge length")
      ->capture_default_str();
  app.add_option("--seed", base.seed, "seed")->capture_default_str();
  app.add_option("--threads", base.threads, "threads (0: every hardware thread)")->capture_default_str();
  app.add_option("--time-limit", base.time_limit_seconds, "time limit per run (s), 0 none")->capture_default_str();
  app.add_option("--max-points", base.max_points, "point limit per run")->capture_default_str();
  app.add_option("--out-dir", out_dir, "output directory")->capture_default_str();
  if (const auto code = parse_command_line(app, argc, argv)) return *code;

  return run_guarded([&] {
    const fs::path dir = fs::path(out_dir) / "remesh";
    fs::create_directories(dir);
    if (paths.empty()) paths = extract_inputs(archive, split(names), dir / "inputs");
    const TheoremBounds bounds = theorem_bounds(base.lambda);

    std::vector<std::string> columns = {"mesh", "phase", "status", "lambda", "min_spacing", "vertices", "triangles",
                                        "seconds", "seconds_validation"};
    for (const std::string& key : insertion_keys) columns.push_back("insertions_" + key);
    append(columns, std::vector<std::string>{"floor_reached", "witnesses_below_floor", "min_angle_deg", "max_radius_edge_ratio",
                     "max_roughness_rad", "bound_min_angle_deg", "bound_max_radius_edge_ratio",
                     "bound_max_roughness_rad", "input_vertices", "input_components", "input_genus",
                     "output_components", "output_genus", "topology_matches", "bbox_diagonal", "max_distance",
                     "max_distance_relative"});
    CsvWriter csv(fs::path(out_dir) / "remesh.csv", "remesh",
                  {{"lambda", field(base.lambda)},
                   {"min_spacing_fraction", field(min_spacing_fraction)},
                   {"seed", field(static_cast<long long>(base.seed))},
                   {"threads", field(base.threads)},
                   {"time_limit", field(base.time_limit_seconds)},
                   {"max_points", field(base.max_points)}},
                  columns);

    for (const std::string& path : paths) {
      const std::string name = fs::path(path).stem().string();
      Stopwatch validation_clock;
      const InputMesh input = read_input_mesh(path);
      const double seconds_validation = validation_clock.seconds();
      write_mesh(input.mesh, (dir / (name + "_input.off")).string());
      const MeshReport input_report = check_file(path);
      write_json(dir / (name + "_input_check.json"), to_json(input_report));
      const DistanceToInput distance(input.mesh);
      std::cout << name << ": " << input.report.vertices << " vertices, genus "
                << field(input.report.genus_per_component) << ", median edge " << input.median_edge_length
                << (input.reoriented() ? ", reoriented outward" : "") << std::endl;

      for (const MeshPhase phase : {MeshPhase::topology, MeshPhase::all}) {
        const std::string label = phase == MeshPhase::topology ? "topology" : "final";
        DelMeshOptions options = base;
        options.phase = phase;
        options.min_spacing = min_spacing_fraction * input.median_edge_length;
        PreparedInput prepared = make_oracle(TriangleMeshInput{path, &input});
        prepared.seconds_validation = seconds_validation;  // reading and validating the mesh
        DelMeshResult result = del_mesh(prepared, options);
        const fs::path mesh_file = dir / (name + "_" + label + ".off");
        write_mesh(result.mesh, mesh_file.string());
        write_json(dir / (name + "_" + label + "_stats.json"), result.statistics);
        const MeshReport report = check_file(mesh_file);
        write_json(dir / (name + "_" + label + "_check.json"), to_json(report));
        const double max_distance = distance.max_distance(result.mesh);

        const nlohmann::json& s = result.statistics;
        std::ostringstream status;
        status << result.status;
        std::vector<std::string> row = {name,
                                        label,
                                        status.str(),
                                        field(options.lambda),
                                        field(options.min_spacing),
                                        field(report.vertices),
                                        field(report.triangles),
                                        json_field(s, "seconds"),
                                        field(seconds_validation)};
        const nlohmann::json insertions = s.contains("insertions") ? s["insertions"] : nlohmann::json::object();
        for (const std::string& key : insertion_keys) row.push_back(json_field(insertions, key));
        const nlohmann::json floor = s.contains("min_spacing") ? s["min_spacing"] : nlohmann::json::object();
        append(row, std::vector<std::string>{json_field(floor, "reached"), json_field(floor, "witnesses_below"), field(report.min_angle_deg),
                     field(report.max_radius_edge_ratio), field(report.max_roughness_rad),
                     field(bounds.min_angle_deg), field(bounds.max_radius_edge_ratio),
                     field(bounds.max_roughness_rad), field(input_report.vertices),
                     field(input_report.components), field(input_report.genus_per_component),
                     field(report.components), field(report.genus_per_component),
                     field(report.has_topology(input_report.genus_per_component) &&
                           report.components == input_report.components),
                     field(input.bounding_box_diagonal), field(max_distance),
                     field(max_distance / input.bounding_box_diagonal)});
        csv.row(row);
        std::cout << "  " << label << ": " << status.str() << ", " << report.vertices << " vertices, "
                  << json_field(s, "seconds") << " s, genus " << field(report.genus_per_component)
                  << ", min angle " << report.min_angle_deg << ", floor reached " << json_field(floor, "reached")
                  << ", max distance / diagonal " << max_distance / input.bounding_box_diagonal << std::endl;
      }
    }
    std::cout << "wrote " << csv.path().string() << " and the meshes in " << dir.string() << std::endl;
  });
}
