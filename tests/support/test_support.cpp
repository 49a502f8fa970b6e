#include "support/test_support.hpp"

#include "layerjkr/callable_profile.hpp"

namespace test {

layerjkr::ProfilePtr sampled_sphere_table(double R, double r_max, int n) {
  std::vector<double> r, z;
  for (int i = 0; i < n; ++i) {
    const double x = r_max * i / (n - 1);
    r.push_back(x);
    z.push_back(R - std::sqrt(R * R - x * x));
  }
  return layerjkr::make_table_profile(r, z);
}

std::vector<NamedProfile> profile_zoo() {
  const std::vector<double> radii{3.75e-4, 6.25e-4, 1.125e-3, 1.875e-3};
  return {
      {"paraboloid", layerjkr::make_paraboloid(1e-2), radii},
      {"sphere", layerjkr::make_sphere(1e-2), radii},
      {"cone", layerjkr::make_cone(70.0 * M_PI / 180.0), radii},
      {"power_law_1.5", layerjkr::make_power_law(0.3, 1.5), radii},
      {"power_law_3", layerjkr::make_power_law(2e3, 3.0), radii},
      {"table", sampled_sphere_table(1e-2, 5e-3, 21), radii},
      {"callable_cosh",
       layerjkr::make_callable_profile(
           [](auto r) {
             using std::cosh;
             return 1e-2 * (cosh(r / 1e-2) - 1.0);
           },
           1e-2, 1.0, "cosh"),
       radii},
  };
}

}  // namespace test
