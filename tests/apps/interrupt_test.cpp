// Tests of apps/interrupt.h: SIGINT and SIGTERM stop `delmesh mesh` like a limit.
#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
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

// Starts `delmesh args...` in `directory` (stdout and stderr to /dev/null), sends `signal` after
// `delay`, and returns the exit status of waitpid.
int run_and_signal(const std::vector<std::string>& args, const std::filesystem::path& directory, int signal,
                   std::chrono::milliseconds delay) {
  std::vector<std::string> argv_text{DELMESH_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(directory.c_str()) != 0) ::_exit(127);
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  std::this_thread::sleep_for(delay);
  ::kill(pid, signal);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

// A run long enough to be interrupted (about 10^5 samples), stopped by `signal`: exit code 3,
// status interrupted, and both files written completely — the mesh that stood in the output's
// place before is replaced by a partial mesh that matches the statistics.
void check_interrupted_by(int signal) {
  ScratchDirectory scratch;
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

BOOST_AUTO_TEST_SUITE_END()
