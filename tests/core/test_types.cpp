// The one spelling registry of the public enums (types.hpp).
#include <catch2/catch.hpp>

#include <set>
#include <sstream>
#include <string>

#include "layerjkr/error.hpp"
#include "layerjkr/types.hpp"

using namespace layerjkr;

namespace {

// Every spelling known_names lists parses back to an enumerator whose spelling it is, and
// the spellings are distinct: the registry is a bijection.
template <class E>
void check_round_trip(std::size_t expected_count) {
  std::stringstream list(known_names<E>());
  std::string name;
  std::set<std::string> seen;
  while (std::getline(list, name, ',')) {
    if (!name.empty() && name.front() == ' ') name.erase(0, 1);
    INFO(name);
    const std::optional<E> e = from_string<E>(name);
    REQUIRE(e);
    CHECK(to_string(*e) == name);
    CHECK(parse_enum<E>(name, "key") == *e);
    CHECK(seen.insert(name).second);
  }
  CHECK(seen.size() == expected_count);
  CHECK_FALSE(from_string<E>("no such name"));
  CHECK_THROWS_AS(parse_enum<E>("no such name", "the key"), InputError);
}

}  // namespace

TEST_CASE("every registered enum spells each enumerator once and parses it back", "[types]") {
  check_round_trip<Base>(2);
  check_round_trip<FoundationKind>(2);
  check_round_trip<ModelKind>(8);
  check_round_trip<MediumType>(6);
  check_round_trip<SceneModel>(11);
  check_round_trip<Solver>(2);
  check_round_trip<Branch>(5);
  check_round_trip<FitParameter>(16);
  check_round_trip<LossType>(3);
  check_round_trip<RetractWindow>(3);
  check_round_trip<RetractControl>(4);
  check_round_trip<Baseline>(2);
  check_round_trip<ContactPointMethod>(4);
  check_round_trip<AdhesionModel>(3);
  check_round_trip<FitFamily>(6);
  check_round_trip<SegmentStyle>(4);
  check_round_trip<InstrumentFormat>(9);
  check_round_trip<Smoothing>(2);
  check_round_trip<DiscreteApproach>(2);
}

TEST_CASE("the registry keeps the schema's spellings", "[types]") {
  CHECK(std::string(to_string(SceneModel::automatic)) == "auto");
  CHECK(std::string(to_string(RetractControl::fixed_grips)) == "grips");
  CHECK(std::string(to_string(InstrumentFormat::jpk_qi_data)) == "jpk-qi-data");
  CHECK(std::string(to_string(ModelKind::full_foundation)) == "full_foundation");
  CHECK(known_names<Branch>() == "approach, retract, all, dwell, approach_dwell");
  CHECK(from_string<FitParameter>("T") == FitParameter::G);  // a Filonenko-Borodich tension
  CHECK(std::string(to_string(static_cast<Branch>(42))) == "unknown");
}

TEST_CASE("parse_enum names the key, the text and the known values", "[types]") {
  CHECK_THROWS_WITH(parse_enum<LossType>("tukey", "loss"),
                    "loss = \"tukey\" is unknown (known: none, huber, cauchy)");
  // Text from a binary file is shortened and made printable.
  CHECK_THROWS_WITH(parse_enum<Branch>(std::string(50, 'x') + "\x01", "branch"),
                    Catch::Contains(std::string(40, 'x') + "...") && Catch::Contains("approach"));
}
