#pragma once
//! \file fuzz_support.h
//! What the fuzz targets share: the rule that invalid input may only end as an exception derived
//! from std::invalid_argument (InvalidInput, which the command line reports as `error:` and exit
//! 2).  Any other exception is a finding: it is printed and the target aborts, so that libFuzzer
//! saves the input.

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <stdexcept>
#include <typeinfo>

namespace delmesh::fuzz {

//! Runs body(); returns true if it returned, false if it threw std::invalid_argument; aborts on
//! any other exception.
template <class Body>
bool expect_valid_or_invalid_input(const char* what, Body&& body) {
  try {
    body();
    return true;
  } catch (const std::invalid_argument&) {
    return false;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz: %s threw %s (not InvalidInput): %s\n", what, typeid(e).name(), e.what());
  } catch (...) {
    std::fprintf(stderr, "fuzz: %s threw a non-standard exception\n", what);
  }
  std::abort();
}

}  // namespace delmesh::fuzz
