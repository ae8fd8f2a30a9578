//! bench_evaluators: evaluations per second of one primitive's values + Jacobian, compiled
//! (CompiledSystem over double, Interval, MPFI) against GiNaC (subs + evalf of the same
//! expressions) on the same points.  Release builds only; prints a table (and optionally CSV).
//!
//!   bench_evaluators [--points N] [--repeats R] [--evalf-points K] [--csv FILE]
//!
//! Timing: each measurement evaluates the whole point set once; the rate reported is from the
//! median of R such measurements.

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "experiments/experiment_support.h"
#include "symbolic/catalog.h"
#include "symbolic/compiled_system.h"
#include "solvers/primitives.h"

using namespace delmesh;

namespace {

using Clock = std::chrono::steady_clock;

//! Median over `repeats` runs of the seconds one call of `run` takes.
double median_seconds(int repeats, const std::function<void()>& run) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    run();
    t.push_back(std::chrono::duration<double>(Clock::now() - start).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

struct Row {
  std::string surface, primitive;
  std::size_t instructions = 0;
  double double_rate = 0, interval_rate = 0, mpfi_rate = 0, evalf_rate = 0;
  double checksum = 0;
};

Row measure(const std::string& surface_name, const std::string& primitive, int n_points, int repeats,
            int evalf_points) {
  const CatalogEntry& entry = catalog_entry(surface_name);
  const PrimitiveSystem system = build_primitive(primitive, entry.surface());
  const CompiledSystem compiled(system);
  const std::size_t n = system.n_unknowns(), p = system.n_parameters(), m = system.n_equations();

  // Points in the catalog box, parameters random unit vectors' components in [-1, 1].
  std::mt19937_64 rng(2026);
  std::vector<double> unknowns(n_points * n), parameters(n_points * p);
  for (int k = 0; k < n_points; ++k) {
    for (std::size_t j = 0; j < n; ++j) {
      const double lo = n == 3 ? entry.box.lo[j] : -1.0, hi = n == 3 ? entry.box.hi[j] : 1.0;
      unknowns[k * n + j] = std::uniform_real_distribution<double>(lo, hi)(rng);
    }
    for (std::size_t j = 0; j < p; ++j) parameters[k * p + j] = std::uniform_real_distribution<double>(-1, 1)(rng);
  }

  Row row{surface_name, primitive, compiled.instruction_count()};
  std::vector<double> values(m), jacobian(m * n);
  const double t_double = median_seconds(repeats, [&] {
    for (int k = 0; k < n_points; ++k) {
      compiled.values_and_jacobian(&unknowns[k * n], &parameters[k * p], values.data(), jacobian.data());
      row.checksum += values[0] + jacobian[0];
    }
  });
  row.double_rate = n_points / t_double;

  std::vector<Interval> box(n_points * n), iparams(parameters.begin(), parameters.end()), ivalues(m),
      ijacobian(m * n);
  for (std::size_t i = 0; i < box.size(); ++i) box[i] = Interval(unknowns[i] - 1e-3, unknowns[i] + 1e-3);
  const double t_interval = median_seconds(repeats, [&] {
    RoundingGuard guard;
    for (int k = 0; k < n_points; ++k) {
      compiled.values_and_jacobian(&box[k * n], &iparams[k * p], ivalues.data(), ijacobian.data());
      row.checksum += ivalues[0].sup();
    }
  });
  row.interval_rate = n_points / t_interval;

  const unsigned saved = MpfiInterval::default_precision();
  MpfiInterval::default_precision(32);  // ≈ 106 bits: the first escalation precision
  const int mpfi_points = std::max(1, n_points / 10);
  std::vector<MpfiInterval> fbox(mpfi_points * n), fparams(mpfi_points * p), fvalues(m), fjacobian(m * n);
  for (int k = 0; k < mpfi_points; ++k) {
    for (std::size_t j = 0; j < n; ++j)
      fbox[k * n + j] = MpfiInterval(unknowns[k * n + j] - 1e-3, unknowns[k * n + j] + 1e-3);
    for (std::size_t j = 0; j < p; ++j) fparams[k * p + j] = MpfiInterval(parameters[k * p + j]);
  }
  const double t_mpfi = median_seconds(repeats, [&] {
    for (int k = 0; k < mpfi_points; ++k) {
      compiled.values_and_jacobian(&fbox[k * n], &fparams[k * p], fvalues.data(), fjacobian.data());
      row.checksum += upper(fvalues[0]).convert_to<double>();
    }
  });
  row.mpfi_rate = mpfi_points / t_mpfi;
  MpfiInterval::default_precision(saved);

  // GiNaC: substitute the point and the parameters, then evalf every value and Jacobian entry.
  std::vector<GiNaC::ex> expressions(system.equations);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t j = 0; j < n; ++j) expressions.push_back(system.jacobian(i, j));
  const int k_points = std::min(evalf_points, n_points);
  const double t_evalf = median_seconds(std::max(1, repeats / 4), [&] {
    for (int k = 0; k < k_points; ++k) {
      GiNaC::exmap sub;
      for (std::size_t j = 0; j < n; ++j) sub[system.unknowns[j]] = unknowns[k * n + j];
      for (std::size_t j = 0; j < p; ++j) sub[system.parameters[j]] = parameters[k * p + j];
      for (const GiNaC::ex& e : expressions)
        row.checksum += GiNaC::ex_to<GiNaC::numeric>(e.subs(sub).evalf()).to_double() * 1e-300;
    }
  });
  row.evalf_rate = k_points / t_evalf;
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Compiled evaluators vs GiNaC evalf: values + Jacobian evaluations per second"};
  int n_points = 2000, repeats = 9, evalf_points = 40;
  std::string csv;
  app.add_option("--points", n_points, "points per measurement (double and Interval; MPFI uses a tenth)");
  app.add_option("--repeats", repeats, "measurements per rate (the median is reported)");
  app.add_option("--evalf-points", evalf_points, "points per GiNaC evalf measurement");
  app.add_option("--csv", csv, "also write the table as CSV to this file");
  if (const auto code = experiments::parse_command_line(app, argc, argv)) return *code;

  std::printf("bench_evaluators (git %s, %s): values + Jacobian per second, median of %d\n\n",
              experiments::git_revision().c_str(), experiments::utc_now().c_str(), repeats);
  std::vector<Row> rows;
  for (const std::string surface : {"genus2", "tanglecube"})
    for (const std::string primitive : {"surface_critical", "silhouette_critical", "surface_plane_contact"})
      rows.push_back(measure(surface, primitive, n_points, repeats, evalf_points));

  std::printf("%-11s %-22s %6s %12s %12s %11s %10s %10s %10s\n", "surface", "primitive", "instr", "double/s",
              "interval/s", "mpfi106/s", "evalf/s", "dbl/evalf", "iv/evalf");
  for (const Row& r : rows)
    std::printf("%-11s %-22s %6zu %12.4g %12.4g %11.4g %10.4g %10.0f %10.0f\n", r.surface.c_str(),
                r.primitive.c_str(), r.instructions, r.double_rate, r.interval_rate, r.mpfi_rate, r.evalf_rate,
                r.double_rate / r.evalf_rate, r.interval_rate / r.evalf_rate);
  double checksum = 0;
  for (const Row& r : rows) checksum += r.checksum;
  std::printf("(checksum %.6g)\n", checksum);

  if (!csv.empty()) {
    experiments::CsvWriter out(csv, "bench_evaluators",
                               {{"points", std::to_string(n_points)},
                                {"repeats", std::to_string(repeats)},
                                {"evalf_points", std::to_string(evalf_points)}},
                               {"surface", "primitive", "instructions", "double_per_s", "interval_per_s",
                                "mpfi106_per_s", "evalf_per_s", "double_over_evalf"});
    for (const Row& r : rows)
      out.row({r.surface, r.primitive, experiments::field(r.instructions), experiments::field(r.double_rate),
               experiments::field(r.interval_rate), experiments::field(r.mpfi_rate),
               experiments::field(r.evalf_rate), experiments::field(r.double_rate / r.evalf_rate)});
  }
  return 0;
}
