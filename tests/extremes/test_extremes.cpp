// Every cell of the extreme-value matrix (extremes.cpp) must hold: finite where valid, an
// error or a warning where not, and within tolerance of its limit or reference. Each group
// of the matrix (one cell, or a short sequence) is its own test case, registered from
// test::extreme_groups() and named "extreme-value matrix: <area>: <cell>", so ctest runs
// and reports every cell on its own and a failure names its cell.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "extremes/extremes.hpp"

namespace {

class GroupTest : public Catch::ITestInvoker {
 public:
  explicit GroupTest(std::size_t index) : index_(index) {}
  void invoke() const override {
    const auto rows = test::run_extreme_group(index_);
    REQUIRE(!rows.empty());
    for (const auto& r : rows) {
      INFO(r.area << " | " << r.cell << " | expected " << r.expected << " | got " << r.outcome);
      CHECK(r.ok);
    }
  }

 private:
  std::size_t index_;
};

// Registers one test case per group before main() runs (as Catch's own TEST_CASE does; the
// test case owns its invoker and copies the name and tags).
[[maybe_unused]] const bool registered = [] {
  const std::vector<test::ExtremeGroup> groups = test::extreme_groups();
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const std::string name = "extreme-value matrix: " + groups[i].tag + ": " + groups[i].name;
    const std::string tags = "[extremes][" + groups[i].tag + "]";
    Catch::AutoReg(new GroupTest(i), CATCH_INTERNAL_LINEINFO, Catch::StringRef(), Catch::NameAndTags{name, tags});
  }
  return true;
}();

}  // namespace

TEST_CASE("extreme-value matrix: more than 60 cells", "[extremes]") {
  // Every group has at least one cell (its test case REQUIREs it).
  REQUIRE(test::extreme_groups().size() > 60);
}
