//! \file expression_fuzzer.cpp
//! libFuzzer target fuzz_expression: the input as the text of --expr (Surface::parse: GiNaC's
//! parser, the grammar check, exact rationals, ∇E and the Hessian) and as the text of --box
//! (Box3::parse).  Either parses or throws InvalidInput; anything else is a finding.

#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_support.h"
#include "symbolic/surface.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  delmesh::fuzz::expect_valid_or_invalid_input("Surface::parse", [&] {
    const delmesh::Surface surface = delmesh::Surface::parse(text);
    (void)surface.degree();
  });
  delmesh::fuzz::expect_valid_or_invalid_input("Box3::parse", [&] { (void)delmesh::Box3::parse(text); });
  return 0;
}
