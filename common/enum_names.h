#pragma once
//! \file enum_names.h
//! One name table per enumeration gives both its text (operator<<, statistics, messages) and its
//! parsing (command-line options).
//!
//! An enumeration E declares its table next to itself, as a function found by argument-dependent
//! lookup:
//!
//!     enum class Mode { fast, exact };
//!     constexpr auto enum_names(Mode) { return name_table<Mode>("Mode", {{Mode::fast, "fast"}, {Mode::exact, "exact"}}); }
//!     inline std::ostream& operator<<(std::ostream& out, Mode mode) { return write_enum(out, mode); }
//!
//! and everything below reads that table.

#include <array>
#include <cstddef>
#include <map>
#include <optional>
#include <ostream>
#include <string>

#include "common/errors.h"

namespace delmesh {

//! One enumerator and its name.
template <class E>
struct EnumName {
  E value;
  const char* name;
};

//! The name table of the enumeration E (`type` names E itself, for values outside the table).
template <class E, std::size_t N>
struct EnumNames {
  const char* type;
  std::array<EnumName<E>, N> names;
};

namespace detail {
constexpr bool same_text(const char* a, const char* b) {
  while (*a != '\0' && *a == *b) ++a, ++b;
  return *a == *b;
}
}  // namespace detail

//! The table of `names`, in the order given (the order of enum_choices).  The functions below
//! build each table at compile time, so a table that breaks the precondition does not compile.
//! \pre no enumerator and no name occurs twice.
//! \throws PreconditionViolation otherwise.
template <class E, std::size_t N>
constexpr EnumNames<E, N> name_table(const char* type, const EnumName<E> (&names)[N]) {
  EnumNames<E, N> table{type, {}};
  for (std::size_t i = 0; i < N; ++i) {
    for (std::size_t j = 0; j < i; ++j)
      if (names[j].value == names[i].value || detail::same_text(names[j].name, names[i].name))
        throw PreconditionViolation(std::string("name_table: an enumerator or a name of ") + type + " occurs twice");
    table.names[i] = names[i];
  }
  return table;
}

//! \return the name of `value`, or nullptr if its table does not list it.
template <class E>
constexpr const char* enum_name(E value) {
  constexpr auto table = enum_names(E{});
  for (const EnumName<E>& entry : table.names)
    if (entry.value == value) return entry.name;
  return nullptr;
}

//! Writes the name of `value`; a value outside the table (only a cast can make one) as "Type(N)".
template <class E>
std::ostream& write_enum(std::ostream& out, E value) {
  if (const char* name = enum_name(value)) return out << name;
  return out << enum_names(E{}).type << '(' << static_cast<long long>(value) << ')';
}

//! \return the enumerator named `text` (exactly), or nothing.
template <class E>
std::optional<E> find_enum(const std::string& text) {
  constexpr auto table = enum_names(E{});
  for (const EnumName<E>& entry : table.names)
    if (text == entry.name) return entry.value;
  return std::nullopt;
}

//! The names of E in table order as prose: "a or b", "a, b or c".
template <class E>
std::string enum_choices() {
  constexpr auto names = enum_names(E{}).names;
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i)
    text += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + std::string(names[i].name);
  return text;
}

//! The enumerator named `text`, given as the value of the user's option `what` (e.g. "--phase").
//! \throws InvalidInput "<what>: expected <enum_choices>, got '<text>'" if no enumerator has that name.
template <class E>
E parse_enum(const std::string& text, const std::string& what) {
  if (const std::optional<E> value = find_enum<E>(text)) return *value;
  throw InvalidInput(what + ": expected " + enum_choices<E>() + ", got '" + text + "'");
}

//! Name → enumerator, for parsers that take a map (CLI11's CheckedTransformer).
template <class E>
std::map<std::string, E> enum_name_map() {
  std::map<std::string, E> map;
  constexpr auto table = enum_names(E{});
  for (const EnumName<E>& entry : table.names) map.emplace(entry.name, entry.value);
  return map;
}

}  // namespace delmesh
