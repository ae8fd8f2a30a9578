// Tests of apps/interrupt.h: SIGINT and SIGTERM stop `delmesh mesh` like a limit, and stop the
// certificate of `delmesh check --certify` and `delmesh mesh --certify` with nothing lost.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>
#include <nlohmann/json.hpp>

#include "meshing/mesh_io.h"
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
