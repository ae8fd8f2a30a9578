#include "common/enum_names.h"

#include <sstream>

#include <boost/test/unit_test.hpp>

namespace enum_names_test {

enum class Mode { fast, exact, careful };
constexpr auto enum_names(Mode) {
  return delmesh::name_table<Mode>("Mode", {{Mode::fast, "fast"}, {Mode::exact, "exact"}, {Mode::careful, "careful"}});
}
inline std::ostream& operator<<(std::ostream& out, Mode mode) { return delmesh::write_enum(out, mode); }

enum class Pair { first = 3, second = 7 };
constexpr auto enum_names(Pair) { return delmesh::name_table<Pair>("Pair", {{Pair::first, "first"}, {Pair::second, "second"}}); }

template <class T>
std::string text_of(T value) {
  std::ostringstream s;
  s << value;
  return s.str();
}

}  // namespace enum_names_test

using namespace delmesh;
using enum_names_test::Mode;
using enum_names_test::Pair;

BOOST_AUTO_TEST_SUITE(enum_names)

BOOST_AUTO_TEST_CASE(names_print_and_parse_back) {
  for (Mode mode : {Mode::fast, Mode::exact, Mode::careful}) {
    const std::string name = enum_names_test::text_of(mode);
    BOOST_TEST(name == enum_name(mode));
    BOOST_TEST((find_enum<Mode>(name) == mode));
    BOOST_TEST((parse_enum<Mode>(name, "--mode") == mode));
  }
  BOOST_TEST(enum_names_test::text_of(Mode::exact) == "exact");
  BOOST_TEST((find_enum<Pair>("second") == Pair::second));  // enumerators need not be 0, 1, ...
  BOOST_TEST(std::string(enum_name(Pair::first)) == "first");
}

BOOST_AUTO_TEST_CASE(a_value_outside_the_table_prints_type_and_number) {
  BOOST_TEST(enum_names_test::text_of(static_cast<Mode>(9)) == "Mode(9)");
  BOOST_TEST(!enum_name(static_cast<Mode>(9)));
}

BOOST_AUTO_TEST_CASE(unknown_names_are_refused_with_the_choices) {
  BOOST_TEST(!find_enum<Mode>("Fast").has_value());  // exact match only
  BOOST_TEST(!find_enum<Mode>("").has_value());
  BOOST_TEST(enum_choices<Mode>() == "fast, exact or careful");
  BOOST_TEST(enum_choices<Pair>() == "first or second");
  try {
    (void)parse_enum<Mode>("slow", "--mode");
    BOOST_FAIL("parse_enum accepted 'slow'");
  } catch (const InvalidInput& e) {
    BOOST_TEST(std::string(e.what()) == "--mode: expected fast, exact or careful, got 'slow'");
  }
}

BOOST_AUTO_TEST_CASE(name_map_holds_every_name) {
  const auto map = enum_name_map<Mode>();
  BOOST_TEST(map.size() == 3u);
  BOOST_TEST((map.at("careful") == Mode::careful));
}

BOOST_AUTO_TEST_CASE(a_table_with_a_repeated_name_is_refused) {
  // At compile time the same call does not compile; at run time it throws.
  const EnumName<Mode> names[] = {{Mode::fast, "fast"}, {Mode::exact, "fast"}};
  BOOST_CHECK_THROW(name_table<Mode>("Mode", names), PreconditionViolation);
  const EnumName<Mode> values[] = {{Mode::fast, "fast"}, {Mode::fast, "quick"}};
  BOOST_CHECK_THROW(name_table<Mode>("Mode", values), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
