// Tests of apps/interrupt.h: SIGINT and SIGTERM stop `delmesh mesh` like a limit, and stop the
// certificate of `delmesh check --certify` and `delmesh mesh --certify` with nothing lost; every
// handled signal, at any moment of any subcommand, ends the program with an exit code, never by
// the signal; a second signal removes the temporary files.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/inputs/mesh_io.h"
#include "run_delmesh.h"

using namespace delmesh;
using namespace delmesh::test;

namespace {

// Whether process `pid` has a handler installed for `signal`: bit signal - 1 of the hexadecimal
// mask on the SigCgt line of /proc/pid/status.
bool catches(pid_t pid, int signal) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("SigCgt:", 0) == 0) return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1)) & 1u;
  return false;
}

// Starts `delmesh args...` in `directory` (stdout and stderr to the files stdout.txt and
// stderr.txt there), sends `signal` once the process has installed its handler for it and stderr
// contains `trigger` (if not empty), after a further `delay`, and returns the exit status of
// waitpid.  Fails the test if the handler or the trigger has not appeared after 120 s or the
// process ended before the signal.
int run_and_signal(const std::vector<std::string>& args, const std::filesystem::path& directory, int signal,
                   std::chrono::milliseconds delay, const std::string& trigger = {}) {
  std::vector<std::string> argv_text{DELMESH_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const std::string out = (directory / "stdout.txt").string(), err = (directory / "stderr.txt").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(directory.c_str()) != 0) ::_exit(127);
    const int null = ::open("/dev/null", O_RDONLY);
    const int out_fd = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int err_fd = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(null, 0);
    ::dup2(out_fd, 1);
    ::dup2(err_fd, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!catches(pid, signal) || (!trigger.empty() && read_text(err).find(trigger) == std::string::npos)) {
    if (::waitpid(pid, &status, WNOHANG) == pid) {
      BOOST_ERROR("delmesh ended before its handler was installed and '" << trigger
                                                                           << "' appeared on stderr: " << read_text(err));
      return status;
    }
    if (std::chrono::steady_clock::now() > give_up) {
      BOOST_ERROR("no handler, or '" << trigger << "' not on stderr, within 120 s");
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  std::this_thread::sleep_for(delay);
  BOOST_TEST(::waitpid(pid, &status, WNOHANG) == 0, "delmesh ended before the signal");
  ::kill(pid, signal);
  ::waitpid(pid, &status, 0);
  return status;
}

// A run long enough to be interrupted (about 10^5 samples), stopped by `signal`: exit code 3,
// status interrupted, and both files written completely — the mesh that stood in the output's
// place before is replaced by a partial mesh that matches the statistics.
void check_interrupted_by(int signal) {
  TempDir scratch;
  write_text(scratch / "torus.off", "previous contents\n");
  const int status = run_and_signal({"mesh", "--surface", "torus", "--size-bound", "0.01", "--threads", "1"},
                                    scratch.path, signal, std::chrono::milliseconds(1500));
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 3);
  const auto stats = nlohmann::json::parse(read_text(scratch / "torus.json"));
  BOOST_TEST(stats["status"] == "interrupted");
  const TriangleSoup soup = read_triangle_soup((scratch / "torus.off").string());
  BOOST_TEST(soup.points.size() == stats["vertices"].get<std::size_t>());
  BOOST_TEST(soup.triangles.size() == stats["triangles"].get<std::size_t>());
  BOOST_TEST(stats["points"].get<std::size_t>() < 100000u);
}

}  // namespace

BOOST_AUTO_TEST_SUITE(interrupt)

BOOST_AUTO_TEST_CASE(sigint_stops_the_run_with_its_partial_mesh) { check_interrupted_by(SIGINT); }

BOOST_AUTO_TEST_CASE(sigterm_stops_the_run_with_its_partial_mesh) { check_interrupted_by(SIGTERM); }

// A signal during the certificate of `mesh --certify` (sent once the program says it certifies):
// exit code 3; the finished mesh is written whole and matches the statistics, whose status is
// interrupted (with run_status complete: the mesh itself finished) and whose certificate is
// interrupted (status undecided).  Then the same mesh is given to `check --certify` and
// interrupted 100 ms after its handler is installed (while the mesh is read or during the
// certificate: either way the certificate stops): exit code 3, the report on stdout with the
// certificate interrupted, one warning on stderr.
BOOST_AUTO_TEST_CASE(a_signal_stops_a_certificate_with_nothing_lost) {
  TempDir scratch;
  write_text(scratch / "torus.off", "previous contents\n");
  int status = run_and_signal({"mesh", "--surface", "torus", "--size-bound", "0.05", "--threads", "1", "--certify"},
                              scratch.path, SIGINT, std::chrono::milliseconds(100), "certifying the mesh");
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 3);
  const auto stats = nlohmann::json::parse(read_text(scratch / "torus.json"));
  BOOST_TEST(stats["status"] == "interrupted");
  BOOST_TEST(stats["run_status"] == "complete");
  BOOST_TEST(stats["certificate"]["interrupted"] == true);
  BOOST_TEST(stats["certificate"]["status"] == "undecided");
  const TriangleSoup soup = read_triangle_soup((scratch / "torus.off").string());
  BOOST_TEST(soup.points.size() == stats["vertices"].get<std::size_t>());
  BOOST_TEST(soup.triangles.size() == stats["triangles"].get<std::size_t>());
  BOOST_TEST(read_text(scratch / "stderr.txt").find("interrupted by a signal during the certificate") != std::string::npos);

  status = run_and_signal({"check", "torus.off", "--surface", "torus", "--certify", "--json"}, scratch.path, SIGTERM,
                          std::chrono::milliseconds(100));
  BOOST_TEST_REQUIRE(WIFEXITED(status));
  BOOST_TEST(WEXITSTATUS(status) == 3);
  const auto report = nlohmann::json::parse(read_text(scratch / "stdout.txt"));
  BOOST_TEST(report["certificate"]["interrupted"] == true);
  BOOST_TEST(report["certificate"]["status"] == "undecided");
  BOOST_TEST(report["vertices"].get<std::size_t>() == soup.points.size());
  const std::string err = read_text(scratch / "stderr.txt");
  BOOST_TEST(err.find("interrupted by a signal") != std::string::npos, err);
  BOOST_TEST(std::count(err.begin(), err.end(), '\n') == 1, err);
}

BOOST_AUTO_TEST_SUITE_END()

namespace {

// After a run that got signals: no temporary file is left in `directory`, and each of its
// outputs m.off and m.json is either untouched (still `old`) or replaced by a whole file, the
// two of one run.
void check_outputs(const std::filesystem::path& directory, const std::string& old) {
  BOOST_TEST(temporaries_in(directory).empty());
  const std::string mesh = read_text(directory / "m.off"), stats = read_text(directory / "m.json");
  BOOST_TEST((mesh == old) == (stats == old), "one output replaced, the other not");
  if (mesh == old || stats == old) return;
  const auto statistics = nlohmann::json::parse(stats);
  // The counts of the OFF header (a partial mesh may have no triangles, which the readers refuse).
  std::istringstream off(mesh);
  std::string magic;
  std::size_t vertices = 0, triangles = 0;
  off >> magic >> vertices >> triangles;
  BOOST_TEST(magic == "OFF");
  BOOST_TEST(vertices == statistics.at("vertices").get<std::size_t>());
  BOOST_TEST(triangles == statistics.at("triangles").get<std::size_t>());
}

// The torus with a small size bound: a run of about 10^5 vertices and 15 s of CPU time, so the
// signals of the tests below (at most 120 ms after the handler is installed) reach it while it
// meshes even when a loaded machine keeps the test waiting, and stop it early.
const std::vector<std::string> torus_run{"mesh",  "--surface", "torus", "--size-bound", "0.01", "--quiet",
                                         "--out", "m.off",     "--stats", "m.json"};

}  // namespace

BOOST_AUTO_TEST_SUITE(signals)

// Each handled signal, sent once the refinement runs (its first progress line, with the handler
// installed and the process still running), stops it like a limit: exit code 3, status
// interrupted, the partial mesh and its statistics written.  The whole run (about 10^5 vertices,
// some 15 s of CPU time) is far longer than the half second before its first progress line, so it
// cannot end between that line and the signal.
BOOST_AUTO_TEST_CASE(every_handled_signal_stops_a_run) {
  for (const int signal : {SIGINT, SIGTERM, SIGHUP, SIGQUIT, SIGXCPU, SIGUSR1, SIGUSR2, SIGALRM}) {
    BOOST_TEST_CONTEXT("signal " << signal) {
      TempDir dir;
      const int status = run_and_signal(
          {"mesh", "--surface", "torus", "--size-bound", "0.01", "--out", "m.off", "--stats", "m.json"}, dir.path,
          signal, std::chrono::milliseconds(0), "delmesh: meshing");
      BOOST_TEST_REQUIRE(WIFEXITED(status));
      BOOST_TEST(WEXITSTATUS(status) == 3, read_text(dir / "stderr.txt"));
      BOOST_TEST(nlohmann::json::parse(read_text(dir / "m.json"))["status"] == "interrupted");
      check_outputs(dir.path, "");
    }
  }
}

// The partial meshes a signal can leave early in a run, where Surface_mesh refuses some of the
// restricted triangles (statistics: faces_not_added): the OFF file and the statistics count the
// same vertices and triangles (at 5 points a vertex keeps no triangle of its own).
BOOST_AUTO_TEST_CASE(an_early_partial_mesh_matches_its_statistics) {
  for (const std::string points : {"5", "9", "17"}) {
    BOOST_TEST_CONTEXT("--max-points " << points) {
      TempDir dir;
      write_text(dir / "m.off", "old\n");
      write_text(dir / "m.json", "old\n");
      const RunResult r = run_delmesh({"mesh", "--surface", "torus", "--quiet", "--max-points", points, "--out", "m.off",
                                       "--stats", "m.json"},
                                      dir.path);
      BOOST_TEST(r.exit_code == 3, r.err);
      BOOST_TEST(nlohmann::json::parse(read_text(dir / "m.json")).at("faces_not_added").get<std::size_t>() > 0u);
      check_outputs(dir.path, "old\n");
    }
  }
}

// SIGINT and SIGTERM at 0 to 50 ms after the handler is installed (the earliest moment a program
// can answer a signal), to every subcommand: never death by a signal; a command that ran when
// the signal came exits with 3 (mesh: always, it runs for longer), the fast ones may have ended
// with 0 before it; no temporary file is left, and the outputs of mesh are untouched or whole.
BOOST_AUTO_TEST_CASE(signals_at_any_moment_never_kill) {
  TempDir dir;
  write_text(dir / "oct.off", octahedron_off);
  const std::string old = "old\n";
  const std::vector<std::vector<std::string>> commands{
      {"surfaces"},
      {"surfaces", "--json"},
      {"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction", "0,0,1"},
      {"check", "oct.off", "--json"},
      torus_run,
  };
  for (const auto& args : commands) {
    const bool mesh = args[0] == "mesh";
    for (const int signal : {SIGINT, SIGTERM}) {
      for (const int delay_ms : {0, 1, 2, 5, 10, 20, 50}) {
        BOOST_TEST_CONTEXT(args[0] << " " << (args.size() > 1 ? args[1] : "") << ", signal " << signal << " after "
                                   << delay_ms << " ms") {
          write_text(dir / "m.off", old);
          write_text(dir / "m.json", old);
          const pid_t pid = spawn_delmesh(args, dir.path);
          if (!wait_for_handler(pid, signal)) {
            // The command ended before the loop saw its handler: it must have succeeded.
            const RunResult r = wait_delmesh(pid, dir.path);
            BOOST_TEST(!mesh);
            BOOST_TEST(r.exit_code == 0, r.err);
            continue;
          }
          std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
          ::kill(pid, signal);
          const RunResult r = wait_delmesh(pid, dir.path);
          BOOST_TEST(!r.signalled);
          if (mesh) {
            BOOST_TEST(r.exit_code == 3, r.err);
          } else {
            BOOST_TEST((r.exit_code == 0 || r.exit_code == 3), "exit code " << r.exit_code << ": " << r.err);
            if (r.exit_code == 3) {
              BOOST_TEST(r.err_lines().size() == 1u, r.err);
              BOOST_TEST(r.err.find("interrupted by") != std::string::npos, r.err);
            }
          }
          check_outputs(dir.path, old);
        }
      }
    }
  }
}

// Signals during the write: the statistics go to a FIFO, so the run has written its temporary
// mesh file and waits for a reader; nothing is replaced yet.  One SIGINT there lets the run finish
// once the FIFO is read (exit code 3, both outputs of the run); a second SIGINT ends it at once
// with exit code 3, the temporary file removed and the old mesh untouched.
BOOST_AUTO_TEST_CASE(signals_during_the_write) {
  for (const int signals : {1, 2}) {
    BOOST_TEST_CONTEXT(signals << " SIGINT") {
      TempDir dir;
      write_text(dir / "m.off", "old\n");
      BOOST_TEST_REQUIRE(::mkfifo((dir / "m.json").c_str(), 0644) == 0);
      const pid_t pid = spawn_delmesh({"mesh", "--surface", "sphere", "--out", "m.off", "--stats", "m.json"}, dir.path);
      const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
      while (temporaries_in(dir.path).empty() && std::chrono::steady_clock::now() < give_up)
        std::this_thread::sleep_for(std::chrono::microseconds(200));
      BOOST_TEST_REQUIRE(temporaries_in(dir.path).size() == 1u);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      for (int i = 0; i < signals; ++i) {
        ::kill(pid, SIGINT);
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
      }
      std::string statistics;
      if (signals == 1) {
        const int fd = ::open((dir / "m.json").c_str(), O_RDONLY);
        char buffer[4096];
        for (ssize_t n; (n = ::read(fd, buffer, sizeof buffer)) > 0;) statistics.append(buffer, static_cast<std::size_t>(n));
        ::close(fd);
      }
      const RunResult r = wait_delmesh(pid, dir.path);
      BOOST_TEST(!r.signalled);
      BOOST_TEST(r.exit_code == 3, r.err);
      BOOST_TEST(temporaries_in(dir.path).empty());
      if (signals == 1) {
        const TriangleSoup soup = read_triangle_soup((dir / "m.off").string());
        BOOST_TEST(soup.points.size() == nlohmann::json::parse(statistics).at("vertices").get<std::size_t>());
        BOOST_TEST(r.err.find("interrupted by SIGINT") != std::string::npos, r.err);
      } else {
        BOOST_TEST(read_text(dir / "m.off") == "old\n");
        BOOST_TEST(r.err.find("second signal") != std::string::npos, r.err);
      }
    }
  }
}

// Two signals in a row at several moments of a meshing run (the second 0 to 20 ms after the
// first, so some arrive while the outputs are written): exit code 3, never death by a signal, no
// temporary file left, each output untouched or whole.
BOOST_AUTO_TEST_CASE(a_second_signal_ends_the_run_cleanly) {
  for (const int first_ms : {0, 20, 100}) {
    for (const int gap_ms : {0, 1, 5, 20}) {
      BOOST_TEST_CONTEXT("first after " << first_ms << " ms, second " << gap_ms << " ms later") {
        TempDir dir;
        write_text(dir / "m.off", "old\n");
        write_text(dir / "m.json", "old\n");
        const pid_t pid = spawn_delmesh(torus_run, dir.path);
        BOOST_TEST_REQUIRE(wait_for_handler(pid, SIGINT));
        std::this_thread::sleep_for(std::chrono::milliseconds(first_ms));
        ::kill(pid, SIGINT);
        std::this_thread::sleep_for(std::chrono::milliseconds(gap_ms));
        ::kill(pid, SIGTERM);
        const RunResult r = wait_delmesh(pid, dir.path);
        BOOST_TEST(!r.signalled);
        BOOST_TEST(r.exit_code == 3, r.err);
        check_outputs(dir.path, "old\n");
      }
    }
  }
}

BOOST_AUTO_TEST_SUITE_END()
