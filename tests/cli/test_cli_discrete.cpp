// layerjkr discrete: the two-model approach from files, its summary against a closed form,
// and its input errors (exit 2, one line, nothing on stdout).
#include <catch2/catch.hpp>

#include <cmath>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "support/cli_support.hpp"

using namespace test::cli;

namespace {
// Winkler paraboloid: flat punch S = pi K a^2, convex P = pi K R delta^2.
constexpr double kK = 4e10, kR = 1e-2, kPi = 3.14159265358979323846;
std::string flat_csv(int radii) {
  std::string s = "a,delta,P\n";
  for (int k = 1; k <= radii; ++k)
    for (int i = 1; i <= 10; ++i) {
      const double a = 1e-4 * k, d = 1e-7 * i;
      s += layerjkr::format_double(a) + "," + layerjkr::format_double(d) + "," + layerjkr::format_double(kPi * kK * a * a * d) + "\n";
    }
  return s;
}
std::string convex_csv() {
  std::string s = "delta,P,a\n";
  for (int i = 1; i <= 20; ++i) {
    const double a = 4e-5 * i, d = a * a / (2 * kR);
    s += layerjkr::format_double(d) + "," + layerjkr::format_double(kPi * kK * kR * d * d) + "," + layerjkr::format_double(a) + "\n";
  }
  return s;
}
}  // namespace

TEST_CASE("discrete --summary: Winkler data give the pull-off -2 pi w R", "[cli][discrete]") {
  const std::string flat = write_file("flat.csv", flat_csv(6)), convex = write_file("convex.csv", convex_csv());
  const Run r = run("discrete --flat " + flat + " --convex " + convex + " --w 0.05 --summary");
  INFO(r.err);
  REQUIRE(r.code == 0);
  const auto j = nlohmann::json::parse(r.out);
  CHECK(j["model"] == "discrete");
  CHECK(std::abs(j["pull_off_force"].get<double>() / (-2 * kPi * 0.05 * kR) - 1) < 1e-8);
  const Run curve = run("discrete --flat " + flat + " --convex " + convex + " --w 0.05 --points 5");
  REQUIRE(curve.code == 0);
  CHECK(lines(curve.out).size() == 6);
  CHECK(lines(curve.out)[0] == "a,P,delta,P_H,delta_H,S,P_err,delta_err");
  // Noiseless power laws: the bootstrap has nothing to resample.
  const std::string row = lines(curve.out)[3];
  const std::string P_err = row.substr(0, row.rfind(',')).substr(row.substr(0, row.rfind(',')).rfind(',') + 1);
  CHECK(std::abs(std::stod(P_err)) < 1e-12);
  const Run single = run("discrete --single-model --convex " + convex + " --w 0.05 --summary --smoothing spline");
  INFO(single.err);
  REQUIRE(single.code == 0);
  const auto js = nlohmann::json::parse(single.out);
  CHECK(js["model"] == "single");
  CHECK(std::abs(js["pull_off_force"].get<double>() / (-2 * kPi * 0.05 * kR) - 1) < 1e-6);
  CHECK(js["bootstrap"]["replicates"] == 200);
}

TEST_CASE("discrete: bad data and options exit 2 with one message", "[cli][discrete][errors]") {
  const std::string convex = write_file("convex.csv", convex_csv());
  const std::string few = write_file("few.csv", flat_csv(3)), good = write_file("good.csv", flat_csv(6));
  struct Case { std::string args, expected; };
  const std::vector<Case> cases{
      {"discrete --flat " + few + " --convex " + convex + " --w 0.05 --summary", "3 radii"},
      {"discrete --flat " + good + " --convex " + convex + " --w 0.05", "exactly one of --at, --points"},
      {"discrete --flat " + good + " --convex " + convex + " --w -1 --summary", "--w = -1"},
      {"discrete --flat " + good + " --convex " + convex + " --w 0.05 --at 9e-4", "contact radius a"},
      {"discrete --flat /nonexistent.csv --convex " + convex + " --w 0.05 --summary", "cannot open"},
      {"discrete --convex " + convex + " --w 0.05 --summary", "needs --flat"},
      {"discrete --single-model --flat " + good + " --convex " + convex + " --w 0.05 --summary", "drop --flat"},
      {"discrete --flat " + good + " --convex " + convex + " --w 0.05 --summary --smoothing cubic", "--smoothing = 'cubic'"},
      {"discrete --flat " + good + " --convex " + convex + " --w 0.05 --summary --bootstrap 5", "replicates = 5 is invalid"},
  };
  for (const auto& c : cases) {
    const Run r = run(c.args);
    INFO(c.args << "\nstderr: " << r.err);
    CHECK(r.code == 2);
    CHECK(r.out.empty());
    CHECK(r.err.find(c.expected) != std::string::npos);
  }
}
