// bench_homotopy: subdivision vs homotopy on the same systems (Release, one core).
//  1. SurfaceCritical-shaped Kostlan systems: E a random Kostlan polynomial of degree d in (x, y, z),
//     the system E = ⟨∇E, a⟩ = ⟨∇E, b⟩ = 0 (degrees d, d−1, d−1; d(d−1)² paths) for a random
//     direction, over [−1, 1]³.  Targets: subdivision ≤ 5 ms at d = 4, ≤ 200 ms at d = 8.
//  2. surface_critical of the catalog surfaces torus, genus2, tanglecube over their catalog box,
//     in a generic (seeded) direction.
// Reports medians of the thread CPU time per system (one core), box counts, paths, mean predictor–corrector
// steps per path (accepted + rejected, endgame included), roots and the time ratio homotopy / subdivision;
// optionally writes CSV (with the git revision and the parameters).

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#define FMT_HEADER_ONLY  // experiments do not link libfmt
#include <fmt/format.h>

#include "experiments/experiment_support.h"
#include "solvers/homotopy_solver.h"
#include "solvers/kostlan_system.h"
#include "solvers/query_geometry.h"
#include "solvers/subdivision_solver.h"
#include "symbolic/catalog.h"
#include "solvers/primitives.h"

using namespace delmesh;

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0;
  std::sort(v.begin(), v.end());
  const std::size_t m = v.size() / 2;
  return v.size() % 2 ? v[m] : 0.5 * (v[m - 1] + v[m]);
}

std::string git_revision(const std::string& repository) {
  std::string out;
  const std::string command = "git -C '" + repository + "' rev-parse --short HEAD 2>/dev/null";
  if (FILE* pipe = popen(command.c_str(), "r")) {
    char buffer[64];
    while (fgets(buffer, sizeof buffer, pipe)) out += buffer;
    pclose(pipe);
  }
  out.erase(std::remove(out.begin(), out.end(), '\n'), out.end());
  return out.empty() ? "unknown" : out;
}

//! CPU time of this thread (the machine may be shared: wall time would count other processes).
double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

template <class F>
double seconds_of(F&& f) {
  const double t0 = thread_seconds();
  f();
  return thread_seconds() - t0;
}

struct Row {
  std::string name;
  std::size_t systems = 0;
  std::vector<double> sub_seconds, hom_seconds, ratio, boxes, paths, steps_per_path, roots_sub, roots_hom;
  std::size_t sub_complete = 0, hom_complete = 0, both_complete = 0, count_mismatch = 0;
};

//! Solves one system with both solvers `repeats` times; records medians of this system.
void measure(Row& row, const CompiledSystem& compiled, const std::vector<int>& degrees,
             const std::vector<double>& parameters, const Domain& domain, std::uint64_t seed, int repeats) {
  std::vector<double> ts, th;
  SolveResult sub;
  HomotopySolveResult hom;
  HomotopyOptions options;
  options.seed = seed;
  for (int r = 0; r < repeats; ++r) {
    ts.push_back(seconds_of([&] { sub = solve_subdivision(compiled, parameters, domain); }));
    th.push_back(seconds_of([&] { hom = solve_homotopy(compiled, degrees, parameters, domain, options); }));
  }
  ++row.systems;
  row.sub_seconds.push_back(median(ts));
  row.hom_seconds.push_back(median(th));
  row.ratio.push_back(median(th) / median(ts));
  row.boxes.push_back(static_cast<double>(sub.counters.boxes));
  row.paths.push_back(static_cast<double>(hom.counters.paths));
  row.steps_per_path.push_back(static_cast<double>(hom.statistics.steps + hom.statistics.rejections) /
                               static_cast<double>(std::max<std::size_t>(hom.counters.paths, 1)));
  row.roots_sub.push_back(static_cast<double>(sub.roots.size()));
  row.roots_hom.push_back(static_cast<double>(hom.roots.size()));
  row.sub_complete += sub.is_complete();
  row.hom_complete += hom.is_complete();
  if (sub.is_complete() && hom.is_complete()) {
    ++row.both_complete;
    row.count_mismatch += sub.roots.size() != hom.roots.size();
  }
}

void print(const Row& row, std::ostream* csv, const std::string& revision) {
  std::cout << fmt::format(
      "{:<26} {:>4} | subdiv {:>9.3f} ms  boxes {:>7.0f} complete {:>3}/{} | homotopy {:>9.3f} ms  paths {:>5.0f} "
      "steps/path {:>6.1f} complete {:>3}/{} | ratio hom/sub {:>6.2f} | roots {:>4.1f}/{:>4.1f} | count mismatches {}\n",
      row.name, row.systems, 1e3 * median(row.sub_seconds), median(row.boxes), row.sub_complete, row.systems,
      1e3 * median(row.hom_seconds), median(row.paths), median(row.steps_per_path), row.hom_complete, row.systems,
      median(row.ratio), median(row.roots_sub), median(row.roots_hom), row.count_mismatch);
  if (csv)
    *csv << fmt::format("{},{},{},{:.6f},{:.0f},{},{:.6f},{:.0f},{:.2f},{},{:.4f},{},{}\n", revision, row.name,
                        row.systems, 1e3 * median(row.sub_seconds), median(row.boxes), row.sub_complete,
                        1e3 * median(row.hom_seconds), median(row.paths), median(row.steps_per_path),
                        row.hom_complete, median(row.ratio), row.both_complete, row.count_mismatch);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"subdivision vs homotopy: Kostlan SurfaceCritical systems and catalog surfaces"};
  int systems = 15, repeats = 3;
  std::uint64_t seed = 1;
  std::vector<int> kostlan_degrees{4, 8};
  std::vector<std::string> surfaces{"torus", "genus2", "tanglecube"};
  std::string csv_path, repository = ".";
  app.add_option("--systems", systems, "random systems per degree")->check(CLI::PositiveNumber);
  app.add_option("--repeats", repeats, "timed repetitions per system (median)")->check(CLI::PositiveNumber);
  app.add_option("--seed", seed, "first seed");
  app.add_option("--degrees", kostlan_degrees, "Kostlan degrees of E");
  app.add_option("--surfaces", surfaces, "catalog surfaces for surface_critical");
  app.add_option("--csv", csv_path, "write a CSV file");
  app.add_option("--repository", repository, "the delmesh git checkout (for the revision recorded)");
  if (const auto code = experiments::parse_command_line(app, argc, argv)) return *code;

  const std::string revision = git_revision(repository);
  std::ofstream csv_file;
  std::ostream* csv = nullptr;
  if (!csv_path.empty()) {
    csv_file.open(csv_path);
    csv = &csv_file;
    *csv << "# bench_homotopy revision " << revision << " systems " << systems << " repeats " << repeats << " seed "
         << seed << "\n";
    *csv << "revision,name,systems,subdivision_ms_median,boxes_median,subdivision_complete,homotopy_ms_median,"
            "paths_median,steps_per_path_median,homotopy_complete,ratio_median,both_complete,count_mismatches\n";
  }
  std::cout << "bench_homotopy revision " << revision << " (medians over systems of the thread CPU time, each the median of "
            << repeats << " runs; one core)\n";

  const Domain unit_box = Domain::from_box({{{-1.0, 1.0}}, {{-1.0, 1.0}}, {{-1.0, 1.0}}});
  for (int d : kostlan_degrees) {
    Row row;
    row.name = fmt::format("kostlan_critical_d{}", d);
    for (int k = 0; k < systems; ++k) {
      const std::uint64_t s = seed + static_cast<std::uint64_t>(k);
      KostlanRng rng(s);
      const Surface surface(kostlan_polynomial({coordinate_x(), coordinate_y(), coordinate_z()}, d, rng));
      const PrimitiveSystem system = surface_critical_system(surface);
      const CompiledSystem compiled(system);
      const Vec3 direction = unit_vector({rng.normal(), rng.normal(), rng.normal()});
      const auto frame = orthonormal_frame(direction);
      const std::vector<double> parameters{frame.a[0], frame.a[1], frame.a[2], frame.b[0], frame.b[1], frame.b[2]};
      measure(row, compiled, equation_degrees(system), parameters, unit_box, s, repeats);
    }
    print(row, csv, revision);
  }

  for (const auto& name : surfaces) {
    const CatalogEntry& entry = catalog_entry(name);
    const PrimitiveSystem system = surface_critical_system(entry.surface());
    const CompiledSystem compiled(system);
    const auto degrees = equation_degrees(system);
    const Domain domain = box_domain(entry.box);
    Row row;
    row.name = "critical_" + name;
    KostlanRng rng(seed);
    for (int k = 0; k < std::min(systems, 5); ++k) {
      const Vec3 direction = unit_vector({rng.normal(), rng.normal(), rng.normal()});
      const auto frame = orthonormal_frame(direction);
      const std::vector<double> parameters{frame.a[0], frame.a[1], frame.a[2], frame.b[0], frame.b[1], frame.b[2]};
      measure(row, compiled, degrees, parameters, domain, seed + k, repeats);
    }
    print(row, csv, revision);
  }
  std::cout << "targets: subdivision on kostlan_critical_d4 <= 5 ms, kostlan_critical_d8 <= 200 ms\n";
  return 0;
}
