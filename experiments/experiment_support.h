#pragma once
//! \file experiment_support.h
//! What every experiment program shares (header only: each experiments/*.cpp is one program):
//! the CSV files with their metadata (experiments/csv_writer.h), the error policy and command-line
//! parsing, E compiled for fast double evaluation, a point inside Σ, and the checker columns.

#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common/errors.h"
#include "experiments/csv_writer.h"
#include "meshing/core/mesh_checker.h"
#include "symbolic/compiled_system.h"
#include "symbolic/surface.h"

namespace delmesh::experiments {

//! Runs an experiment's body with the programs' error policy: InvalidInput → `error: …` on stderr
//! and exit code 2; any other exception → `error: …` and exit code 1; otherwise 0.
template <class Body>
int run_guarded(Body&& body) {
  try {
    body();
  } catch (const InvalidInput& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << std::endl;
    return 1;
  }
  return 0;
}

//! Parses the command line.  A usage error (an unknown option, a value out of range, …) prints
//! one line `error: …` on stderr and gives exit code 2, as `delmesh` does; --help prints the help
//! and gives 0.  Returns the code main() should return then, or nothing when the run goes on.
inline std::optional<int> parse_command_line(CLI::App& app, int argc, char** argv) {
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);
    std::cerr << "error: " << e.what() << std::endl;
    return 2;
  }
  return std::nullopt;
}

//! The non-empty items of a comma-separated list ("torus,genus2" → {"torus", "genus2"}).
inline std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  std::string part;
  while (std::getline(in, part, ','))
    if (!part.empty()) parts.push_back(part);
  return parts;
}

//! Seconds of wall-clock time since construction.
class Stopwatch {
 public:
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

//! E and ∇E of a surface compiled once, evaluated in double.  Cheap to copy (shared program).
class CompiledE {
 public:
  explicit CompiledE(const Surface& surface)
      : system_(std::make_shared<CompiledSystem>(
            std::vector<GiNaC::ex>{surface.E()},
            std::vector<GiNaC::symbol>{coordinate_x(), coordinate_y(), coordinate_z()},
            std::vector<GiNaC::symbol>{})) {}
  double operator()(double x, double y, double z) const {
    const double p[3] = {x, y, z};
    double value = 0;
    system_->values<double>(p, nullptr, &value);
    return value;
  }
  //! Returns E(p) and writes ∇E(p) to gradient.
  double value_and_gradient(const std::array<double, 3>& p, std::array<double, 3>& gradient) const {
    double value = 0;
    system_->values_and_jacobian<double>(p.data(), nullptr, &value, gradient.data());
    return value;
  }

 private:
  std::shared_ptr<const CompiledSystem> system_;
};

//! The most negative sample of E on a regular grid of the box (n³ points): a point inside Σ for the
//! CGAL meshers' bounding spheres (which need E(centre) < 0).  Throws if no sample is negative.
inline std::array<double, 3> inside_point(const CompiledE& E, const Box3& box, int n = 41) {
  std::array<double, 3> best{};
  double best_value = std::numeric_limits<double>::infinity();
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        const std::array<double, 3> p{box.lo[0] + (box.hi[0] - box.lo[0]) * (i + 0.5) / n,
                                      box.lo[1] + (box.hi[1] - box.lo[1]) * (j + 0.5) / n,
                                      box.lo[2] + (box.hi[2] - box.lo[2]) * (k + 0.5) / n};
        const double value = E(p[0], p[1], p[2]);
        if (value < best_value) {
          best_value = value;
          best = p;
        }
      }
  if (!(best_value < 0)) throw std::runtime_error("no point with E < 0 found in the box");
  return best;
}

//! Squared radius of the smallest sphere about centre that contains the box.
inline double enclosing_squared_radius(const std::array<double, 3>& centre, const Box3& box) {
  double r2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double d = std::max(centre[i] - box.lo[i], box.hi[i] - centre[i]);
    r2 += d * d;
  }
  return r2;
}

//! Column names and fields of the checker's report, in the same order.
inline std::vector<std::string> report_columns() {
  return {"vertices", "triangles", "components", "euler_characteristic", "genus_per_component",
          "closed", "manifold", "orientable", "min_angle_deg", "max_radius_edge_ratio",
          "max_roughness_rad"};
}
inline std::vector<std::string> report_fields(const MeshReport& r) {
  return {field(r.vertices), field(r.triangles), field(r.components), field(r.euler_characteristic),
          field(r.genus_per_component), field(r.closed), field(r.manifold), field(r.orientable),
          field(r.min_angle_deg), field(r.max_radius_edge_ratio), field(r.max_roughness_rad)};
}

template <class T>
void append(std::vector<T>& to, const std::vector<T>& from) {
  to.insert(to.end(), from.begin(), from.end());
}

}  // namespace delmesh::experiments
