// Provenance: SHA-256 against the FIPS 180-2 vectors and coreutils' sha256sum (a second,
// independent implementation), files streamed across chunk boundaries, every option through a
// JSON round trip bit for bit, scenes recorded as parsed (or marked as not reproducible), and
// whole records read back.
#include <catch2/catch.hpp>

#include <sys/stat.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <fstream>
#include <random>
#include <sstream>

#include <nlohmann/json.hpp>

#include "layerjkr/error.hpp"
#include "layerjkr/provenance.hpp"
#include "support/temp_dir.hpp"

using namespace layerjkr;

namespace {

std::string sha256sum(const std::string& path) {
  const std::string cmd = "sha256sum '" + path + "' 2>/dev/null";
  std::FILE* p = ::popen(cmd.c_str(), "r");
  if (!p) return "";
  char buf[128] = {};
  const std::size_t n = std::fread(buf, 1, 64, p);
  ::pclose(p);
  return std::string(buf, n);
}

std::string write(const std::string& name, const std::string& bytes) {
  const std::string path = test::scratch().file(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

std::uint64_t bits(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

const std::string kScene = std::string(LAYERJKR_SOURCE_DIR) + "/data/scenes/hydrogel_film_two_term.json";

}  // namespace

TEST_CASE("SHA-256 gives the FIPS 180-2 example digests", "[provenance]") {
  CHECK(sha256_hex("", 0) == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abc", 3) == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  const std::string m448 = "abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq";
  CHECK(m448.size() * 8 == 448);
  CHECK(sha256_hex(m448.data(), m448.size()) == "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  const std::string million(1000000, 'a');
  CHECK(sha256_hex(million.data(), million.size()) ==
        "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // The same message as a file: the streamed digest and its size.
  const InputRecord r = record_file(write("million_a", million));
  CHECK(r.error.empty());
  CHECK(r.size == 1000000);
  CHECK(r.sha256 == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("a file hashed in chunks equals coreutils' sha256sum at and around the chunk size", "[provenance]") {
  if (sha256sum(kScene).size() != 64) {
    test::report_skip("sha256sum (coreutils) is not available");
    return;
  }
  std::mt19937_64 rng(7);
  const std::size_t chunk = std::size_t{1} << 20;
  for (std::size_t size : {std::size_t{0}, std::size_t{1}, chunk - 1, chunk, chunk + 1, 3 * chunk + 12345}) {
    std::string bytes(size, '\0');
    for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
    const std::string path = write("random_" + std::to_string(size), bytes);
    const InputRecord r = record_file(path);
    INFO("size " << size);
    CHECK(r.size == size);
    CHECK(r.sha256 == sha256sum(path));
    CHECK(r.sha256 == sha256_hex(bytes.data(), bytes.size()));
    CHECK(r.path.front() == '/');  // recorded absolute
  }
}

TEST_CASE("record_file names what is not a regular file without opening it, verify_input names both hashes",
          "[provenance]") {
  const std::string fifo = test::scratch().file("fifo.csv");
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  const InputRecord f = record_file(fifo);  // would block forever if it opened the FIFO
  CHECK(f.sha256.empty());
  CHECK(f.error.find("FIFO") != std::string::npos);
  const InputRecord missing = record_file(test::scratch().file("nothing.csv"));
  CHECK(missing.sha256.empty());
  CHECK_FALSE(missing.error.empty());

  const std::string path = write("data.csv", "delta,P\n1,2\n");
  const InputRecord r = record_file(path);
  CHECK_NOTHROW(verify_input(r));
  write("data.csv", "delta,P\n1,3\n");
  try {
    verify_input(r);
    FAIL("a changed file was accepted");
  } catch (const InputError& e) {
    const std::string what = e.what();
    CHECK(what.find(r.path) == 0);
    CHECK(what.find(r.sha256) != std::string::npos);
    CHECK(what.find(sha256_hex("delta,P\n1,3\n", 12)) != std::string::npos);
  }
  std::remove(path.c_str());
  CHECK_THROWS_WITH(verify_input(r), Catch::Contains(r.path) && Catch::Contains("missing") && Catch::Contains(r.sha256));
}

TEST_CASE("every option survives the JSON round trip bit for bit", "[provenance]") {
  // Every field away from its default (the static_asserts in src/provenance/provenance.cpp
  // point here when a field is added): a field the table forgets comes back as its default.
  FitOptions o;
  o.free = {FitParameter::w, FitParameter::E, FitParameter::P0};
  o.branch = Branch::all;
  o.retract_control = RetractControl::cantilever;
  o.cantilever_stiffness = 0.1 + 0.2;
  o.exclusion_sigmas = 1.0 / 3.0;
  o.force_noise = 1.0 / 7.0;
  o.radius_noise = 2.0 / 7.0;
  o.errors_in_displacement = true;
  o.displacement_noise = 3.0 / 7.0;
  o.baseline = Baseline::tilt;
  o.remove_offset = false;
  o.retract_window = RetractWindow::force_fraction;
  o.window_fraction = 0.7000000000000001;
  o.loss = LossType::cauchy;
  o.loss_scale = 4.9406564584124654e-324;  // the smallest subnormal
  o.max_iterations = 77;
  o.function_tolerance = 1.7976931348623157e308;
  o.parameter_tolerance = 2.2250738585072014e-308;
  o.gradient_tolerance = 1e-300;
  o.extra_starts = 5;
  o.compute_covariance = false;
  o.correlation_limit = 0.95;
  o.table_points_per_decade = 13;
  o.trace = true;
  o.contact_point = ContactPointMethod::rov;
  o.indentation_range = Interval{-1e-7, 0.1 + 0.2};
  o.force_range = Interval{0.0, 1.0 / 3.0};
  o.baseline_window = Interval{-3e-6, -2.5e-6};
  o.bounds = {{FitParameter::E, 1.0 / 3.0, std::numeric_limits<double>::infinity()}, {FitParameter::w, -0.0, 0.1 + 0.2}};
  const std::string text = to_json(o);
  CHECK(nlohmann::json::parse(text).size() == 29);  // one key per field
  const FitOptions b = fit_options_from_json(text);
  CHECK(b.free == o.free);
  CHECK(b.branch == o.branch);
  CHECK(b.retract_control == o.retract_control);
  REQUIRE(b.cantilever_stiffness);
  CHECK(bits(*b.cantilever_stiffness) == bits(*o.cantilever_stiffness));
  CHECK(bits(b.exclusion_sigmas) == bits(o.exclusion_sigmas));
  REQUIRE(b.force_noise);
  REQUIRE(b.radius_noise);
  CHECK(bits(*b.force_noise) == bits(*o.force_noise));
  CHECK(bits(*b.radius_noise) == bits(*o.radius_noise));
  CHECK(b.errors_in_displacement);
  REQUIRE(b.displacement_noise);
  CHECK(bits(*b.displacement_noise) == bits(*o.displacement_noise));
  CHECK(b.baseline == o.baseline);
  CHECK(b.remove_offset == o.remove_offset);
  CHECK(b.retract_window == o.retract_window);
  CHECK(bits(b.window_fraction) == bits(o.window_fraction));
  CHECK(b.loss == o.loss);
  CHECK(bits(b.loss_scale) == bits(o.loss_scale));
  CHECK(b.max_iterations == o.max_iterations);
  CHECK(bits(b.function_tolerance) == bits(o.function_tolerance));
  CHECK(bits(b.parameter_tolerance) == bits(o.parameter_tolerance));
  CHECK(bits(b.gradient_tolerance) == bits(o.gradient_tolerance));
  CHECK(b.extra_starts == o.extra_starts);
  CHECK(b.compute_covariance == o.compute_covariance);
  CHECK(bits(b.correlation_limit) == bits(o.correlation_limit));
  CHECK(b.table_points_per_decade == o.table_points_per_decade);
  CHECK(b.trace == o.trace);
  CHECK(b.contact_point == o.contact_point);
  for (const auto& [got, want] : {std::pair{b.indentation_range, o.indentation_range},
                                  std::pair{b.force_range, o.force_range},
                                  std::pair{b.baseline_window, o.baseline_window}}) {
    REQUIRE(got);
    CHECK(bits(got->first) == bits(want->first));
    CHECK(bits(got->second) == bits(want->second));
  }
  REQUIRE(b.bounds.size() == 2);
  for (std::size_t k = 0; k < 2; ++k) {
    CHECK(b.bounds[k].parameter == o.bounds[k].parameter);
    CHECK(bits(b.bounds[k].lower) == bits(o.bounds[k].lower));
    CHECK(bits(b.bounds[k].upper) == bits(o.bounds[k].upper));
  }
  CHECK(to_json(b) == text);

  CsvOptions c;
  c.length_unit = 1e-9;
  c.force_unit = 1e-12;
  c.spring_constant = 0.04312345678901234;
  c.sensitivity = 6.1234567890123e-8;
  c.z_sign = -1.0;
  c.deflection_sign = -1.0;
  c.curve = 3;
  c.max_bytes = (std::size_t{1} << 40) + 1;
  c.max_rows = 12345;
  const std::string ctext = to_json(c);
  CHECK(nlohmann::json::parse(ctext).size() == 9);
  const CsvOptions d = csv_options_from_json(ctext);
  CHECK(bits(d.length_unit) == bits(c.length_unit));
  CHECK(bits(d.force_unit) == bits(c.force_unit));
  CHECK(bits(d.spring_constant) == bits(c.spring_constant));
  CHECK(bits(d.sensitivity) == bits(c.sensitivity));
  CHECK(d.z_sign == c.z_sign);
  CHECK(d.deflection_sign == c.deflection_sign);
  CHECK(d.curve == c.curve);
  CHECK(d.max_bytes == c.max_bytes);
  CHECK(d.max_rows == c.max_rows);
  CHECK(to_json(d) == ctext);
}

TEST_CASE("doubles of every magnitude come back with the same bits", "[provenance]") {
  // 20 000 random bit patterns of finite positive doubles (subnormals included) in a field that
  // takes any of them.
  std::mt19937_64 rng(2026);
  FitOptions o;
  o.free = {FitParameter::E};
  std::size_t tried = 0;
  while (tried < 20000) {
    const std::uint64_t b = rng() & 0x7fffffffffffffffULL;
    double x;
    std::memcpy(&x, &b, sizeof x);
    if (!(x > 0.0) || !std::isfinite(x)) continue;
    ++tried;
    o.function_tolerance = x;
    const double back = fit_options_from_json(to_json(o)).function_tolerance;
    if (bits(back) != b) FAIL("bits " << b << " came back as " << bits(back));
  }
  SUCCEED("20 000 doubles round-tripped");
}

TEST_CASE("options read back strictly: unknown keys and wrong types are named, missing keys default",
          "[provenance]") {
  CHECK_THROWS_WITH(fit_options_from_json(R"({"free": ["E"], "contact_pint": "rov"})", "R.json"),
                    Catch::Contains("R.json: unknown option 'contact_pint'"));
  CHECK_THROWS_WITH(fit_options_from_json(R"({"free": ["E"], "max_iterations": 2.5})", "R.json"),
                    Catch::Contains("R.json: max_iterations = 2.5 is invalid; expected an integer"));
  CHECK_THROWS_WITH(fit_options_from_json(R"({"free": ["Q"]})", "R.json"), Catch::Contains("R.json: free[0]"));
  CHECK_THROWS_WITH(fit_options_from_json(R"({"free": ["E"], "branch": "sideways"})", "R.json"),
                    Catch::Contains("sideways") && Catch::Contains("approach"));
  CHECK_THROWS_AS(fit_options_from_json(R"({"free": []})", "R.json"), DomainError);  // validated
  CHECK_THROWS_WITH(csv_options_from_json("{\"z_sign\": ", "R.json"), Catch::Contains("R.json: not valid JSON"));
  const FitOptions d = fit_options_from_json(R"({"free": ["E", "w"]})");
  CHECK(to_json(d) == [] {
    FitOptions o;
    o.free = {FitParameter::E, FitParameter::w};
    return to_json(o);
  }());
}

TEST_CASE("a scene file is recorded as its parsed JSON with the file's SHA-256", "[provenance]") {
  const Scene s = load_scene(kScene);
  std::ifstream f(kScene, std::ios::binary);
  std::stringstream text;
  text << f.rdbuf();
  const auto r = nlohmann::json::parse(scene_json(s));
  CHECK(r["json"] == nlohmann::json::parse(text.str()));
  CHECK(r["file"] == kScene);
  CHECK(r["sha256"] == sha256_hex(text.str().data(), text.str().size()));
  const std::string independent = sha256sum(kScene);
  if (independent.size() == 64) CHECK(r["sha256"] == independent);
  CHECK_FALSE(r.contains("note"));
  CHECK(r["description"]["model"] == "two_term");

  // Changed after parsing: the JSON no longer describes it.
  Scene changed = s;
  changed.medium.E *= 1.0000000000000002;
  const auto c = nlohmann::json::parse(scene_json(changed));
  CHECK(c["json"].is_null());
  CHECK(c["note"].get<std::string>().find("changed in code") != std::string::npos);
  // Built in code: described only.
  Scene built;
  built.profile = s.profile;
  built.medium = s.medium;
  built.model = s.model;
  const auto b = nlohmann::json::parse(scene_json(built));
  CHECK(b["json"].is_null());
  CHECK(b["file"].is_null());
  CHECK(b["note"].get<std::string>().find("built in code") != std::string::npos);
  CHECK(b["description"]["medium"]["E"] == s.medium.E);

  // A stack changed in a lower layer (or its substrate) after parsing is stale too.
  const Scene stack = parse_scene(R"({"indenter": {"shape": "paraboloid", "R": 1e-3},
      "medium": {"type": "layers", "layers": [{"E": 3e6, "nu": 0.3, "h": 1e-4}, {"E": 3e8, "nu": 0.3, "h": 1.9e-3}],
                 "base": {"E": 1e9, "nu": 0.25}}, "model": "exact"})");
  CHECK_FALSE(nlohmann::json::parse(scene_json(stack))["json"].is_null());
  Scene lower = stack;
  lower.medium.stack.layers[1].h *= 2.0;
  CHECK(nlohmann::json::parse(scene_json(lower))["json"].is_null());
  Scene substrate = stack;
  substrate.medium.stack.substrate->nu = 0.3;
  CHECK(nlohmann::json::parse(scene_json(substrate))["json"].is_null());
}

TEST_CASE("a provenance record reads back to the same scene, options and inputs", "[provenance]") {
  const Scene s = load_scene(kScene);
  FitOptions o;
  o.free = {FitParameter::E, FitParameter::delta0};
  o.window_fraction = 0.3;
  CsvOptions c;
  c.length_unit = 1e-9;
  const std::vector<InputRecord> in{record_file(write("curve.csv", "delta,P\n0,0\n")),
                                    record_bytes("delta (float64 array)", "12345678", 8)};
  const std::string text = provenance_json(s, o, &c, in);
  const auto j = nlohmann::json::parse(text);
  CHECK(j["layerjkr_version"] == version());
  const ProvenanceRecord r = parse_provenance(text, "record");
  CHECK(r.version == version());
  REQUIRE(r.scene);
  CHECK(scene_json(*r.scene) == scene_json(s));
  CHECK(to_json(r.options) == to_json(o));
  REQUIRE(r.csv);
  CHECK(to_json(*r.csv) == to_json(c));
  REQUIRE(r.inputs.size() == 2);
  CHECK(r.inputs[0].path == in[0].path);
  CHECK(r.inputs[0].sha256 == in[0].sha256);
  CHECK(r.inputs[1].size == 8);
  CHECK(provenance_json(*r.scene, r.options, &*r.csv, r.inputs) == text);
  // Without a CSV and with a scene built in code: no csv, no scene to rerun, and a note why.
  Scene built = s;
  built.origin = {};
  const ProvenanceRecord n = parse_provenance(provenance_json(built, o, nullptr, {}), "record");
  CHECK_FALSE(n.scene);
  CHECK_FALSE(n.csv);
  CHECK(n.scene_note.find("built in code") != std::string::npos);
  CHECK_THROWS_WITH(parse_provenance("{}", "R.json"), Catch::Contains("R.json: has no 'layerjkr_version'"));
}
