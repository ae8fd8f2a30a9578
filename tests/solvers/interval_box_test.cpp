#include "solvers/detail/interval_box.h"

#include <atomic>
#include <thread>
#include <vector>

#include <boost/test/unit_test.hpp>

#include "solvers/krawczyk.h"
#include "solvers/univariate_isolator.h"
#include "solvers/primitives.h"
#include "symbolic/scalar_traits.h"

using namespace delmesh;

namespace {

//! Called by each of two threads: returns once both have arrived, so that their loops overlap.
void start_together(std::atomic<int>& ready) {
  ++ready;
  while (ready.load() < 2) std::this_thread::yield();
}

//! The precision in bits that a default-constructed MpfiInterval gets now.
long current_bits() { return ScalarTraits<MpfiInterval>::precision(); }

//! (x + c)² − c² − 2 c x − 1/4 = x² − 1/4 with c = 1e20 (an exact double): at a point the terms
//! cancel from ~1e40, so 106-bit MPFI (ulp 2^27 there) cannot prove the root x = 1/2 in
//! [0.49, 0.51] and 212-bit MPFI can.  A thread whose 106-bit Krawczyk test ran at another
//! thread's 212 bits would therefore report unique_root instead of inconclusive.
struct CancellingQuadratic {
  CompiledSystem system;
  CancellingQuadratic() : system(make()) {}
  static CompiledSystem make() {
    GiNaC::symbol x("x"), c("c");
    return CompiledSystem({GiNaC::pow(x + c, 2) - c * c - 2 * c * x - GiNaC::numeric(1, 4)}, {x}, {c});
  }
};

//! Everything of a Krawczyk result that the threads compare, bit for bit.
struct KrawczykRecord {
  KrawczykOutcome outcome;
  double lo, hi;
  bool operator==(const KrawczykRecord& o) const { return outcome == o.outcome && lo == o.lo && hi == o.hi; }
};

KrawczykRecord krawczyk_record(const CancellingQuadratic& q, int bits) {
  const KrawczykResult r = krawczyk_test_mpfi(q.system, {1e20}, {Interval(0.49, 0.51)}, bits);
  return {r.outcome, r.contracted[0].inf(), r.contracted[0].sup()};
}

//! A univariate isolation that needs MPFI: (x + 10⁸)² − 10¹⁶ − 2·10⁸ x − 1/4 on the x axis, by
//! interval Newton on the unexpanded expression (every double enclosure is ~4 wide).
struct CancellingLine {
  Surface surface;
  CompiledSystem line;
  CancellingLine()
      : surface(Surface::parse("(x+100000000)^2-10000000000000000-200000000*x-0.25+y^2+z^2")),
        line(surface_line_system(surface)) {}
};

//! The certified intervals and status of an isolation, bit for bit.
std::vector<double> isolation_record(const CancellingLine& c) {
  const SolveResult r = isolate_line_roots(c.line, nullptr, {0, 0, 0}, {1, 0, 0}, -1, 1);
  std::vector<double> out{static_cast<double>(r.status), static_cast<double>(r.undecided.size()),
                          static_cast<double>(r.counters.precision_escalations)};
  for (const auto& root : r.roots) out.insert(out.end(), {root.box.bounds[0][0], root.box.bounds[0][1]});
  return out;
}

}  // namespace

BOOST_AUTO_TEST_SUITE(mpfi_precision_scope)

BOOST_AUTO_TEST_CASE(sets_nests_and_restores_the_precision) {
  const long before = current_bits();
  {
    detail::MpfiPrecisionScope outer(106);
    const long outer_bits = current_bits();
    BOOST_TEST(outer_bits >= 106);
    {
      detail::MpfiPrecisionScope inner(212);  // nests on the same thread (recursive lock)
      BOOST_TEST(current_bits() >= 212);
      BOOST_TEST(MpfiInterval().precision() == MpfiInterval::default_precision());
    }
    BOOST_TEST(current_bits() == outer_bits);
  }
  BOOST_TEST(current_bits() == before);
}

BOOST_AUTO_TEST_CASE(concurrent_scopes_each_see_their_own_precision) {
  // Two threads open scopes at different precisions many times and check, inside each, that new
  // MPFI numbers get their own scope's precision.  Without the scope's lock the threads overwrite
  // each other's process-wide default and this fails within a few iterations.
  const long before = current_bits();
  long bits_106 = 0, bits_212 = 0;
  {
    detail::MpfiPrecisionScope s(106);
    bits_106 = MpfiInterval(1).precision();
  }
  {
    detail::MpfiPrecisionScope s(212);
    bits_212 = MpfiInterval(1).precision();
  }
  BOOST_REQUIRE(bits_106 != bits_212);
  std::atomic<int> mismatches{0};
  std::atomic<int> ready{0};
  auto worker = [&](int bits, long expected) {
    start_together(ready);
    for (int i = 0; i < 20000; ++i) {
      detail::MpfiPrecisionScope scope(bits);
      const MpfiInterval a = detail::to_mpfi(0.1, 0.2);
      const MpfiInterval b = a * a + a;
      if (a.precision() != expected || b.precision() != expected) ++mismatches;
    }
  };
  std::thread t1(worker, 106, bits_106), t2(worker, 212, bits_212);
  t1.join();
  t2.join();
  BOOST_TEST(mismatches.load() == 0);
  BOOST_TEST(current_bits() == before);
}

BOOST_AUTO_TEST_CASE(concurrent_escalating_solves_match_the_serial_ones) {
  // Two threads each run Krawczyk tests in MPFI at 106 and 212 bits alternately (in opposite
  // phase) and univariate isolations that escalate to MPFI; every result must equal the serial one.
  const CancellingQuadratic quadratic;
  const CancellingLine cancelling;
  const KrawczykRecord serial_106 = krawczyk_record(quadratic, 106), serial_212 = krawczyk_record(quadratic, 212);
  BOOST_REQUIRE(serial_106.outcome == KrawczykOutcome::inconclusive);  // precision-sensitive case
  BOOST_REQUIRE(serial_212.outcome == KrawczykOutcome::unique_root);
  const std::vector<double> serial_isolation = isolation_record(cancelling);
  BOOST_REQUIRE(serial_isolation.size() == 3 + 4);  // two certified zeros, ±1/2
  BOOST_REQUIRE(serial_isolation[0] == static_cast<double>(SolveStatus::complete));
  BOOST_REQUIRE(serial_isolation[2] > 0);            // it escalated
  std::atomic<int> mismatches{0};
  std::atomic<int> ready{0};
  auto worker = [&](int phase) {
    start_together(ready);
    for (int i = 0; i < 300; ++i) {
      const int bits = (i + phase) % 2 == 0 ? 106 : 212;
      if (!(krawczyk_record(quadratic, bits) == (bits == 106 ? serial_106 : serial_212))) ++mismatches;
      if (i % 10 == 0 && isolation_record(cancelling) != serial_isolation) ++mismatches;
    }
  };
  std::thread t1(worker, 0), t2(worker, 1);
  t1.join();
  t2.join();
  BOOST_TEST(mismatches.load() == 0);
}

BOOST_AUTO_TEST_SUITE_END()
