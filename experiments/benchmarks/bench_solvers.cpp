//! bench_solvers: medians (one thread, pinned to one core when possible) and box counts of the
//! certified solvers.
//!  1. Univariate isolation (isolate_line_roots, Bernstein path, coefficient enclosure included)
//!     at degree 4–10: E = Π_i (x − r_i) + y² + z² − 1/100 with d random r_i ∈ [−0.9, 0.9], on
//!     random lines near the x axis, t ∈ [0, 1] covering x ∈ [−1.2, 1.2] (up to d real roots).
//!     Target: ≤ 3 µs per polynomial at degree 10.
//!  2. Each primitive of the registry (solvers/primitive_registry.h) on torus, genus2, tanglecube
//!     with random options over a domain the size of a typical Voronoi cell: around a random
//!     surface point x (found by isolating a random line through the catalog box), the box is the
//!     cube of side `side` centred at x; every position option (--point, --plane-origin) is x and
//!     every direction option a random unit vector; the row's make_query turns them into the
//!     parameters and the domain (the cube, the line or the polygon plane ∩ cube), and
//!     solve_query solves it (the univariate isolator for a line, subdivision otherwise).
//!
//!   bench_solvers [--queries N] [--side S] [--seed K] [--taylor-forms automatic|always|never] [--csv FILE]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <sched.h>

#include <CLI/CLI.hpp>

#include "experiments/experiment_support.h"
#include "solvers/primitive_registry.h"
#include "solvers/primitives.h"
#include "solvers/query_geometry.h"
#include "solvers/subdivision_solver.h"
#include "solvers/univariate_isolator.h"
#include "symbolic/catalog.h"
#include "symbolic/line_polynomial.h"

using namespace delmesh;

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

struct Stats {
  std::vector<double> seconds, boxes;
  std::map<std::string, int> statuses;
  std::size_t roots = 0, undecided = 0;
  void add(const SolveResult& r, double s) {
    seconds.push_back(s);
    boxes.push_back(static_cast<double>(r.counters.boxes));
    std::ostringstream status;
    status << r.status;
    ++statuses[status.str()];
    roots += r.roots.size();
    undecided += r.undecided.size();
    for (const auto& u : r.undecided) {
      std::ostringstream reason;
      reason << u.reason;
      ++statuses["undecided_" + reason.str()];
    }
  }
  std::string status_text() const {
    std::string text;
    for (const auto& [k, v] : statuses) text += (text.empty() ? "" : " ") + k + ":" + std::to_string(v);
    return text;
  }
};

Vec3 random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return unit_vector({n(rng), n(rng), n(rng)});
}

std::string fmt(double x, int precision = 4) {
  std::ostringstream out;
  out.precision(precision);
  out << x;
  return out.str();
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"bench_solvers: certified solver timings"};
  int queries = 200;
  double side = 0.25;
  std::uint64_t seed = 1;
  std::string csv;
  TaylorForms taylor_forms = TaylorForms::automatic;
  app.add_option("--taylor-forms", taylor_forms, "subdivision on Taylor forms of polynomial systems")
      ->transform(CLI::CheckedTransformer(enum_name_map<TaylorForms>()));
  app.add_option("--queries", queries, "queries per primitive and surface (and lines per degree / 10)");
  app.add_option("--side", side, "side of the Voronoi-cell-sized domain");
  app.add_option("--seed", seed, "random seed");
  app.add_option("--csv", csv, "also write the table as CSV");
  if (const auto code = experiments::parse_command_line(app, argc, argv)) return *code;

  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(0, &set);
  const bool pinned = sched_setaffinity(0, sizeof set, &set) == 0;

  std::unique_ptr<experiments::CsvWriter> out;
  if (!csv.empty())
    out = std::make_unique<experiments::CsvWriter>(
        csv, "bench_solvers",
        std::vector<std::pair<std::string, std::string>>{
            {"queries", std::to_string(queries)}, {"side", fmt(side)}, {"seed", std::to_string(seed)}},
        std::vector<std::string>{"benchmark", "surface", "primitive", "calls", "median_us", "median_boxes",
                                 "roots", "undecided", "statuses"});
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(-1, 1);
  std::printf("bench_solvers (git %s, %s)\n\n", experiments::git_revision().c_str(),
              pinned ? "pinned to CPU 0" : "not pinned");

  // ---- 1. univariate isolation ----
  std::printf("univariate isolation, E = prod(x - r_i) + y^2 + z^2 - 0.01 on lines near the x axis\n");
  std::printf("%6s %8s %12s %12s %10s %10s\n", "degree", "calls", "median_us", "median_box", "roots/call",
              "undecided");
  for (int degree = 4; degree <= 10; ++degree) {
    std::ostringstream text;
    for (int i = 0; i < degree; ++i) text << (i ? "*" : "") << "(x-(" << fmt(0.9 * uni(rng), 6) << "))";
    text << "+y^2+z^2-0.01";
    const Surface surface = Surface::parse(text.str());
    const CompiledSystem line(surface_line_system(surface));
    const LinePolynomial polynomial(surface);
    Stats stats;
    const int lines = std::max(10, queries) * 10;
    for (int q = 0; q < lines; ++q) {
      const std::array<double, 3> p{-1.2, 0.05 * uni(rng), 0.05 * uni(rng)}, v{2.4, 0.05 * uni(rng), 0.05 * uni(rng)};
      const auto start = Clock::now();
      const SolveResult r = isolate_line_roots(line, &polynomial, p, v, 0, 1);
      stats.add(r, std::chrono::duration<double>(Clock::now() - start).count());
    }
    std::printf("%6d %8d %12.3f %12.0f %10.2f %10zu   %s\n", degree, lines, 1e6 * median(stats.seconds),
                median(stats.boxes), static_cast<double>(stats.roots) / lines, stats.undecided,
                stats.status_text().c_str());
    if (out)
      out->row({"univariate", "prod_degree_" + std::to_string(degree), "surface_line", std::to_string(lines),
                fmt(1e6 * median(stats.seconds), 6), fmt(median(stats.boxes)), std::to_string(stats.roots),
                std::to_string(stats.undecided), stats.status_text()});
  }

  // ---- 2. every primitive of the registry over Voronoi-cell-sized domains ----
  std::printf("\nprimitives over a domain of side %.3g around a random surface point (%d queries each)\n", side,
              queries);
  std::printf("%-11s %-25s %12s %12s %8s %10s   %s\n", "surface", "primitive", "median_us", "median_box", "roots",
              "undecided", "statuses");
  for (const std::string name : {"torus", "genus2", "tanglecube"}) {
    const CatalogEntry& entry = catalog_entry(name);
    const Surface surface = entry.surface();
    const CompiledSystem line(surface_line_system(surface));
    const LinePolynomial polynomial(surface);
    // Random surface points: roots of random lines through the catalog box.
    std::vector<Vec3> points;
    while (static_cast<int>(points.size()) < queries) {
      Vec3 p, v = random_unit(rng);
      for (int i = 0; i < 3; ++i) p[i] = entry.box.lo[i] + (0.5 + 0.4 * uni(rng)) * (entry.box.hi[i] - entry.box.lo[i]);
      const auto range = clip_line_to_box(p, v, entry.box);
      if (!range) continue;
      const SolveResult r = isolate_line_roots(line, &polynomial, p, v, (*range)[0], (*range)[1]);
      for (const auto& root : r.roots)
        if (static_cast<int>(points.size()) < queries) points.push_back(root.world);
    }
    const double h = 0.5 * side;
    for (const PrimitiveInfo& info : primitive_registry()) {
      const CompiledPrimitive primitive(info.build(surface));
      QuerySolveOptions options;
      options.taylor_forms = taylor_forms;
      Stats stats;
      for (const Vec3& x : points) {
        QueryOptions given;
        for (const OptionUse& use : info.options) given.values[use.option] = is_position(use.option) ? x : random_unit(rng);
        const Box3 cube{{x[0] - h, x[1] - h, x[2] - h}, {x[0] + h, x[1] + h, x[2] + h}};
        const auto start = Clock::now();
        const SolveResult r = solve_query(primitive, info.query(given, cube), options, &polynomial);
        stats.add(r, std::chrono::duration<double>(Clock::now() - start).count());
      }
      std::printf("%-11s %-25s %12.1f %12.0f %8zu %10zu   %s\n", name.c_str(), info.name.c_str(),
                  1e6 * median(stats.seconds), median(stats.boxes), stats.roots, stats.undecided,
                  stats.status_text().c_str());
      if (out)
        out->row({"primitive", name, info.name, std::to_string(points.size()), fmt(1e6 * median(stats.seconds), 6),
                  fmt(median(stats.boxes)), std::to_string(stats.roots), std::to_string(stats.undecided),
                  stats.status_text()});
    }
  }
  if (out) out->close();
  return 0;
}
