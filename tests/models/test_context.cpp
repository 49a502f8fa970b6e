// Context: the caches behind the exact and uniform layers belong to an explicit object.
// Oracles: the same computation before and after clear(), bit for bit, and the entry counts
// that the requests made imply.
#include <catch2/catch.hpp>

#include <thread>
#include <vector>

#include "layerjkr/context.hpp"
#include "layerjkr/exact_layer.hpp"
#include "layerjkr/model.hpp"
#include "models/layer_kernel.hpp"
#include "support/catch_after_glog.hpp"  // after the internal headers: Catch's CHECK, not glog's

using namespace layerjkr;

namespace {

bool identical(const NonAdhesiveState& x, const NonAdhesiveState& y) {
  return x.a == y.a && x.P_H == y.P_H && x.delta_H == y.delta_H && x.S == y.S && x.dS_da == y.dS_da;
}

bool same_counts(const CacheStats& x, const CacheStats& y) {
  return x.kernels == y.kernels && x.power_law_tables == y.power_law_tables &&
         x.uniform_betas == y.uniform_betas;
}

ExactLayerOptions with(std::shared_ptr<Context> context, bool tabulate = true) {
  ExactLayerOptions o;
  o.context = std::move(context);
  o.tabulate_power_laws = tabulate;
  return o;
}

const ElasticLayer kLayer{3e4, 0.41, 2e-5, Base::bonded};

}  // namespace

TEST_CASE("context: stats count the entries requested and fall to 0 after clear()", "[context]") {
  const auto context = std::make_shared<Context>();
  CHECK(same_counts(context->stats(), CacheStats{}));
  const auto paraboloid = make_paraboloid(1e-2);
  (void)make_exact_layer(paraboloid, kLayer, with(context))->state(1e-4);
  CHECK(context->stats().kernels == 1);
  CHECK(context->stats().power_law_tables == 1);
  // Another d on the same layer: a new table, the same kernel.
  (void)make_exact_layer(make_cone(1.2), kLayer, with(context))->state(1e-4);
  CHECK(context->stats().kernels == 1);
  CHECK(context->stats().power_law_tables == 2);
  // Another base: a new kernel; no tabulation: no new table.
  (void)make_exact_layer(paraboloid, {3e4, 0.41, 2e-5, Base::frictionless}, with(context, false))->state(1e-4);
  CHECK(context->stats().kernels == 2);
  CHECK(context->stats().power_law_tables == 2);
  // The uniform layer's beta fit solves on its own Context's kernel for (nu, bonded).
  const double beta = uniform_layer_beta(kLayer, context);
  CHECK(context->stats().uniform_betas == 1);
  CHECK(context->stats().kernels == 2);
  CHECK(uniform_layer_beta(kLayer, context) == beta);
  CHECK(context->stats().uniform_betas == 1);
  context->clear();
  CHECK(same_counts(context->stats(), CacheStats{}));
  CHECK(uniform_layer_beta(kLayer, context) == beta);  // rebuilt, the same number
}

TEST_CASE("context: clear() then recomputing gives bit-identical states", "[context]") {
  const auto context = std::make_shared<Context>();
  const auto profile = make_paraboloid(1e-2);
  for (const bool tabulate : {true, false}) {
    const auto before = make_exact_layer(profile, kLayer, with(context, tabulate));
    const NonAdhesiveState first = before->state(3e-4);
    context->clear();
    // A model built before clear() keeps its kernel and table; one built after rebuilds them.
    CHECK(identical(before->state(3e-4), first));
    const auto after = make_exact_layer(profile, kLayer, with(context, tabulate));
    CHECK(identical(after->state(3e-4), first));
  }
  // A model outlives its Context and keeps working.
  auto own = std::make_shared<Context>();
  const auto orphan = make_exact_layer(profile, kLayer, with(own));
  const NonAdhesiveState kept = orphan->state(2e-4);
  own.reset();
  CHECK(identical(orphan->state(2e-4), kept));
}

TEST_CASE("context: a private Context leaves the global one untouched", "[context]") {
  const CacheStats global_before = Context::global().stats();
  const auto context = std::make_shared<Context>();
  // A nu and d no other test uses, so the global caches could not already hold them.
  const ElasticLayer layer{3e4, 0.377, 2e-5, Base::bonded};
  const auto model = make_exact_layer(make_power_law(3.0, 2.5), layer, with(context));
  (void)model->state(5e-5);
  (void)make_uniform_layer(make_paraboloid(1e-2), layer, true, context)->state(1e-4);
  CHECK(same_counts(Context::global().stats(), global_before));
  CHECK(context->stats().kernels == 1);
  CHECK(context->stats().power_law_tables == 1);
  CHECK(context->stats().uniform_betas == 1);
  // And the default (null) Context is the global one.
  (void)make_exact_layer(make_power_law(3.0, 2.5), layer)->state(5e-5);
  CHECK(Context::global().stats().power_law_tables >= 1);
}

TEST_CASE("context: two threads asking for the same kernel build it once", "[context]") {
  const auto context = std::make_shared<Context>();
  std::vector<std::shared_ptr<const detail::LayerKernelFunction>> got(2);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < got.size(); ++i)
    threads.emplace_back([&, i] { got[i] = detail::shared_layer_kernel(0.33, true, context); });
  for (std::thread& t : threads) t.join();
  CHECK(context->stats().kernels == 1);
  CHECK(got[0] == got[1]);
  // Solvers on that Context share it too.
  const ExactLayerKernel solver({3e4, 0.33, 2e-5, Base::bonded}, with(context));
  CHECK(context->stats().kernels == 1);
  CHECK(solver.kernel(1.7) == got[0]->value(1.7));
  CHECK(solver.options().context == nullptr);  // a solver does not keep its Context alive
}
