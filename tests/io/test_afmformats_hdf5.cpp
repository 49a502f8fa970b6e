// afmformats' HDF5 export (src/io/afmformats_hdf5.cpp, the target layerjkr_hdf5 the CLI links):
// its test file read to the value afmformats' test_fmt_hdf5.py asserts, the columns checked
// against the same curve's tab export, and what is not afmformats' refused by name.
#include <catch2/catch.hpp>

#include <hdf5.h>

#include <cmath>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "support/temp_dir.hpp"
#include "support/test_support.hpp"

using namespace layerjkr;

namespace {
const std::string kDir = std::string(LAYERJKR_SOURCE_DIR) + "/tests/data/instrument/";
const std::string kH5 = kDir + "fmt-hdf5-fd_version_0.13.3.h5";
}  // namespace

TEST_CASE("afmformats HDF5: refused until a program enables it, then read to afmformats' values", "[io][afmformats]") {
  // The library alone links no libhdf5: the refusal says where the file is read.
  CHECK_THAT(test::input_error([] { read_instrument_file(kH5); }),
             Catch::Contains("not read by this program") && Catch::Contains("layerjkr export FILE.h5"));
  enable_hdf5_reading();
  REQUIRE(instrument_format(kH5) == InstrumentFormat::afmformats_hdf5);
  const InstrumentFile f = read_instrument_file(kH5);
  CHECK(f.software == "afmformats 0.13.3");
  REQUIRE(f.curves.size() == 1);
  const InstrumentCurve& c = f.curves[0];
  CHECK(c.spring_constant == Approx(0.0223007).epsilon(1e-5));
  REQUIRE(c.segments.size() == 2);
  CHECK(c.segments[0].style == SegmentStyle::extend);
  CHECK(c.segments[1].style == SegmentStyle::retract);
  const CurveData d = to_curve_data(c, kH5);
  REQUIRE(d.size() == 7796);
  CHECK(d.P[2000] == -7.038311459845539e-10);  // afmformats: fdat["force"][2000]
  // The same JPK curve as afmformats' tab export, "cropped compared to h5" (its test says) and
  // written to 8 digits: the tab's 4 029 samples are the HDF5 file's 2 249 to 6 277.
  const CurveData tab = read_curve_csv(kDir + "fmt-tab-fd_version_0.13.3.tab");
  REQUIRE(tab.size() == 4029);
  const std::size_t offset = 2249;
  for (std::size_t i = 0; i < tab.size(); i += 97) {
    INFO(i);
    CHECK(tab.P[i] == Approx(d.P[i + offset]).epsilon(1e-7));
    CHECK(tab.delta[i] == Approx(d.delta[i + offset]).epsilon(1e-7));
  }
}

TEST_CASE("afmformats HDF5: files afmformats did not write are refused by name", "[io][afmformats]") {
  enable_hdf5_reading();
  test::TempDir dir;
  const std::string other = dir.file("asylum.h5");
  const hid_t file = H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  REQUIRE(file >= 0);
  H5Fclose(file);
  CHECK_THAT(test::input_error([&] { read_instrument_file(other); }),
             Catch::Contains("an HDF5 file that afmformats did not write") &&
                 Catch::Contains("LineLLLLPointPPPP<Channel>.ibw"));
  const std::string text = dir.file("text.h5");
  std::ofstream(text) << "delta,P\n";
  CHECK_THAT(test::input_error([&] { read_instrument_file(text); }), Catch::Contains("text.h5: afmformats HDF5 export: is not an HDF5 file"));
}
