#include "experiments/csv_writer.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <random>
#include <sstream>
#include <string>

#include <boost/test/unit_test.hpp>

#include "tests/temp_dir.h"

using namespace delmesh::experiments;

namespace {

std::string contents(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

BOOST_AUTO_TEST_SUITE(csv_writer_suite)

BOOST_AUTO_TEST_CASE(doubles_are_written_in_the_shortest_form_that_reads_back_exactly) {
  BOOST_TEST(field(0.06) == "0.06");  // not 0.059999999999999998
  BOOST_TEST(field(0.1 + 0.2) == "0.30000000000000004");
  BOOST_TEST(field(1.0) == "1");
  BOOST_TEST(field(-2.5e-12) == "-2.5e-12");
  BOOST_TEST(field(std::numeric_limits<double>::quiet_NaN()) == "nan");
  BOOST_TEST(field(-std::numeric_limits<double>::infinity()) == "-inf");
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> exponent(-30, 30), mantissa(-1, 1);
  for (int i = 0; i < 10000; ++i) {
    const double x = mantissa(random) * std::pow(10.0, exponent(random));
    const std::string text = field(x);
    BOOST_TEST_REQUIRE(std::strtod(text.c_str(), nullptr) == x, text);
    // No longer than the 17 significant digits that always round-trip.
    char longest[64];
    std::snprintf(longest, sizeof longest, "%.17g", x);
    BOOST_TEST_REQUIRE(text.size() <= std::strlen(longest), text << " against " << longest);
  }
}

BOOST_AUTO_TEST_CASE(the_csv_has_a_plain_header_and_the_metadata_is_a_json_file_beside_it) {
  delmesh::test::TempDir dir;
  const auto path = dir / "sub" / "runs.csv";
  {
    CsvWriter csv(path, "sweep", {{"lambdas", "0.06;0.05"}, {"seed", "3"}}, {"surface", "lambda"});
    csv.row({"sphere", field(0.06)});
    // Nothing under the final names before close().
    BOOST_TEST(!std::filesystem::exists(path));
    BOOST_TEST(!std::filesystem::exists(metadata_path(path)));
    BOOST_CHECK_THROW(csv.row({"sphere"}), std::logic_error);
    csv.row({"torus", field(0.05)});
  }
  BOOST_TEST(contents(path) == "surface,lambda\nsphere,0.06\ntorus,0.05\n");
  BOOST_TEST(metadata_path(path).string() == path.string() + ".json");
  const nlohmann::json meta = read_metadata(path);
  BOOST_TEST(meta["program"] == "sweep");
  BOOST_TEST(meta["git"].is_string());
  BOOST_TEST(meta["date"].get<std::string>().size() == std::string("2026-01-01T00:00:00Z").size());
  BOOST_TEST(meta["parameters"] == nlohmann::json({{"lambdas", "0.06;0.05"}, {"seed", "3"}}));
  // The parameters keep the order they were given in.
  const std::string text = contents(metadata_path(path));
  BOOST_TEST(text.find("\"lambdas\"") < text.find("\"seed\""));
  BOOST_TEST(!std::filesystem::exists(path.string() + ".partial"));
}

BOOST_AUTO_TEST_CASE(reading_missing_or_malformed_metadata_throws) {
  delmesh::test::TempDir dir;
  BOOST_CHECK_THROW(read_metadata(dir / "none.csv"), std::runtime_error);
  dir.write("bad.csv.json", "[1, 2");
  BOOST_CHECK_THROW(read_metadata(dir / "bad.csv"), std::runtime_error);
}

BOOST_AUTO_TEST_SUITE_END()
