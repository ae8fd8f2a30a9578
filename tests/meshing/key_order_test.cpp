#include "meshing/core/detail/key_order.h"

#include "meshing/voronoi/delaunay.h"

#include <algorithm>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include <boost/test/unit_test.hpp>

using namespace delmesh;

BOOST_AUTO_TEST_SUITE(key_order)

// The packed comparators return what std::array's operators return on every pair, over ids that
// include −1 (the infinite vertex), the extremes of int and many ties in the leading entries.
BOOST_AUTO_TEST_CASE(comparators_agree_with_the_standard_operators) {
  const std::vector<VertexId> special{std::numeric_limits<VertexId>::min(), -2, -1, 0, 1, 2,
                                      std::numeric_limits<VertexId>::max() - 1, std::numeric_limits<VertexId>::max()};
  std::mt19937 rng(11);
  auto id = [&] { return rng() % 3 == 0 ? special[rng() % special.size()] : static_cast<VertexId>(rng() % 5); };
  const detail::KeyLess less;
  const detail::KeyEqual equal;
  for (int i = 0; i < 200000; ++i) {
    const TriangleKey a{id(), id(), id()}, b{id(), id(), id()};
    BOOST_TEST_REQUIRE(less(a, b) == (a < b));
    BOOST_TEST_REQUIRE(equal(a, b) == (a == b));
    const EdgeKey e{a[0], a[1]}, f{b[0], b[1]};
    BOOST_TEST_REQUIRE(less(e, f) == (e < f));
    BOOST_TEST_REQUIRE(equal(e, f) == (e == f));
    BOOST_TEST_REQUIRE((detail::pair_word(a[0], a[1]) < detail::pair_word(b[0], b[1])) ==
                       (std::make_pair(a[0], a[1]) < std::make_pair(b[0], b[1])));
  }
}

// A sort with KeyLess leaves the sequence a sort with operator< leaves, element for element, and
// sort_unique() is std::sort followed by std::unique.
BOOST_AUTO_TEST_CASE(sorting_gives_the_standard_sequence) {
  std::mt19937 rng(3);
  for (int round = 0; round < 200; ++round) {
    std::vector<TriangleKey> keys(rng() % 300);
    for (auto& k : keys) k = make_triangle_key(rng() % 40, rng() % 40, rng() % 40);
    auto expected = keys;
    std::sort(expected.begin(), expected.end());
    auto got = keys;
    std::sort(got.begin(), got.end(), detail::KeyLess{});
    BOOST_TEST_REQUIRE(got == expected);
    expected.erase(std::unique(expected.begin(), expected.end()), expected.end());
    detail::sort_unique(keys);
    BOOST_TEST_REQUIRE(keys == expected);
  }
}

// make_triangle_key sorts its three ids, whatever their order.
BOOST_AUTO_TEST_CASE(triangle_keys_are_sorted_in_every_order) {
  std::array<VertexId, 3> ids{-1, 4, 9};
  do {
    BOOST_TEST((make_triangle_key(ids[0], ids[1], ids[2]) == TriangleKey{-1, 4, 9}));
  } while (std::next_permutation(ids.begin(), ids.end()));
  BOOST_TEST((make_triangle_key(3, 3, 1) == TriangleKey{1, 3, 3}));
}

BOOST_AUTO_TEST_SUITE_END()
