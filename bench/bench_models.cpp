// Cost of one non-adhesive state per model and profile, of the JKR transform over a
// 200-point curve, and of the critical-point search. Medians go in docs/benchmarks.md:
//   build/bin/bench_models --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "layerjkr/callable_profile.hpp"
#include "layerjkr/layerjkr.hpp"

namespace {

using namespace layerjkr;

const ThinLayerConstants kFilm = thin_layer_constants({3e6, 0.2, 1e-4, Base::bonded});

ProfilePtr table() {
  std::vector<double> r, z;
  for (int i = 0; i <= 40; ++i) {
    r.push_back(5e-3 * i / 40);
    z.push_back(1e-2 - std::sqrt(1e-4 - r.back() * r.back()));
  }
  return make_table_profile(r, z);
}

ProfilePtr callable() {
  return make_callable_profile([](auto r) { return r * r / 2e-2; }, 1e-2, INFINITY, "callable");
}

void run_state(benchmark::State& st, const ContactModelPtr& model) {
  double a = 5e-4;
  for (auto _ : st) {
    benchmark::DoNotOptimize(model->state(a));
    a = a == 5e-4 ? 5.0001e-4 : 5e-4;  // defeat caching by the compiler
  }
}

#define STATE_BENCH(name, expr)                                 \
  void BM_State_##name(benchmark::State& st) { run_state(st, expr); } \
  BENCHMARK(BM_State_##name)

STATE_BENCH(Winkler_Paraboloid, make_winkler(make_paraboloid(1e-2), kFilm.K));
STATE_BENCH(TwoTerm_Paraboloid, make_two_term(make_paraboloid(1e-2), kFilm.K, kFilm.G));
STATE_BENCH(TwoTerm_Sphere, make_two_term(make_sphere(1e-2), kFilm.K, kFilm.G));
STATE_BENCH(TwoTerm_Table, make_two_term(table(), kFilm.K, kFilm.G));
STATE_BENCH(TwoTerm_Callable, make_two_term(callable(), kFilm.K, kFilm.G));
STATE_BENCH(FullFoundation_Paraboloid, make_full_foundation(make_paraboloid(1e-2), kFilm.K, kFilm.G));
STATE_BENCH(Incompressible_Paraboloid, make_incompressible_layer(make_paraboloid(1e-2), {3e6, 0.5, 1e-4, Base::bonded}));
STATE_BENCH(Incompressible_Sphere, make_incompressible_layer(make_sphere(1e-2), {3e6, 0.5, 1e-4, Base::bonded}));
STATE_BENCH(Uniform_Paraboloid_nu049, make_uniform_layer(make_paraboloid(1e-2), {3e6, 0.49, 1e-4, Base::bonded}));
STATE_BENCH(Uniform_Sphere_nu049, make_uniform_layer(make_sphere(1e-2), {3e6, 0.49, 1e-4, Base::bonded}));
STATE_BENCH(HalfSpace_Paraboloid, make_half_space(make_paraboloid(1e-2), 3e6, 0.3));
STATE_BENCH(HalfSpace_Sphere, make_half_space(make_sphere(1e-2), 3e6, 0.3));
STATE_BENCH(HalfSpace_Table, make_half_space(table(), 3e6, 0.3));
STATE_BENCH(Ode_TwoTerm_Paraboloid,
            make_ode_foundation(make_paraboloid(1e-2), kFilm.K, kFilm.G, FoundationKind::asymptotic));
STATE_BENCH(Ode_Full_Paraboloid,
            make_ode_foundation(make_paraboloid(1e-2), kFilm.K, kFilm.G, FoundationKind::full));

// Exact layer, one contact radius at a/h = 1, 10, 50 (no error estimate): a sphere, which
// is solved (Nystrom, Cholesky), and a paraboloid, whose state comes from the shared
// per-(nu, base, d) table (built outside the loop).
void BM_State_Exact_Sphere(benchmark::State& st) {
  static const auto model = make_exact_layer(make_sphere(1e3), {1.0, 0.3, 1.0, Base::bonded});
  const double a = static_cast<double>(st.range(0));
  for (auto _ : st) benchmark::DoNotOptimize(model->state(a));
}
BENCHMARK(BM_State_Exact_Sphere)->Arg(1)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond);

void BM_State_Exact_Paraboloid(benchmark::State& st) {
  static const auto model = make_exact_layer(make_paraboloid(1.0), {1.0, 0.3, 1.0, Base::bonded});
  const double a = static_cast<double>(st.range(0));
  (void)model->state(a);  // builds the table piece
  for (auto _ : st) benchmark::DoNotOptimize(model->state(a));
}
BENCHMARK(BM_State_Exact_Paraboloid)->Arg(1)->Arg(10)->Arg(50)->Unit(benchmark::kMicrosecond);

// A 200-point curve of a sphere a_i = (a/h) h i / 200, radius by radius (one factorisation
// each) and as one sweep (ContactModel::states: one factorisation when that is cheaper).
void BM_Curve200_Exact(benchmark::State& st) {
  static const auto model = make_exact_layer(make_sphere(1e3), {1.0, 0.3, 1.0, Base::bonded});
  const double top = static_cast<double>(st.range(0));
  for (auto _ : st)
    for (int i = 1; i <= 200; ++i) benchmark::DoNotOptimize(model->state(top * i / 200));
}
BENCHMARK(BM_Curve200_Exact)->Arg(1)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond)->Iterations(1);

void BM_Curve200_Exact_Sweep(benchmark::State& st) {
  static const auto model = make_exact_layer(make_sphere(1e3), {1.0, 0.3, 1.0, Base::bonded});
  const double top = static_cast<double>(st.range(0));
  std::vector<double> radii;
  for (int i = 1; i <= 200; ++i) radii.push_back(top * i / 200);
  for (auto _ : st) benchmark::DoNotOptimize(model->states(radii));
}
BENCHMARK(BM_Curve200_Exact_Sweep)->Arg(1)->Arg(10)->Arg(50)->Unit(benchmark::kMillisecond)->Iterations(1);

// The paraboloid table of a new layer (a new nu each time: the caches miss), built over
// a/h in [1e-6, A] for A = 30 (what a typical scene reaches) and 220 (all of it); the kernel
// (BM_ExactKernelTable) is included.
void BM_ExactParaboloidTable(benchmark::State& st) {
  static double nu = 0.45;
  const double top = static_cast<double>(st.range(0));
  for (auto _ : st) {
    nu += 1e-9;
    const auto model = make_exact_layer(make_paraboloid(1.0), {1.0, nu, 1.0, Base::bonded});
    for (double rho = 1e-6; rho < top; rho *= 1.3) benchmark::DoNotOptimize(model->state(rho));
  }
}
BENCHMARK(BM_ExactParaboloidTable)->Arg(30)->Arg(220)->Unit(benchmark::kMillisecond);

// Building the kernel function (a new nu each time, so the process-wide cache misses) and
// constructing a kernel whose function is already cached.
void BM_ExactKernelTable(benchmark::State& st) {
  static double nu = 0.3;  // never repeats across repetitions: every build misses the cache
  for (auto _ : st) {
    nu += 1e-9;
    benchmark::DoNotOptimize(ExactLayerKernel({1.0, nu, 1.0, Base::bonded}));
  }
}
BENCHMARK(BM_ExactKernelTable)->Unit(benchmark::kMillisecond);

void BM_ExactKernelCached(benchmark::State& st) {
  const ExactLayerKernel first({1.0, 0.3, 1.0, Base::bonded});
  for (auto _ : st) benchmark::DoNotOptimize(ExactLayerKernel({2.0, 0.3, 5.0, Base::bonded}));
}
BENCHMARK(BM_ExactKernelCached)->Unit(benchmark::kMicrosecond);

void BM_Curve200_TwoTerm_Sphere(benchmark::State& st) {
  const JkrSolution jkr(make_two_term(make_sphere(1e-2), kFilm.K, kFilm.G), 0.05);
  std::vector<double> radii;
  for (int i = 1; i <= 200; ++i) radii.push_back(1e-3 * i / 200);
  for (auto _ : st) benchmark::DoNotOptimize(jkr.curve(radii));
}
BENCHMARK(BM_Curve200_TwoTerm_Sphere);

void BM_Summary(benchmark::State& st, ContactModelPtr model) {
  const JkrSolution jkr(std::move(model), 0.05);
  for (auto _ : st) benchmark::DoNotOptimize(summarize(jkr));
}
BENCHMARK_CAPTURE(BM_Summary, TwoTerm_Paraboloid, make_two_term(make_paraboloid(1e-2), kFilm.K, kFilm.G));
BENCHMARK_CAPTURE(BM_Summary, HalfSpace_Paraboloid, make_half_space(make_paraboloid(1e-2), 3e6, 0.3));
BENCHMARK_CAPTURE(BM_Summary, FullFoundation_Sphere, make_full_foundation(make_sphere(1e-2), kFilm.K, kFilm.G));

}  // namespace

// The front-end curve (layerjkr curve, layerjkr.curve in Python): 200 radii of the bundled
// hydrogel scene with the model error column; python/bench/bench_python.py subtracts this
// from the Python call to get the binding's overhead.
void BM_CurveTable200_Hydrogel(benchmark::State& st) {
  const Scene scene = load_scene(LAYERJKR_SOURCE_DIR "/data/scenes/hydrogel_film_two_term.json");
  std::vector<double> radii;
  for (int i = 0; i < 200; ++i) radii.push_back(1e-7 + (2e-6 - 1e-7) * i / 199);
  for (auto _ : st) benchmark::DoNotOptimize(solve_curve(scene, radii));
}
BENCHMARK(BM_CurveTable200_Hydrogel)->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
