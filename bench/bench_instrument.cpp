// What this measures: reading instrument files - a 16 x 16 QI map (256 curves of ~600
// samples, int32 channels) and a single JPK curve - end to end through libzip.
// How the data is made: the 256-curve archive is assembled in a temporary directory from the
// four curves of ../shared/data/instrument's QI file, each copied 64 times under new index
// numbers (headers, shared calibration and channel data unchanged). Skipped without ../shared.
#include <benchmark/benchmark.h>

#include <zip.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "layerjkr/fit.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/scene.hpp"

namespace {

const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/../shared/data/instrument/";
const std::string kQi = kDir + "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data";

std::string read_entry(zip_t* z, const char* name) {
  zip_stat_t st;
  zip_stat(z, name, 0, &st);
  std::string data(st.size, '\0');
  zip_file_t* f = zip_fopen(z, name, 0);
  zip_fread(f, data.data(), st.size);
  zip_fclose(f);
  return data;
}

// index/N/... of the source's four curves, copied to index/0 .. index/255.
std::string make_qi_256(const std::filesystem::path& out) {
  int code = 0;
  zip_t* in = zip_open(kQi.c_str(), ZIP_RDONLY, &code);
  zip_t* dst = zip_open(out.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
  std::vector<std::string> keep;  // buffers must live until zip_close
  keep.reserve(4096);
  auto add = [&](const std::string& name, std::string data) {
    keep.push_back(std::move(data));
    zip_source_t* src = zip_source_buffer(dst, keep.back().data(), keep.back().size(), 0);
    zip_file_add(dst, name.c_str(), src, ZIP_FL_OVERWRITE);
  };
  const zip_int64_t n = zip_get_num_entries(in, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const std::string name = zip_get_name(in, static_cast<zip_uint64_t>(i), 0);
    if (name.back() == '/') continue;
    if (name.rfind("index/", 0) != 0) {
      add(name, read_entry(in, name.c_str()));
      continue;
    }
    const std::size_t slash = name.find('/', 6);
    const int source = std::stoi(name.substr(6, slash - 6));
    const std::string data = read_entry(in, name.c_str());
    for (int copy = 0; copy < 64; ++copy)
      add("index/" + std::to_string(copy * 4 + source) + name.substr(slash), data);
  }
  zip_close(dst);
  zip_discard(in);
  return out.string();
}

void BM_ReadQiMap256(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "layerjkr_bench_instrument";
  std::filesystem::create_directories(dir);
  const std::string path = make_qi_256(dir / "map256.jpk-qi-data");
  for (auto _ : state) {
    const layerjkr::InstrumentFile f = layerjkr::read_instrument_file(path);
    if (f.curves.size() != 256) state.SkipWithError("expected 256 curves");
    benchmark::DoNotOptimize(f);
  }
  std::filesystem::remove_all(dir);
}

void BM_ReadJpkSpot3(benchmark::State& state) {
  for (auto _ : state) benchmark::DoNotOptimize(layerjkr::read_instrument_file(kDir + "fmt-jpk-fd_spot3-0192.jpk-force"));
}

const char* kHertzScene = R"({"indenter": {"shape": "paraboloid", "R": 4e-8},
    "medium": {"type": "half_space", "E": 3e5, "nu": 0.5}})";

layerjkr::FitOptions spot3_options() {
  layerjkr::FitOptions o;
  o.free = {layerjkr::FitParameter::E, layerjkr::FitParameter::delta0, layerjkr::FitParameter::P0};
  return o;  // approach branch, 2000 samples
}

// The fit alone of the spot3 archive's curve, and fit_files over 200 copies of the archive
// on one thread (read, convert, fit): the issue's target is at most 2x the fit alone.
void BM_FitJpkSpot3(benchmark::State& state) {
  const layerjkr::InstrumentFile f = layerjkr::read_instrument_file(kDir + "fmt-jpk-fd_spot3-0192.jpk-force");
  const layerjkr::CurveData d = layerjkr::to_curve_data(f.curves[0], "spot3");
  const layerjkr::Scene scene = layerjkr::parse_scene(kHertzScene);
  for (auto _ : state) benchmark::DoNotOptimize(layerjkr::fit(d, scene, spot3_options()));
}

void BM_FitFilesJpkSpot3_200(benchmark::State& state) {
  const auto dir = std::filesystem::temp_directory_path() / "layerjkr_bench_jpk_files";
  std::filesystem::create_directories(dir);
  std::vector<std::string> paths;
  for (int i = 0; i < 200; ++i) {
    paths.push_back((dir / ("c" + std::to_string(i) + ".jpk-force")).string());
    std::filesystem::copy_file(kDir + "fmt-jpk-fd_spot3-0192.jpk-force", paths.back(),
                               std::filesystem::copy_options::overwrite_existing);
  }
  const layerjkr::Scene scene = layerjkr::parse_scene(kHertzScene);
  for (auto _ : state) benchmark::DoNotOptimize(layerjkr::fit_files(paths, scene, spot3_options(), {}));
  state.SetItemsProcessed(state.iterations() * 200);
  std::filesystem::remove_all(dir);
}

}  // namespace

int main(int argc, char** argv) {
  if (std::ifstream(kQi).good()) {
    benchmark::RegisterBenchmark("BM_ReadQiMap256", BM_ReadQiMap256)->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark("BM_ReadJpkSpot3", BM_ReadJpkSpot3)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_FitJpkSpot3", BM_FitJpkSpot3)->Unit(benchmark::kMicrosecond);
    benchmark::RegisterBenchmark("BM_FitFilesJpkSpot3_200", BM_FitFilesJpkSpot3_200)->Unit(benchmark::kMillisecond);
  }
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
