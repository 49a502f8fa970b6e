// README runs as written: every `$ build/bin/layerjkr ...` example and the main job's fit run in
// order, as a reader runs them from the repository (a scratch directory whose data/ is the files
// the repository ships), exit 0, and print what README shows (each shown line, up to a "...",
// begins a printed line: its text exactly, its numbers to 1e-4).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <cstdlib>
#include <string>
#include <vector>

#include "support/cli_support.hpp"

using namespace test::cli;

namespace {

struct Example {
  std::string args;                 // after build/bin/layerjkr
  std::vector<std::string> shown;   // the output README prints for it, trimmed
};

std::string trimmed(const std::string& s) {
  const auto b = s.find_first_not_of(' ');
  const auto e = s.find_last_not_of(' ');
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

// The indented lines from `from` on, up to the first that is not indented or is another example.
std::vector<std::string> block(const std::vector<std::string>& lines, std::size_t from) {
  std::vector<std::string> out;
  for (std::size_t k = from; k < lines.size(); ++k) {
    if (lines[k].rfind("    ", 0) != 0 || lines[k].rfind("    $", 0) == 0) break;
    out.push_back(trimmed(lines[k]));
  }
  return out;
}

std::vector<Example> readme_examples() {
  const std::vector<std::string> lines = test::cli::lines(slurp(std::string(LAYERJKR_SOURCE_DIR) + "/README.md"));
  const std::string prompt = "    $ build/bin/layerjkr ", main_job = "&& build/bin/layerjkr ";
  std::vector<Example> out;
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (lines[k].rfind(prompt, 0) == 0) {
      out.push_back({lines[k].substr(prompt.size()), block(lines, k + 1)});
    } else if (const auto at = lines[k].find(main_job); at != std::string::npos && lines[k].rfind("    ", 0) == 0) {
      // The main job: its output is the block after "It prints".
      std::size_t j = k + 1;
      while (j < lines.size() && lines[j].rfind("It prints", 0) != 0) ++j;
      out.push_back({lines[k].substr(at + main_job.size()), j + 2 < lines.size() ? block(lines, j + 2) : std::vector<std::string>{}});
    }
  }
  return out;
}

// Whether `line` begins with `expected`, text exactly and numbers within 1e-4 relative: README
// shows fits' results to 6 digits, whose last ones may move with another CPU's libm or
// vectorisation; the text around them, and every number to 4 digits, may not.
bool shows(const std::string& line, const std::string& expected) {
  const auto number_at = [](const std::string& s, std::size_t i) {
    const auto digit = [&](std::size_t k) { return k < s.size() && std::isdigit(static_cast<unsigned char>(s[k])); };
    const bool after_word = i > 0 && (std::isalnum(static_cast<unsigned char>(s[i - 1])) || s[i - 1] == '_');
    return !after_word && (digit(i) || ((s[i] == '-' || s[i] == '.') && (digit(i + 1) || (s[i + 1] == '.' && digit(i + 2)))));
  };
  std::size_t i = 0, j = 0;
  while (j < expected.size()) {
    if (i >= line.size()) return false;
    if (number_at(expected, j) && number_at(line, i)) {
      char *end_e = nullptr, *end_l = nullptr;
      const double e = std::strtod(expected.c_str() + j, &end_e), l = std::strtod(line.c_str() + i, &end_l);
      if (!(std::abs(e - l) <= 1e-4 * std::abs(e))) return false;
      j = static_cast<std::size_t>(end_e - expected.c_str());
      i = static_cast<std::size_t>(end_l - line.c_str());
    } else if (expected[j++] != line[i++]) {
      return false;
    }
  }
  return true;
}

}  // namespace

TEST_CASE("README's examples run as written and print what README shows", "[cli][readme]") {
  const std::vector<Example> examples = readme_examples();
  REQUIRE(examples.size() >= 5);  // the main job and the quick starts
  // In order, in one scratch directory whose data/ is the bundled data, as a reader runs them from
  // the repository: a later example reads what an earlier one wrote, and nothing lands in the tree.
  const std::filesystem::path dir = fresh_dir("readme");
  std::filesystem::create_directory_symlink(std::filesystem::path(LAYERJKR_SOURCE_DIR) / "data", dir / "data");
  for (const Example& e : examples) {
    INFO("layerjkr " << e.args);
    const Run r = run("cd " + dir.string() + " && " + cli_path() + " " + e.args, true);
    INFO(r.err);
    CHECK(r.code == 0);
    const std::string printed = r.out + r.err;
    for (const std::string& line : e.shown) {
      const std::string expected = trimmed(line.substr(0, line.find("...")));
      if (expected.empty()) continue;
      INFO("README shows: " << line << "\nprinted:\n" << printed);
      const std::vector<std::string> printed_lines = lines(printed);
      CHECK(std::any_of(printed_lines.begin(), printed_lines.end(),
                        [&](const std::string& p) { return shows(trimmed(p), expected); }));
    }
  }
}
