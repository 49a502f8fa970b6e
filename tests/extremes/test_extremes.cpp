// Every cell of the extreme-value matrix (extremes.cpp) must hold: finite where valid, an
// error or a warning where not, and within tolerance of its limit or reference.
#include <catch2/catch.hpp>

#include "extremes/extremes.hpp"

TEST_CASE("extreme-value matrix: every cell holds", "[extremes]") {
  const auto rows = test::run_extreme_matrix();
  REQUIRE(rows.size() > 60);
  for (const auto& r : rows) {
    INFO(r.area << " | " << r.cell << " | expected " << r.expected << " | got " << r.outcome);
    CHECK(r.ok);
  }
}
