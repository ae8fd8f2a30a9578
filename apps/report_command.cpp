//! \file report_command.cpp
//! `delmesh report MESH [--stats STATS.json] [--color min-angle|radius-edge|area|none] --out
//! report.html`: one self-contained HTML page about a mesh file (apps/report_html.h): an
//! interactive 3-D view with the triangles coloured by a quality measure, histograms of the
//! angles and radius-edge ratios, the checker's report and, with --stats, the statistics of
//! `delmesh mesh` as tables.  The mesh is read as `delmesh check` reads it (OFF, PLY, OBJ or STL,
//! polygons triangulated); the page is written all or nothing (apps/output_files.h).

#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <system_error>

#include <nlohmann/json.hpp>

#include "apps/command_line.h"
#include "apps/output_files.h"
#include "apps/phase_watchdog.h"
#include "apps/report_html.h"
#include "apps/report_three_js.h"
#include "common/errors.h"
#include "meshing/core/mesh_checker.h"
#include "meshing/inputs/mesh_io.h"

namespace delmesh::app {

namespace {

struct ReportOptions {
  std::string mesh;
  std::string stats;
  std::string color = "min-angle";
  std::string out;
  CLI::Option* stats_option = nullptr;
};

//! The statistics file: a JSON object.  Throws InvalidInput naming the file otherwise.
nlohmann::ordered_json read_statistics(const std::string& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) throw InvalidInput("--stats " + path + ": is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InvalidInput("--stats " + path + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InvalidInput("--stats " + path + ": cannot read the file");
  nlohmann::ordered_json statistics;
  try {
    statistics = nlohmann::ordered_json::parse(text.str());
  } catch (const nlohmann::json::exception& e) {
    throw InvalidInput("--stats " + path + ": not a JSON file (" + e.what() + ")");
  }
  if (!statistics.is_object())
    throw InvalidInput("--stats " + path + ": expected a JSON object (the statistics `delmesh mesh` writes)");
  return statistics;
}

//! True if a and b name the same existing file.
bool same_file(const std::string& a, const std::string& b) {
  std::error_code error;
  return std::filesystem::equivalent(a, b, error) && !error;
}

ExitCode run_report(const ReportOptions& o) {
  const ReportColor color = parse_enum<ReportColor>(o.color, "--color");
  const std::string unavailable = three_js_unavailable_reason();
  if (!unavailable.empty()) throw InvalidInput(unavailable);
  if (same_file(o.out, o.mesh)) throw InvalidInput("--out " + o.out + " is the mesh file itself");
  if (o.stats_option->count() > 0 && same_file(o.out, o.stats))
    throw InvalidInput("--out " + o.out + " is the statistics file itself");
  OutputSet outputs;
  outputs.add("--out", o.out);

  // Read as `delmesh check` reads it: any soup, polygons triangulated.
  const TriangleSoup soup = triangulate_polygons(read_polygon_soup(o.mesh), o.mesh);
  ReportPage page;
  page.mesh_name = o.mesh;
  page.soup = &soup;
  page.check = check_mesh(soup.points, soup.triangles);
  page.color = color;
  if (o.stats_option->count() > 0) {
    page.statistics = read_statistics(o.stats);
    page.statistics_name = o.stats;
    // Statistics of another mesh are shown all the same, with a warning.
    const auto count = [&](const char* key) -> std::optional<std::size_t> {
      const auto it = page.statistics->find(key);
      if (it == page.statistics->end() || !it->is_number_unsigned()) return std::nullopt;
      return it->get<std::size_t>();
    };
    const std::optional<std::size_t> vertices = count("vertices"), triangles = count("triangles");
    if ((vertices && *vertices != page.check.vertices) || (triangles && *triangles != page.check.triangles)) {
      const std::string note = "the statistics " + o.stats + " describe a mesh of " +
                               (vertices ? std::to_string(*vertices) : "?") + " vertices and " +
                               (triangles ? std::to_string(*triangles) : "?") + " triangles, " + o.mesh + " has " +
                               std::to_string(page.check.vertices) + " and " + std::to_string(page.check.triangles);
      print_warning(note);
      page.notes.push_back("Warning: " + note + ".");
    }
  }
  page.three_js = three_js_module();
  page.three_js_version = three_js_version();
  page.program_version = "delmesh 0.1.0";
  outputs.write({[&](std::ostream& s) { write_report_page(s, page); }});
  return ExitCode::complete;
}

}  // namespace

Command add_report_command(CLI::App& parent) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App* sub = parent.add_subcommand("report", "Write one self-contained HTML page about a mesh (3-D view, quality, statistics)");
  sub->footer(
      "Write a single HTML file that needs no network and no installed viewer: an interactive 3-D view of the "
      "mesh (three.js, embedded; drag to rotate, wheel to zoom, click a triangle for its measures) with the "
      "triangles coloured by a quality measure and a legend, histograms of the angles and of the radius-edge "
      "ratios, the checker's report (as `delmesh check`), and with --stats the statistics JSON of `delmesh mesh`: "
      "the run, the distance certificate, Theorem 6.1's bounds checked on the file, and every statistic as "
      "tables.\n\n"
      "Exit codes: 0 written, 2 invalid input (missing or corrupt mesh or statistics file, a program built "
      "without three.js), 3 stopped by a signal, 4 internal error, 6 the page could not be written (an existing "
      "file is left as it was).");
  sub->add_option("MESH", o->mesh, "The mesh file (.off, .ply or .obj; polygons are triangulated)")->required();
  o->stats_option =
      sub->add_option("--stats", o->stats, "The statistics JSON that `delmesh mesh` wrote for the mesh")->type_name("STATS.json");
  sub->add_option("--color", o->color,
                  "What the triangles are coloured by when the page opens: min-angle, radius-edge, area (relative "
                  "to the mean) or none; the page can switch")
      ->type_name("M")
      ->capture_default_str();
  sub->add_option("--out", o->out, "The HTML file to write (- for standard output)")->type_name("FILE.html")->required();
  return {sub, [o]() { return stopped_as_limit([&] { return run_report(*o); }); }};
}

}  // namespace delmesh::app
