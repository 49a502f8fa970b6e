// fit-map --report: the page's embedded data equal the results table cell for cell (numbers
// bit for bit), a report directory can be written again, and a bad --report is one line with
// exit 2 before any fitting (no table written).
#include <catch2/catch.hpp>

#include <filesystem>

#include <nlohmann/json.hpp>

#include "support/cli_support.hpp"

using namespace test::cli;
using nlohmann::json;
namespace fs = std::filesystem;

namespace {

// The cells of one CSV line (quoted cells as csv_cell writes them).
std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quoted) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (c == '"') {
        quoted = false;
      } else {
        out.back() += c;
      }
    } else if (c == '"') {
      quoted = true;
    } else if (c == ',') {
      out.emplace_back();
    } else {
      out.back() += c;
    }
  }
  return out;
}

json page_data(const std::string& html) {
  const std::string open = "<script type=\"application/json\" id=\"layerjkr-data\">";
  const std::size_t a = html.find(open);
  REQUIRE(a != std::string::npos);
  const std::size_t b = html.find("</script>", a);
  return json::parse(html.substr(a + open.size(), b - a - open.size()));
}

fs::path inputs(const std::string& name) {
  const fs::path dir = unique(name);
  fs::create_directories(dir);
  for (int i = 0; i < 3; ++i) fs::create_symlink(sample_curve(), dir / ("c" + std::to_string(i) + ".csv"));
  std::ofstream(dir / "d_bad.csv") << "delta,P\n1,oops\n";
  return dir;
}

}  // namespace

TEST_CASE("fit-map --report: the page's data are the table's values, cell for cell", "[cli][report]") {
  const fs::path in = inputs("in");
  const std::string out = unique("results.csv"), dir = unique("report");
  const Run r = run("fit-map " + in.string() + sample_fit_flags() + " --jobs 2 --out " + out + " --report " + dir);
  INFO(r.err);
  REQUIRE(r.code == 3);  // one curve of the inputs fails
  CHECK(r.err.find("report written to " + dir + "/index.html") != std::string::npos);
  const auto rows = lines(slurp(out));
  REQUIRE(rows.size() == 5);
  const std::string html = slurp(dir + "/index.html");
  const json d = page_data(html);
  const json& c = d["columns"];
  REQUIRE(d["count"] == 4);
  const auto head = cells(rows[0]);
  std::size_t compared = 0;
  for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
    const auto row = cells(rows[i + 1]);
    REQUIRE(row.size() == head.size());
    for (std::size_t k = 0; k < head.size(); ++k) {
      INFO("row " << i << " column " << head[k] << " cell " << row[k]);
      const json& v = c[head[k]][i];
      if (head[k] == "file" || head[k] == "status" || head[k] == "error" || head[k] == "model" ||
          head[k] == "identifiability" || head[k] == "quality") {
        CHECK((v.is_null() ? std::string() : v.get<std::string>()) == row[k]);
      } else if (head[k] == "warnings" || head[k] == "notices") {  // the table joins the list in one cell
        std::string joined;
        for (const auto& m : v) joined += (joined.empty() ? "" : " | ") + m.get<std::string>();
        CHECK(joined == row[k]);
      } else if (row[k].empty()) {
        CHECK(v.is_null());
      } else {
        REQUIRE(v.is_number());
        CHECK(v.get<double>() == std::stod(row[k]));
        ++compared;
      }
    }
  }
  CHECK(compared > 3 * 10);
  CHECK(c["quality"][3] == "failed");
  CHECK(c["error"][3].get<std::string>().find("oops") != std::string::npos);
  // The fitted curves are kept (thinned) for the page; the failed one has none.
  for (int i = 0; i < 3; ++i) CHECK(d["curves"][i]["n"].get<int>() > 0);
  CHECK(d["curves"][3].is_null());
  CHECK(d["views"].size() == 1);
  CHECK(d["views"][0]["kind"] == "index");
  // The same directory again: an earlier report is replaced.
  const Run again = run("fit-map " + in.string() + sample_fit_flags() + " --jobs 2 --out " + out + " --report " + dir);
  CHECK(again.code == 3);
  CHECK(fs::is_regular_file(dir + "/index.html"));
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 1);
  // The table may go beside the page, again and again.
  for (int k = 0; k < 2; ++k) {
    const Run beside =
        run("fit-map " + in.string() + sample_fit_flags() + " --out " + dir + "/results.csv --report " + dir);
    INFO(beside.err);
    CHECK(beside.code == 3);
  }
  CHECK(lines(slurp(dir + "/results.csv")).size() == 5);
  CHECK(std::distance(fs::directory_iterator(dir), fs::directory_iterator()) == 3);  // + the table's record
}

TEST_CASE("fit-map --report refuses a file, an unwritable place, a directory of other files, and --resume",
          "[cli][report][errors]") {
  const fs::path in = inputs("in_bad");
  const std::string flags = sample_fit_flags() + " --jobs 1 --out ";
  auto refused = [&](const std::string& report, const std::string& extra, const std::string& expected) {
    const std::string out = unique("never.csv");
    const Run r = run("fit-map " + in.string() + flags + out + " --report " + report + extra);
    INFO(r.err);
    CHECK(r.code == 2);
    CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
    CHECK(r.err.find(expected) != std::string::npos);
    CHECK(!fs::exists(out));  // refused before the table, let alone a fit
  };
  const std::string file = write_file("plain.txt", "x");
  refused(file, "", "--report " + file + ": exists and is not a directory");
  refused(file + "/sub", "", "--report " + file + "/sub: cannot create the directory");
  const std::string busy = unique("busy");
  fs::create_directories(busy);
  std::ofstream(busy + "/keep.me") << "mine";
  refused(busy, "", "is not a previous report (it holds keep.me)");
  CHECK(slurp(busy + "/keep.me") == "mine");
  refused(unique("fresh"), " --resume", "--report needs every fit, and --resume does not redo the earlier ones");
}
