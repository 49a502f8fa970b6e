// What this makes: the bundled data of the two-model approach (data/discrete/), an FEM stand-in
// whose truth is known, so that examples/discrete_workflow.cpp can show both reconstructions
// against it.
//
// How the data is made: the exact bonded layer of the paper's Appendix A top layer (E = 3 MPa,
// nu = 0.3, h = 0.1 mm) stands in for the FEM model. flat_punch.csv: flat punches of radius
// 0.1 .. 0.6 mm (a/h 1 .. 6, six radii), 20 displacement substeps to 0.025 mm each, as the
// paper's Step 1. convex.csv: a rigid sphere R = 10 mm, 20 substeps to 0.025 mm (Step 2), the contact
// radius read off a 5 um surface mesh (the outermost node in contact). Both start with the zero
// row of first contact, as the paper's data do, and carry 0.3 % Gaussian force noise
// (seeds 14 and 15).
//
// Run: build/bin/make_discrete_data flat data/discrete/flat_punch.csv
//      build/bin/make_discrete_data convex data/discrete/convex.csv
// (target regenerate_discrete_data); the tests generated_discrete_* fail when a committed copy
// is stale.
#include <fstream>
#include <iostream>
#include <string>

#include "layerjkr/layerjkr.hpp"

using namespace layerjkr;

int main(int argc, char** argv) {
  const std::string which = argc == 3 ? argv[1] : "";
  if (which != "flat" && which != "convex") {
    std::cerr << "usage: make_discrete_data flat|convex OUT.csv\n";
    return 2;
  }
  try {
    const ElasticLayer layer{3e6, 0.3, 0.1e-3, Base::bonded};
    const auto truth = make_exact_layer(make_sphere(10e-3), layer);
    std::string csv;
    if (which == "flat") {
      const std::vector<double> radii{0.1e-3, 0.2e-3, 0.3e-3, 0.4e-3, 0.5e-3, 0.6e-3};
      const FlatPunchData d = sample_flat_punch(*truth, radii, {20, 0.025e-3, 0.003, 14});
      csv = "a,delta,P\n";
      for (std::size_t i = 0; i < d.a.size(); ++i) {
        if (i % 20 == 0) csv += format_double(d.a[i]) + ",0,0\n";
        csv += format_double(d.a[i]) + "," + format_double(d.delta[i]) + "," + format_double(d.P[i]) + "\n";
      }
    } else {
      const ConvexData c = sample_convex(*truth, {20, 0.025e-3, 0.003, 15, 5e-6});
      csv = "delta,P,a\n0,0,0\n";
      for (std::size_t i = 0; i < c.delta.size(); ++i)
        csv += format_double(c.delta[i]) + "," + format_double(c.P[i]) + "," + format_double(c.a[i]) + "\n";
    }
    std::ofstream out(argv[2], std::ios::binary);
    out << csv;
    if (!out) throw InputError(std::string("cannot write ") + argv[2]);
  } catch (const Error& e) {
    std::cerr << "make_discrete_data: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
