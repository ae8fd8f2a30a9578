// Tests of the command's limits over every phase (apps/phase_watchdog.h, common/run_limits.h):
// `--time-limit 1` and a SIGINT stop parsing and differentiating a large expression, reading and
// validating a large input mesh, a remeshing run, and the certificates of `mesh --certify` and
// `check --certify`, each
// within the limit plus `slack`, with exit code 3 and no `error:` line.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "apps/phase_watchdog.h"
#include "run_delmesh.h"

using namespace delmesh::test;
using Clock = std::chrono::steady_clock;

namespace {

// How much later than its limit a command may end: its start-up, the watchdog's polling and
// the writing of a partial result, on a loaded machine; under AddressSanitizer, which slows the
// program's start-up and every step several times, 4 s.
#if defined(__SANITIZE_ADDRESS__)
#define DELMESH_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define DELMESH_TEST_UNDER_ASAN 1
#endif
#endif
#ifdef DELMESH_TEST_UNDER_ASAN
constexpr double slack = 4;
#else
constexpr double slack = 1.5;
#endif

// (2+sin(x+1))*(2+sin(x+2))*…*(2+sin(x+n))*(x^2+y^2+z^2-1): valid, a sphere, and its Hessian and
// compiled systems grow about as n^3.4.  50 factors pass the derivative size limit of
// symbolic/surface.h and take about 35 s to compile and validate; 100 are refused by it.
std::string sin_product(int n) {
  std::string e;
  for (int i = 1; i <= n; ++i) e += "(2+sin(x+" + std::to_string(i) + "))*";
  return e + "(x^2+y^2+z^2-1)";
}

struct TimedRun {
  RunResult result;
  double seconds = 0;
};

TimedRun timed_delmesh(const std::vector<std::string>& args, const std::filesystem::path& directory) {
  const auto start = Clock::now();
  TimedRun r{run_delmesh(args, directory)};
  r.seconds = std::chrono::duration<double>(Clock::now() - start).count();
  return r;
}

// A stop before any output: exit code 3, one warning line naming the status, no `error:`.
void require_stopped_without_output(const RunResult& r, const std::string& status) {
  BOOST_TEST(!r.signalled);
  BOOST_TEST(r.exit_code == 3);
  BOOST_TEST(r.err.find("error:") == std::string::npos, "stderr: " << r.err);
  BOOST_TEST(r.err_lines().size() == 1u, "stderr: " << r.err);
  BOOST_TEST(r.err.rfind("warning:", 0) == 0, "stderr: " << r.err);
  BOOST_TEST(r.err.find("(status " + status + ")") != std::string::npos, "stderr: " << r.err);
}

// A torus of revolution (radii 1 and 0.4) as an OFF grid of n × m vertices.
void write_torus_off(const std::filesystem::path& path, int n, int m) {
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << n * m << ' ' << 2 * n * m << " 0\n";
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * M_PI * i / n, v = 2 * M_PI * j / m;
      out << (1 + 0.4 * std::cos(v)) * std::cos(u) << ' ' << (1 + 0.4 * std::cos(v)) * std::sin(u) << ' '
          << 0.4 * std::sin(v) << '\n';
    }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const int a = i * m + j, b = (i + 1) % n * m + j, c = (i + 1) % n * m + (j + 1) % m, d = i * m + (j + 1) % m;
      out << "3 " << a << ' ' << b << ' ' << c << "\n3 " << a << ' ' << c << ' ' << d << '\n';
    }
}

// The icosphere of two subdivisions (162 vertices, 320 triangles) scaled by `radius`, as OFF.
void write_icosphere_off(const std::filesystem::path& path, double radius) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> v{{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                       {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<std::array<int, 3>> f{{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                    {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                    {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                    {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  auto unit = [](std::array<double, 3> p) {
    const double l = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
    return std::array<double, 3>{p[0] / l, p[1] / l, p[2] / l};
  };
  for (auto& p : v) p = unit(p);
  for (int level = 0; level < 2; ++level) {
    std::map<std::pair<int, int>, int> middle;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto found = middle.find(key);
      if (found != middle.end()) return found->second;
      v.push_back(unit({(v[a][0] + v[b][0]) / 2, (v[a][1] + v[b][1]) / 2, (v[a][2] + v[b][2]) / 2}));
      return middle[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<std::array<int, 3>> finer;
    for (const auto& [a, b, c] : f) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      finer.insert(finer.end(), {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}});
    }
    f = finer;
  }
  std::ofstream out(path);
  out.precision(17);
  out << "OFF\n" << v.size() << ' ' << f.size() << " 0\n";
  for (const auto& p : v) out << radius * p[0] << ' ' << radius * p[1] << ' ' << radius * p[2] << '\n';
  for (const auto& [a, b, c] : f) out << "3 " << a << ' ' << b << ' ' << c << '\n';
}

}  // namespace

BOOST_AUTO_TEST_SUITE(phase_watchdog)

BOOST_AUTO_TEST_CASE(time_limit_stops_compiling_a_large_expression) {
  TempDir scratch;
  // 50 factors, and sin nested 100 deep: each takes tens of seconds to compile and validate.
  std::string nested = "x";
  for (int i = 0; i < 100; ++i) nested = "sin(" + nested + ")";
  for (const std::string& expression : {sin_product(50), nested + "+x^2+y^2+z^2-1"}) {
    const TimedRun r = timed_delmesh({"mesh", "--expr", expression, "--box", "-2,2,-2,2,-2,2", "--time-limit", "1",
                                      "--quiet", "--out", "s.off", "--stats", "s.json"},
                                     scratch.path);
    require_stopped_without_output(r.result, "time_limit");
    BOOST_TEST(r.seconds <= 1 + slack);
    BOOST_TEST(!std::filesystem::exists(scratch.path / "s.off"));
    BOOST_TEST(!std::filesystem::exists(scratch.path / "s.json"));
  }
  // `solve` compiles its primitive from the same expression under the same deadline; its solver
  // stops at it by itself, or the watchdog ends it solve_grace later.
  const TimedRun solve = timed_delmesh({"solve", "--expr", sin_product(50), "--box", "-2,2,-2,2,-2,2", "--primitive",
                                        "surface_critical", "--time-limit", "1"},
                                       scratch.path);
  BOOST_TEST(!solve.result.signalled);
  BOOST_TEST((solve.result.exit_code == 0 || solve.result.exit_code == 3));
  BOOST_TEST(solve.result.err.find("error:") == std::string::npos, "stderr: " << solve.result.err);
  BOOST_TEST(solve.seconds <= 1 + delmesh::app::PhaseWatchdog::solve_grace.count() + slack);
}

BOOST_AUTO_TEST_CASE(a_product_of_100_factors_is_refused_at_once) {
  TempDir scratch;
  const TimedRun r = timed_delmesh({"mesh", "--expr", sin_product(100), "--box", "-2,2,-2,2,-2,2", "--time-limit", "1",
                                    "--quiet", "--out", "s.off", "--stats", "s.json"},
                                   scratch.path);
  require_invalid_input(r.result, "too large to differentiate");
  BOOST_TEST(r.seconds <= 1.0);
}

BOOST_AUTO_TEST_CASE(sigint_stops_differentiating_a_large_expression) {
  TempDir scratch;
  const auto start = Clock::now();
  const pid_t pid = spawn_delmesh({"mesh", "--expr", sin_product(50), "--box", "-2,2,-2,2,-2,2", "--quiet", "--out",
                                   "s.off", "--stats", "s.json"},
                                  scratch.path);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  int status = 0;
  BOOST_TEST(::waitpid(pid, &status, WNOHANG) == 0, "delmesh ended before the signal");
  const auto signalled = Clock::now();
  ::kill(pid, SIGINT);
  const RunResult r = wait_delmesh(pid, scratch.path);
  const double after_signal = std::chrono::duration<double>(Clock::now() - signalled).count();
  BOOST_TEST_MESSAGE("SIGINT at " << std::chrono::duration<double>(signalled - start).count() << " s took effect after "
                                  << after_signal << " s");
  BOOST_TEST(after_signal <= slack);
  BOOST_TEST(!r.signalled);
  require_stopped_without_output(r, "interrupted");
  BOOST_TEST(!std::filesystem::exists(scratch.path / "s.off"));
}

BOOST_AUTO_TEST_CASE(time_limit_stops_validating_a_large_input_mesh) {
  TempDir scratch;
  // 80 000 vertices: reading, validating and building the oracle take several seconds.
  write_torus_off(scratch.path / "big.off", 400, 200);
  const TimedRun r = timed_delmesh({"mesh", "--input-mesh", "big.off", "--time-limit", "1", "--quiet"}, scratch.path);
  require_stopped_without_output(r.result, "time_limit");
  BOOST_TEST(r.seconds <= 1 + slack);
  BOOST_TEST(!std::filesystem::exists(scratch.path / "big_remeshed.off"));
}

BOOST_AUTO_TEST_CASE(time_limit_holds_on_a_tiny_icosphere) {
  TempDir scratch;
  write_icosphere_off(scratch.path / "tiny.off", 1e-80);
  const TimedRun r = timed_delmesh({"mesh", "--input-mesh", "tiny.off", "--time-limit", "1", "--quiet"}, scratch.path);
  BOOST_TEST(!r.result.signalled);
  // However its numerics fare, the run ends by the limit: complete, uncertified or stopped.
  BOOST_TEST((r.result.exit_code == 0 || r.result.exit_code == 3 || r.result.exit_code == 5), "stderr: " << r.result.err);
  BOOST_TEST(r.result.err.find("error:") == std::string::npos, "stderr: " << r.result.err);
  BOOST_TEST(r.seconds <= 1 + slack);
  BOOST_TEST(std::filesystem::exists(scratch.path / "tiny_remeshed.json"));
}

BOOST_AUTO_TEST_CASE(time_limit_stops_the_certificate) {
  TempDir scratch;
  const std::vector<std::string> run{"mesh",     "--surface", "torus", "--size-bound", "0.1", "--threads", "1",
                                     "--certify", "--quiet",  "--out", "t.off",        "--stats", "t.json"};
  // The unlimited run gives the seconds of the mesh and of its certificate.
  const TimedRun full = timed_delmesh(run, scratch.path);
  BOOST_TEST_REQUIRE(full.result.exit_code == 0, "stderr: " << full.result.err);
  const auto stats = nlohmann::json::parse(read_text(scratch.path / "t.json"));
  const double certificate_seconds = stats["certificate"]["seconds"].get<double>();
  const double mesh_seconds = full.seconds - certificate_seconds;
  // A limit within the certificate's time.  A run that is faster than the first one may still end
  // before it (exit 0, within the limit, which breaks no promise); the limit then moves earlier.
  bool stopped = false;
  for (double fraction : {0.5, 0.25, 0.1, 0.0}) {
    const double limit = mesh_seconds + fraction * certificate_seconds;
    std::vector<std::string> limited = run;
    limited.insert(limited.end(), {"--time-limit", std::to_string(limit)});
    const TimedRun r = timed_delmesh(limited, scratch.path);
    BOOST_TEST(!r.result.signalled);
    BOOST_TEST(r.result.err.find("error:") == std::string::npos, "stderr: " << r.result.err);
    BOOST_TEST(r.seconds <= limit + slack, "limit " << limit << " s");
    if (r.result.exit_code == 0) continue;
    BOOST_TEST(r.result.exit_code == 3, "stderr: " << r.result.err);
    const auto cut = nlohmann::json::parse(read_text(scratch.path / "t.json"));
    BOOST_TEST(cut["status"] == "time_limit");
    // On a loaded machine the mesh itself may reach the limit; otherwise the certificate did.
    if (cut.contains("run_status")) {
      BOOST_TEST(cut["run_status"] == "complete");
      BOOST_TEST(cut["certificate"]["time_limited"] == true);
      BOOST_TEST(cut["certificate"]["status"] == "undecided");
    }
    stopped = true;
    break;
  }
  BOOST_TEST(stopped, "no limit within the certificate's time stopped the run");
}

BOOST_AUTO_TEST_CASE(time_limit_stops_the_certificate_of_check) {
  TempDir scratch;
  const RunResult made = run_delmesh({"mesh", "--surface", "torus", "--size-bound", "0.05", "--threads", "1", "--quiet",
                                      "--out", "t.off", "--stats", "t.json"},
                                     scratch.path);
  BOOST_TEST_REQUIRE(made.exit_code == 0, "stderr: " << made.err);
  const std::vector<std::string> check{"check", "t.off", "--surface", "torus", "--certify", "--json"};
  const TimedRun full = timed_delmesh(check, scratch.path);
  BOOST_TEST_REQUIRE(full.result.exit_code == 0, "stderr: " << full.result.err);
  const double certificate_seconds = nlohmann::json::parse(full.result.out)["certificate"]["seconds"].get<double>();
  // Half the certificate's own time: reading and checking the mesh take a small part of it.
  const double limit = 0.5 * certificate_seconds;
  std::vector<std::string> limited = check;
  limited.insert(limited.end(), {"--time-limit", std::to_string(limit)});
  const TimedRun r = timed_delmesh(limited, scratch.path);
  BOOST_TEST(!r.result.signalled);
  BOOST_TEST(r.result.exit_code == 3, "stderr: " << r.result.err);
  BOOST_TEST(r.result.err.find("error:") == std::string::npos, "stderr: " << r.result.err);
  BOOST_TEST(r.seconds <= limit + slack, "limit " << limit << " s, certificate " << certificate_seconds << " s");
  // The report is printed, with the certificate undecided and marked as stopped by the limit.
  const auto cut = nlohmann::json::parse(r.result.out);
  BOOST_TEST(cut["certificate"]["time_limited"] == true);
  BOOST_TEST(cut["certificate"]["status"] == "undecided");
  BOOST_TEST(cut["vertices"] == nlohmann::json::parse(full.result.out)["vertices"]);
  BOOST_TEST(r.result.err.find("stopped by --time-limit") != std::string::npos, "stderr: " << r.result.err);
  // Out of range: refused like mesh's and solve's.
  require_invalid_input(run_delmesh({"check", "t.off", "--time-limit", "-1"}, scratch.path), "--time-limit");
}

BOOST_AUTO_TEST_SUITE_END()
