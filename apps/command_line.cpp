#include "apps/command_line.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <sstream>

#include "common/errors.h"
#include "symbolic/catalog.h"

namespace delmesh::app {

namespace {

std::string trim(const std::string& s) {
  const auto first = s.find_first_not_of(" \t");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t");
  return s.substr(first, last - first + 1);
}

//! How the whole of a text reads as a double.
struct NumberReading {
  enum Kind { number, not_a_number, not_finite, overflows, underflows } kind = not_a_number;
  double value = 0;
};

//! Reads the whole of `text` (no surrounding spaces) as a double: a finite number (subnormal
//! numbers included), text that is not a number, nan or inf, a number whose magnitude exceeds
//! the largest double (overflows), or a nonzero number below the smallest subnormal double that
//! would read as 0 (underflows).
NumberReading read_number(const std::string& text) {
  NumberReading r;
  if (text.empty() || std::isspace(static_cast<unsigned char>(text.front()))) return r;
  const char* begin = text.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (end != begin + text.size()) return r;
  r.value = value;
  const bool range_error = errno == ERANGE;
  if (std::isnan(value)) {
    r.kind = NumberReading::not_finite;
  } else if (std::isinf(value)) {
    r.kind = range_error ? NumberReading::overflows : NumberReading::not_finite;
  } else if (range_error && value == 0) {
    r.kind = NumberReading::underflows;
  } else {
    r.kind = NumberReading::number;  // a subnormal result also sets ERANGE: it is a number
  }
  return r;
}

//! Why `text`, read as r, is not a finite double: "expected a finite number, got 'TEXT'" (with
//! the reason for an overflow), or that it underflows.
std::string number_problem(const std::string& text, const NumberReading& r) {
  const std::string quoted = "'" + printable(text) + "'";
  if (r.kind == NumberReading::underflows)
    return quoted + " underflows double precision: it is nonzero, but its magnitude is below the smallest "
                    "positive double 4.9406564584124654e-324, so it would read as 0";
  std::string message = "expected a finite number, got " + quoted;
  if (r.kind == NumberReading::overflows)
    message += " (it overflows double precision: its magnitude exceeds 1.7976931348623157e308)";
  return message;
}

//! The whole of `text` as a finite double, if it is one.
std::optional<double> finite_value(const std::string& text) {
  const NumberReading r = read_number(text);
  if (r.kind != NumberReading::number) return std::nullopt;
  return r.value;
}

}  // namespace

CLI::Validator whole_number(unsigned long long min, unsigned long long max) {
  const std::string range = "expected a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  return CLI::Validator(
      [min, max, range](std::string& text) -> std::string {
        const std::string got = ", got '" + text + "'";
        std::size_t i = 0;
        bool negative = false;
        if (i < text.size() && (text[i] == '+' || text[i] == '-')) negative = text[i++] == '-';
        if (i == text.size()) return range + got;
        unsigned long long value = 0;
        bool overflow = false;
        for (; i < text.size(); ++i) {
          if (!std::isdigit(static_cast<unsigned char>(text[i]))) return range + got;
          const unsigned long long digit = static_cast<unsigned long long>(text[i] - '0');
          if (value > (std::numeric_limits<unsigned long long>::max() - digit) / 10) overflow = true;
          if (!overflow) value = 10 * value + digit;
        }
        if (negative && value != 0) return range + got;
        if (overflow || value < min || value > max) return range + got;
        return {};
      },
      "", "whole_number");
}

CLI::Validator finite_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const NumberReading r = read_number(text);
        if (r.kind != NumberReading::number) return number_problem(text, r);
        return {};
      },
      "", "finite_number");
}

void require_whole_number(const std::string& option, std::string text, unsigned long long min,
                          unsigned long long max) {
  const std::string error = whole_number(min, max)(text);
  if (!error.empty()) throw InvalidInput(option + ": " + error);
}

void require_finite_number(const std::string& option, std::string text) {
  const std::string error = finite_number()(text);
  if (!error.empty()) throw InvalidInput(option + ": " + error);
}

std::array<double, 3> parse_vector3(const std::string& text, const std::string& option) {
  std::array<double, 3> v{};
  std::stringstream stream(text);
  std::string item;
  std::size_t count = 0;
  auto bad = [&]() {
    return InvalidInput(option + ": expected three numbers \"a,b,c\", got \"" + printable(text) + "\"");
  };
  while (std::getline(stream, item, ',')) {
    item = trim(item);
    if (count == 3 || item.empty()) throw bad();
    const NumberReading r = read_number(item);
    if (r.kind == NumberReading::not_a_number) throw bad();
    if (r.kind != NumberReading::number) throw InvalidInput(option + ": " + number_problem(item, r));
    v[count++] = r.value;
  }
  if (count != 3 || (!text.empty() && text.back() == ',')) throw bad();
  return v;
}

void SurfaceOptions::add_to(CLI::App& app) {
  surface_option = app.add_option("--surface", surface,
                                  "A catalog surface (list: `delmesh surfaces`), e.g. torus")
                       ->type_name("NAME");
  expr_option = app.add_option("--expr", expr,
                               "An expression E(x,y,z); the surface is E = 0. Operators + - * / ^ "
                               "(integer powers), exp sqrt sin cos log, Pi. Needs --box")
                    ->type_name("E");
  box_option = app.add_option("--box", box,
                              "x0,x1,y0,y1,z0,z1: the box Sigma must lie strictly inside "
                              "(required with --expr; replaces the catalog box with --surface)")
                   ->type_name("X0,X1,Y0,Y1,Z0,Z1");
}

bool SurfaceOptions::given() const {
  return (surface_option && surface_option->count() > 0) || (expr_option && expr_option->count() > 0);
}

SurfaceArguments SurfaceOptions::arguments() const {
  SurfaceArguments a;
  if (surface_option && surface_option->count() > 0) a.surface = surface;
  if (expr_option && expr_option->count() > 0) a.expr = expr;
  if (box_option && box_option->count() > 0) a.box = box;
  return a;
}

SurfaceInput SurfaceOptions::resolve() const { return arguments().resolve(); }

SurfaceInput SurfaceArguments::resolve() const {
  if (surface.has_value() == expr.has_value()) throw InvalidInput("give exactly one of --surface NAME and --expr E");
  if (surface) {
    const CatalogEntry& entry = catalog_entry(*surface);
    return SurfaceInput{entry.name, entry.surface(), box ? Box3::parse(*box) : entry.box};
  }
  if (!box) throw InvalidInput("--expr needs --box x0,x1,y0,y1,z0,z1");
  const Box3 parsed_box = Box3::parse(*box);
  return SurfaceInput{"surface", Surface::parse(*expr), parsed_box};
}

std::string format_number(double x) {
  if (!std::isfinite(x)) return std::isnan(x) ? "nan" : (x > 0 ? "inf" : "-inf");
  if (x == 0) return "0";  // also -0
  for (int digits = 1; digits <= 17; ++digits) {
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
    if (std::strtod(buffer, nullptr) == x) return buffer;
  }
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

std::string format_box(const Box3& box) {
  std::string text;
  for (int i = 0; i < 3; ++i) {
    if (i > 0) text += ",";
    text += format_number(box.lo[i]) + "," + format_number(box.hi[i]);
  }
  return text;
}

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext;
}

void print_json(std::ostream& out, const nlohmann::ordered_json& object) {
  if (!object.is_object() || object.empty()) {
    out << object.dump() << std::endl;
    return;
  }
  out << "{\n";
  std::size_t i = 0;
  for (auto it = object.begin(); it != object.end(); ++it, ++i) {
    out << "  " << nlohmann::ordered_json(it.key()).dump() << ": " << it.value().dump()
        << (i + 1 < object.size() ? ",\n" : "\n");
  }
  out << "}" << std::endl;
}

std::string printable(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f) {
      char escaped[8];
      std::snprintf(escaped, sizeof escaped, "\\x%02x", u);
      out += escaped;
    } else {
      out += c;
    }
  }
  return out;
}

std::string one_line(std::string message) {
  std::replace(message.begin(), message.end(), '\n', ' ');
  std::replace(message.begin(), message.end(), '\r', ' ');
  while (!message.empty() && message.back() == ' ') message.pop_back();
  return printable(message);
}

void print_error(const std::string& message) {
  std::cout.flush();
  std::cerr << "error: " << one_line(message) << std::endl;
}

void print_warning(const std::string& message) {
  std::cerr << "warning: " << one_line(message) << std::endl;
}

}  // namespace delmesh::app
