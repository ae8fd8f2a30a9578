#include "meshing/core/detail/flat_table.h"

#include <map>
#include <random>

#include <boost/test/unit_test.hpp>

using delmesh::detail::FlatTable;

BOOST_AUTO_TEST_SUITE(flat_table)

// Random additions and removals over a small key range (long probe runs, many backward shifts)
// agree with std::map at every step, and references to values survive growth.
BOOST_AUTO_TEST_CASE(agrees_with_a_map_under_random_additions_and_removals) {
  FlatTable<3, int> table;
  std::map<std::array<int, 3>, int> reference;
  std::map<std::array<int, 3>, const int*> address;
  std::mt19937 rng(5);
  std::uniform_int_distribution<int> id(0, 40);
  for (int step = 0; step < 200000; ++step) {
    std::array<int, 3> key{id(rng), id(rng), id(rng)};
    const auto op = rng() % 6;
    if (op == 0) {
      const bool erased = table.erase(key);
      BOOST_TEST_REQUIRE(erased == (reference.erase(key) == 1));
      address.erase(key);
    } else if (op == 1) {
      // take() hands back the removed value itself.
      const int* taken = table.take(key);
      const auto it = reference.find(key);
      BOOST_TEST_REQUIRE((taken != nullptr) == (it != reference.end()));
      if (taken) {
        BOOST_TEST_REQUIRE(*taken == it->second);
        BOOST_TEST_REQUIRE(taken == address[key]);
        reference.erase(it);
      }
      address.erase(key);
    } else {
      const auto [value, added] = table.try_emplace(key);
      BOOST_TEST_REQUIRE(added == (reference.count(key) == 0));
      if (added) {
        *value = step;
        reference[key] = step;
        address[key] = value;
      }
      BOOST_TEST_REQUIRE(*value == reference[key]);
      BOOST_TEST_REQUIRE(address[key] == value);
    }
    BOOST_TEST_REQUIRE(table.size() == reference.size());
  }
  for (const auto& [key, v] : reference) {
    const int* found = table.find(key);
    BOOST_TEST_REQUIRE(found != nullptr);
    BOOST_TEST(*found == v);
  }
  std::size_t visited = 0;
  table.for_each([&](const std::array<int, 3>& key, int v) {
    ++visited;
    BOOST_TEST(reference.at(key) == v);
  });
  BOOST_TEST(visited == reference.size());
  BOOST_TEST(table.find({41, 0, 0}) == nullptr);
  table.clear();
  BOOST_TEST(table.size() == 0u);
  BOOST_TEST(table.find(reference.begin()->first) == nullptr);
}

BOOST_AUTO_TEST_SUITE_END()
