// The number parsing and the messages of apps/command_line.h, through the built program: numbers
// at the ends of double precision, and control characters in user text.
#include <string>

#include <boost/test/unit_test.hpp>

#include "tests/apps/run_delmesh.h"

using namespace delmesh::test;

BOOST_AUTO_TEST_SUITE(command_line)

// A subnormal box coordinate is finite; it is refused because a nonzero box coordinate must be a
// normal double, and the message says so.  One that overflows says that.
BOOST_AUTO_TEST_CASE(box_coordinates_at_the_ends_of_double) {
  const RunResult subnormal = run_delmesh({"mesh", "--expr", "x^2+y^2+z^2-1", "--box", "-2,2,-2,2,0,5e-324"});
  require_invalid_input(subnormal, "field 6 \"5e-324\" is too small: a nonzero box coordinate must be at least "
                                   "2.2250738585072014e-308 in magnitude");
  BOOST_TEST(subnormal.err.find("not a finite number") == std::string::npos, subnormal.err);
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2+z^2-1", "--box", "-2,2,-2,2,0,1e-400"}),
                        "field 6 \"1e-400\" is too small");
  require_invalid_input(run_delmesh({"mesh", "--expr", "x^2+y^2+z^2-1", "--box", "-2,2,-2,2,0,1e400"}),
                        "field 6 \"1e400\" is not a finite number: it overflows double precision");
}

// A real option whose text underflows to 0 says so and echoes the text (not "got 0").
BOOST_AUTO_TEST_CASE(lambda_that_underflows) {
  const RunResult r = run_delmesh({"mesh", "--surface", "sphere", "--lambda", "1e-400"});
  require_invalid_input(r, "--lambda: '1e-400' underflows double precision");
  BOOST_TEST(r.err.find("got 0") == std::string::npos, r.err);
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--lambda", "1e400"}),
                        "--lambda: expected a finite number, got '1e400' (it overflows double precision");
}

// Directions whose squared length overflows or underflows are directions all the same: solve
// takes their unit vector, printed in shortest form.
BOOST_AUTO_TEST_CASE(directions_of_extreme_length) {
  const RunResult huge = run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction",
                                      "1e308,1e308,0"});
  BOOST_TEST(!huge.signalled);
  BOOST_TEST(huge.exit_code == 0, huge.err);
  BOOST_TEST(huge.out.find("direction 0.7071067811865475,0.7071067811865475,0") != std::string::npos, huge.out);
  BOOST_TEST(huge.out.find("roots:     2") != std::string::npos, huge.out);
  const RunResult tiny = run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction",
                                      "1e-320,0,0"});
  BOOST_TEST(tiny.exit_code == 0, tiny.err);
  BOOST_TEST(tiny.out.find("direction 1,0,0") != std::string::npos, tiny.out);
  const RunResult zero = run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction",
                                      "0,0,0"});
  require_invalid_input(zero, "direction (0, 0, 0) is zero");
  const RunResult under = run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction",
                                       "1e-400,0,0"});
  require_invalid_input(under, "--direction: '1e-400' underflows double precision");
  BOOST_TEST(under.err.find("expected three numbers") == std::string::npos, under.err);
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction",
                                     "1e400,0,0"}),
                        "--direction: expected a finite number, got '1e400' (it overflows double precision");
  require_invalid_input(run_delmesh({"solve", "--surface", "sphere", "--primitive", "surface_critical", "--direction",
                                     "1,2"}),
                        "--direction: expected three numbers \"a,b,c\", got \"1,2\"");
}

// Control characters of user text (ESC, BEL, DEL) reach stderr escaped as \xHH.
BOOST_AUTO_TEST_CASE(control_characters_are_escaped) {
  const RunResult r = run_delmesh({"mesh", "--expr", "x^2+\x1b[31my\x07\x7f", "--box", "-2,2,-2,2,-2,2"});
  require_invalid_input(r);
  for (char c = 0; c < 0x20; ++c)
    if (c != '\n') BOOST_TEST(r.err.find(c) == std::string::npos, "byte " << int(c) << " in " << r.err);
  BOOST_TEST(r.err.find('\x7f') == std::string::npos);
  BOOST_TEST(r.err.find("\\x1b[31m") != std::string::npos, r.err);
  require_invalid_input(run_delmesh({"mesh", "--surface", "sphere", "--lambda", "0.1\x1b"}), "got '0.1\\x1b'");
}

BOOST_AUTO_TEST_SUITE_END()
