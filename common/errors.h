#pragma once
//! \file errors.h
//! Exceptions for misuse and invalid input.  Algorithmic outcomes (undecided regions, limits
//! reached) are never exceptions: they are status enums in [[nodiscard]] result structs.

#include <stdexcept>
#include <string>

namespace delmesh {

//! Invalid user input: a malformed expression, a singular or non-compact surface, a surface that
//! leaves its box, a corrupt mesh file, a parameter out of range.  The command line turns it into
//! one line `error: <what()>` on stderr and exit code 2.
struct InvalidInput : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

//! Misuse of an API by the calling code (a violated precondition that is the caller's bug).
struct PreconditionViolation : std::logic_error {
  using std::logic_error::logic_error;
};

}  // namespace delmesh
