// Every bad input gets exit code 2, one `error:` line naming the problem in the user's terms, and
// leaves existing output files untouched; the program never dies by a signal.  One case per row
// of the table of bad inputs in docs/cli.md.
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

namespace {

//! `delmesh mesh --surface sphere EXTRA... --out keep.off --stats keep.json --quiet` must fail with
//! exit 2 and `mention`, and leave the two existing files as they were.
void require_mesh_refused(const std::vector<std::string>& extra, const std::string& mention) {
  TempDir dir;
  write_text(dir / "keep.off", "old mesh");
  write_text(dir / "keep.json", "old statistics");
  std::vector<std::string> args{"mesh"};
  bool has_surface = false;
  for (const std::string& a : extra) has_surface = has_surface || a == "--expr" || a == "--surface";
  if (!has_surface) args.insert(args.end(), {"--surface", "sphere"});
  args.insert(args.end(), extra.begin(), extra.end());
  args.insert(args.end(), {"--out", "keep.off", "--stats", "keep.json", "--quiet"});
  BOOST_TEST_CONTEXT("mesh " << [&] {
    std::string s;
    for (const auto& a : extra) s += (a.size() > 40 ? a.substr(0, 40) + "..." : a) + " ";
    return s;
  }()) {
    require_invalid_input(run_delmesh(args, dir.path), mention);
    BOOST_TEST(read_text(dir / "keep.off") == "old mesh");
    BOOST_TEST(read_text(dir / "keep.json") == "old statistics");
  }
}

std::string nested(std::size_t depth) {
  return std::string(depth, '(') + "x" + std::string(depth, ')') + "^2+y^2+z^2-1";
}

}  // namespace

BOOST_AUTO_TEST_SUITE(bad_input)

// Numbers: negative, huge, fractional, NaN, infinite, overflowing; CLI11 used to wrap -5 to a huge
// unsigned count and accept it.
BOOST_AUTO_TEST_CASE(numeric_options_are_range_checked) {
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--max-points", "-5"}, "--max-points: expected a whole number from 1 to 1000000000, got '-5'"},
      {{"--max-points", "0"}, "--max-points: expected a whole number"},
      {{"--max-points", "1.5"}, "--max-points: expected a whole number"},
      {{"--max-points", "1e30"}, "--max-points: expected a whole number"},
      {{"--max-points", "99999999999999999999999"}, "--max-points: expected a whole number"},
      {{"--seed", "-1"}, "--seed: expected a whole number from 0 to 18446744073709551615"},
      {{"--seed", "18446744073709551616"}, "--seed: expected a whole number"},
      {{"--threads", "-1"}, "--threads: expected a whole number from 0 to 1024"},
      {{"--threads", "100000"}, "--threads: expected a whole number from 0 to 1024"},
      {{"--lambda", "nan"}, "--lambda: expected a finite number, got 'nan'"},
      {{"--lambda", "1e400"}, "--lambda: expected a finite number"},
      {{"--lambda", "-0.1"}, "--lambda must satisfy 0 < lambda < 1/3"},
      {{"--time-limit", "inf"}, "--time-limit: expected a finite number"},
      {{"--time-limit", "-1"}, "--time-limit must be >= 0 and <= 1e9 seconds"},
      {{"--time-limit", "1e308"}, "--time-limit must be >= 0 and <= 1e9 seconds"},
      {{"--size-bound", "-1"}, "--size-bound must be a positive length"},
      {{"--size-bound", "nan"}, "--size-bound: expected a finite number"},
  };
  for (const auto& [extra, mention] : cases) require_mesh_refused(extra, mention);

  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--max-boxes", "-1"}),
                        "--max-boxes: expected a whole number from 1 to 1000000000");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--time-limit", "1e300"}),
                        "--time-limit must be >= 0 and <= 1e9 seconds");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_line", "--point", "0,0,nan",
                                     "--direction", "0,0,1"}),
                        "--point");
  TempDir dir;
  write_text(dir / "octahedron.off", octahedron_off);
  require_invalid_input(run_delmesh({"check", "octahedron.off", "--lambda", "nan"}, dir.path), "--lambda: expected a finite number");
}

// The run's options are checked (DelMeshOptions::validate(), named by flag) before an input mesh
// is read: a missing file with a bad option is refused for the option.
BOOST_AUTO_TEST_CASE(options_are_checked_before_the_input_mesh_is_read) {
  TempDir dir;
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--lambda", "0.5"}, "--lambda must satisfy 0 < lambda < 1/3, got 0.5"},
      {{"--min-spacing", "-1"}, "--min-spacing must be a length >= 0 (0: no floor), got -1"},
      {{"--time-limit", "2e9"}, "--time-limit must be >= 0 and <= 1e9 seconds (0: none), got 2e+09"},
  };
  for (const auto& [extra, message] : cases) {
    std::vector<std::string> args{"mesh", "--input-mesh", "missing.off", "--quiet"};
    args.insert(args.end(), extra.begin(), extra.end());
    require_invalid_input(run_delmesh(args, dir.path), message);
  }
  require_invalid_input(run_delmesh({"mesh", "--input-mesh", "missing.off", "--quiet"}, dir.path), "missing.off");
}

// Expressions: depth (20 000 nested parentheses used to overflow the stack: SIGSEGV), length,
// degree, expanded size, division by zero; the box: overflow.
BOOST_AUTO_TEST_CASE(expressions_and_boxes_beyond_the_limits) {
  const std::string box = "-2,2,-2,2,-2,2";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--expr", nested(20000), "--box", box}, "expression too long: 40013 characters (at most 10000)"},
      {{"--expr", nested(201), "--box", box}, "parentheses nested more than 200 deep"},
      {{"--expr", "x^100000+y", "--box", box}, "too large (at most 1000)"},
      {{"--expr", "x^300+y^2+z^2-1", "--box", box}, "has degree up to 300 in x, y, z (at most 200)"},
      {{"--expr", "(x^2+y^2+z^2+1)^100-2", "--box", box}, "may have more than 200000 terms"},
      {{"--expr", "x^2+y^2+z^2-1+1/(y-y)", "--box", box}, "division by zero"},
      {{"--expr", "x^2+y^2+z^2-1", "--box", "-1e308,1e308,-2,2,-2,2"}, "too large: the width x1 - x0 overflows"},
      {{"--expr", "x^2+y^2+z^2-1", "--box", "-1e200,1e200,-2,2,-2,2"}, "too large: the square of its diagonal overflows"},
      {{"--expr", "x^2+y^2+z^2-1", "--box", "0,1,0,1,0,nan"}, "is not a finite number"},
      {{"--expr", "x^2+y^2+z^2-1", "--box", "1,0,0,1,0,1"}, "empty range for x"},
  };
  for (const auto& [extra, mention] : cases) require_mesh_refused(extra, mention);
  // The deepest nesting allowed is parsed (and meshed: it is the unit sphere).
  const RunResult r = run_delmesh({"solve", "--expr", nested(200), "--box", "-2,2,-2,2,-2,2", "--primitive", "surface_critical"});
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("roots:     2") != std::string::npos, r.out);
}

// Expressions: a function that is not C² gets the one `error:` line with the smooth blend to use;
// ** is the power operator, as in sympy's str() output.
BOOST_AUTO_TEST_CASE(non_smooth_functions_and_python_powers) {
  const std::string box = "-2,2,-2,2,-2,2";
  const std::vector<std::pair<std::vector<std::string>, std::string>> cases = {
      {{"--expr", "abs(x)+y^2+z^2-1", "--box", box},
       "error: abs at position 1 of \"abs(x)+y^2+z^2-1\" is not smooth: E must be C² (use a smooth blend, e.g. "
       "sqrt(x^2+c^2) for |x|, with a small c > 0)"},
      {{"--expr", "max(x^2, y^2)+z^2-1", "--box", box}, "error: max at position 1"},
      {{"--expr", "x***2+y**2+z**2-1", "--box", box}, "expected an integer exponent after '**', got '*'"},
  };
  for (const auto& [extra, mention] : cases) require_mesh_refused(extra, mention);
  const RunResult r = run_delmesh({"solve", "--expr", "x**2 + y**2 + z**2 - 1", "--box", box, "--primitive", "surface_critical"});
  BOOST_TEST(r.exit_code == 0, r.err);
  BOOST_TEST(r.out.find("roots:     2") != std::string::npos, r.out);
}

// Paths: a directory as --out or --stats, a missing folder, an unknown extension.
BOOST_AUTO_TEST_CASE(output_paths) {
  TempDir dir;
  std::filesystem::create_directory(dir / "folder.off");
  write_text(dir / "keep.json", "old statistics");
  require_invalid_input(
      run_delmesh({"mesh", "--surface", "sphere", "--out", "folder.off", "--stats", "keep.json", "--quiet"}, dir.path),
      "--out: folder.off is a directory");
  require_invalid_input(
      run_delmesh({"mesh", "--surface", "sphere", "--out", "m.off", "--stats", "folder.off", "--quiet"}, dir.path),
      "--stats: folder.off is a directory");
  require_invalid_input(
      run_delmesh({"mesh", "--surface", "sphere", "--out", "m.off", "--stats", "missing/s.json", "--quiet"}, dir.path),
      "--stats: directory missing does not exist");
  require_invalid_input(
      run_delmesh({"mesh", "--surface", "sphere", "--out", "missing/m.off", "--stats", "keep.json", "--quiet"}, dir.path),
      "--out: directory missing does not exist");
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--out", "m.stp", "--quiet"}, dir.path),
                        "--out: the extension must be .off, .ply, .obj, .stl or .vtp, got 'm.stp'");
  BOOST_TEST(read_text(dir / "keep.json") == "old statistics");
  BOOST_TEST(!std::filesystem::exists(dir / "m.off"));
  BOOST_TEST(!std::filesystem::exists(dir / "m.stp"));
}

// Mesh files given to `delmesh check`: each corrupt file gets one line saying what is wrong.
BOOST_AUTO_TEST_CASE(corrupt_mesh_files) {
  TempDir dir;
  const std::string ply_header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  std::string ply = ply_header;
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  ply.append(reinterpret_cast<const char*>(v), sizeof v);
  const int face[3] = {0, 1, 2};
  ply += '\3';
  ply.append(reinterpret_cast<const char*>(face), sizeof face);
  std::string negative_ply = ply;
  const int minus_one = -1;
  negative_ply.replace(negative_ply.size() - 4, 4, reinterpret_cast<const char*>(&minus_one), 4);
  write_text(dir / "good.ply", ply);
  write_text(dir / "truncated.ply", ply.substr(0, ply.size() - 6));
  write_text(dir / "negative.ply", negative_ply);
  std::string huge_ply = ply;
  huge_ply.replace(huge_ply.find("face 1"), 6, "face 4000000000");
  write_text(dir / "huge.ply", huge_ply);
  write_text(dir / "range.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  write_text(dir / "negative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -1 -2 -4\n");
  write_text(dir / "relative.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf -3 -2 -1\n");  // valid
  write_text(dir / "no_faces.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  write_text(dir / "no_faces.off", "OFF\n3 0 0\n0 0 0\n1 0 0\n0 1 0\n");
  write_text(dir / "quad.off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n4 0 1 2 3\n");
  write_text(dir / "quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n");
  write_text(dir / "huge.off", "OFF\n3 99999999999999999999 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  write_text(dir / "negative_count.off", "OFF\n-3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  write_text(dir / "negative.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 -1\n");
  write_text(dir / "truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1\n");
  write_text(dir / "word.off", "OFF\n3 1 0\n0 0 0\n1 0 zz\n0 1 0\n3 0 1 2\n");
  write_text(dir / "nan.off", "OFF\n3 1 0\n0 0 0\n1 0 nan\n0 1 0\n3 0 1 2\n");
  write_text(dir / "empty.off", "");
  write_text(dir / "binary.off", std::string("\x01\x02\x03\xff\xfe", 5));
  // Binary STL: 80-byte header, count, 50 bytes per triangle.
  std::string stl(80, ' ');
  const std::uint32_t one = 1;
  stl.append(reinterpret_cast<const char*>(&one), 4);
  const float normal[3] = {0, 0, 1};
  stl.append(reinterpret_cast<const char*>(normal), sizeof normal);
  stl.append(reinterpret_cast<const char*>(v), sizeof v);
  stl.append(2, '\0');
  write_text(dir / "good.stl", stl);
  write_text(dir / "truncated.stl", stl.substr(0, stl.size() - 1));
  std::string nan_stl = stl;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  nan_stl.replace(84 + 12 + 16, 4, reinterpret_cast<const char*>(&nan), 4);
  write_text(dir / "nan.stl", nan_stl);
  std::string huge_stl = stl.substr(0, 84);
  const std::uint32_t huge_count = 0xffffffffu;
  huge_stl.replace(80, 4, reinterpret_cast<const char*>(&huge_count), 4);
  write_text(dir / "huge.stl", huge_stl);
  write_text(dir / "ascii.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
                                "endloop\nendfacet\nendsolid a\n");
  write_text(dir / "cut.stl", "solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0\n");
  std::filesystem::create_directory(dir / "folder.off");
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"truncated.ply", "'truncated.ply': truncated: the file ends in face 0 of the 1 declared"},
      {"negative.ply", "face 0 refers to vertex -1, but the file has 3 vertices (numbered 0 to 2)"},
      {"huge.ply", "declares 4000000000 elements but the file has only"},
      {"range.obj", "refers to vertex 4, but the file has 3 vertices (numbered 1 to 3)"},
      {"negative.obj", "line 4: a face refers to vertex -4, but 3 vertices are defined before it"},
      {"no_faces.obj", "has no faces"},
      {"no_faces.off", "has no faces"},
      {"huge.off", "face count '99999999999999999999' is not a whole number"},
      {"negative_count.off", "the header declares a negative vertex count (-3)"},
      {"negative.off", "face 0 refers to vertex -1, but the file has 3 vertices (numbered 0 to 2)"},
      {"truncated.off", "truncated: the file ends in vertex 2 of the 3 declared"},
      {"word.off", "vertex 1: 'zz' is not a number"},
      {"nan.off", "vertex 1 has a non-finite coordinate"},
      {"empty.off", "'empty.off': is empty"},
      {"binary.off", "vertex count '?????' is not a whole number"},
      {"folder.off", "is a directory, not a mesh file"},
      {"missing.off", "'missing.off': no such file"},
      {"good.txt", "unknown extension '.txt'"},
      {"good.vtp", "unknown extension '.vtp' (expected .off, .ply, .obj or .stl; .vtp files are written, not read)"},
      {"truncated.stl", "binary STL: its 84-byte header declares 1 triangles, which take 84 + 50 x 1 = 134 bytes, but "
                        "the file has 133 bytes (truncated, or a corrupt count)"},
      {"huge.stl", "declares 4294967295 triangles, which take 84 + 50 x 4294967295 = 214748364834 bytes, but the "
                   "file has 84"},
      {"nan.stl", "'nan.stl': triangle 0 has a non-finite coordinate"},
      {"cut.stl", "'cut.stl': truncated: the file ends in facet 0's vertex 1"},
  };
  for (const auto& [file, mention] : cases)
    BOOST_TEST_CONTEXT(file) { require_invalid_input(run_delmesh({"check", file, "--json"}, dir.path), mention); }
  // A quadrilateral is triangulated, as by `mesh --input-mesh`.
  for (const char* file : {"good.ply", "relative.obj", "quad.off", "quad.obj", "good.stl", "ascii.stl"})
    BOOST_TEST_CONTEXT(file) { BOOST_TEST(run_delmesh({"check", file}, dir.path).exit_code == 0); }
}

// Every mesh file that crashed a reader under the fuzzer (fuzz/crashes/fuzz_read_*/: overflowing
// colours, negative or huge counts cast to sizes, a property before its element, list sizes that
// allocated gigabytes) gets exit code 2 and one error line from `delmesh check`.
BOOST_AUTO_TEST_CASE(fuzzer_crash_inputs_get_one_error_line) {
  TempDir dir;
  std::size_t files = 0;
  for (const char* target : {"fuzz_read_off", "fuzz_read_ply", "fuzz_read_obj", "fuzz_read_stl"}) {
    const std::filesystem::path crashes = std::filesystem::path(DELMESH_SOURCE_DIR) / "fuzz" / "crashes" / target;
    if (!std::filesystem::is_directory(crashes)) continue;
    for (const auto& entry : std::filesystem::directory_iterator(crashes)) {
      const std::string name = entry.path().filename().string();
      std::filesystem::copy_file(entry.path(), dir / name);
      BOOST_TEST_CONTEXT(target << "/" << name) {
        require_invalid_input(run_delmesh({"check", name, "--json"}, dir.path), "mesh file '" + name + "'");
      }
      ++files;
    }
  }
  BOOST_TEST(files >= 11u);
}

BOOST_AUTO_TEST_SUITE_END()
