#include "symbolic/monomial_basis.h"

#include <boost/test/unit_test.hpp>

#include "common/errors.h"

using namespace delmesh;

namespace {

std::size_t binomial(std::size_t n, std::size_t k) {
  std::size_t b = 1;
  for (std::size_t i = 1; i <= k; ++i) b = b * (n - k + i) / i;
  return b;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(monomial_basis)

BOOST_AUTO_TEST_CASE(size_order_and_index_are_consistent) {
  for (std::size_t n = 1; n <= 3; ++n)
    for (int d = 0; d <= 9; ++d) {
      const MonomialBasis basis(n, d);
      BOOST_TEST(basis.size() == binomial(n + static_cast<std::size_t>(d), n));
      for (std::size_t i = 0; i < basis.size(); ++i) {
        BOOST_TEST(basis.index(basis.exponent(i)) == i);
        if (i > 0) BOOST_TEST(basis.total_degree(i - 1) <= basis.total_degree(i));  // graded
        bool even = true;
        int total = 0;
        for (std::size_t k = 0; k < n; ++k) total += basis.exponent(i)[k], even = even && basis.exponent(i)[k] % 2 == 0;
        BOOST_TEST(basis.total_degree(i) == total);
        BOOST_TEST(basis.all_even(i) == even);
      }
      BOOST_TEST(basis.total_degree(0) == 0);
      MonomialBasis::Exponent too_high{};
      too_high[0] = d + 1;
      BOOST_TEST(basis.index(too_high) == basis.size());
    }
}

BOOST_AUTO_TEST_CASE(fibres_partition_the_basis_along_each_axis) {
  const MonomialBasis basis(3, 6);
  for (std::size_t k = 0; k < 3; ++k) {
    std::vector<int> seen(basis.size(), 0);
    for (const auto& fibre : basis.fibres(k)) {
      const auto& base = basis.exponent(fibre[0]);
      BOOST_TEST(base[k] == 0);
      BOOST_TEST(static_cast<int>(fibre.size()) == 6 - basis.total_degree(fibre[0]) + 1);
      for (std::size_t j = 0; j < fibre.size(); ++j) {
        ++seen[fibre[j]];
        MonomialBasis::Exponent e = base;
        e[k] = static_cast<int>(j);
        BOOST_TEST(basis.exponent(fibre[j]) == e);
      }
    }
    for (int count : seen) BOOST_TEST(count == 1);
    MonomialBasis::Exponent unit{};
    unit[k] = 1;
    BOOST_TEST(basis.linear(k) == basis.index(unit));
  }
}

BOOST_AUTO_TEST_CASE(invalid_sizes_throw) {
  BOOST_CHECK_THROW(MonomialBasis(0, 2), PreconditionViolation);
  BOOST_CHECK_THROW(MonomialBasis(4, 2), PreconditionViolation);
  BOOST_CHECK_THROW(MonomialBasis(2, -1), PreconditionViolation);
  BOOST_CHECK_THROW(MonomialBasis(2, 65), PreconditionViolation);
}

BOOST_AUTO_TEST_SUITE_END()
