// Help that matches the docs (#43): every option each verb's --help lists is documented in README.md
// or docs/*.md, every documented `layerjkr VERB ... --option` is one that verb takes, and what a
// verb needs is marked REQUIRED in its help. The verbs come from `layerjkr --help`, so a new verb
// or option is covered without editing this file.
#include <catch2/catch.hpp>

#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "support/cli_support.hpp"

using namespace test::cli;

namespace {

// The subcommands `layerjkr --help` lists, in order.
std::vector<std::string> verbs() {
  const Run r = run("--help");
  std::vector<std::string> out;
  bool in_list = false;
  for (const std::string& line : lines(r.out)) {
    if (line.rfind("Subcommands:", 0) == 0) {
      in_list = true;
      continue;
    }
    std::smatch m;
    if (in_list && std::regex_search(line, m, std::regex("^  ([a-z][a-z-]*) ")))
      out.push_back(m[1]);
    else if (in_list && !line.empty() && line[0] != ' ')
      break;
  }
  return out;
}

// The long options a help text lists (each at the start of its line, after an optional -x,).
std::set<std::string> help_options(const std::string& help) {
  std::set<std::string> out;
  const std::regex option("^\\s+(?:-[a-zA-Z],)?(--[A-Za-z][A-Za-z0-9-]*)");
  for (const std::string& line : lines(help)) {
    std::smatch m;
    if (std::regex_search(line, m, option) && m[1] != "--help") out.insert(m[1]);
  }
  return out;
}

// Whether `option` appears in `docs` as a whole option name (not the start of a longer one).
bool documented(const std::string& docs, const std::string& option) {
  for (std::size_t at = docs.find(option); at != std::string::npos; at = docs.find(option, at + 1)) {
    const std::size_t end = at + option.size();
    const bool whole_end = end >= docs.size() || !(std::isalnum(static_cast<unsigned char>(docs[end])) || docs[end] == '-' || docs[end] == '_');
    if (whole_end) return true;
  }
  return false;
}

// Each `layerjkr VERB ...` command in `doc` (continuation lines joined) with the options it uses
// that VERB's help does not list: "VERB --option | the line".
std::vector<std::string> unknown_options(std::string doc, const std::map<std::string, std::set<std::string>>& by_verb) {
  doc = std::regex_replace(doc, std::regex("\\\\\\n"), " ");
  std::vector<std::string> out;
  const std::regex command("layerjkr ([a-z][a-z-]*)"), option("(^|[^A-Za-z0-9-])(--[A-Za-z][A-Za-z0-9-]*)");
  for (const std::string& line : lines(doc)) {
    for (auto it = std::sregex_iterator(line.begin(), line.end(), command); it != std::sregex_iterator(); ++it) {
      const auto verb = by_verb.find((*it)[1]);
      if (verb == by_verb.end()) continue;
      // The command runs to the next command, pipe, '&&', ';', ')' or backtick.
      std::string rest = line.substr(static_cast<std::size_t>(it->position() + it->length()));
      const std::size_t stop = rest.find_first_of("|;)`");
      rest = rest.substr(0, std::min(stop, std::min(rest.find("&&"), rest.find("layerjkr "))));
      for (auto o = std::sregex_iterator(rest.begin(), rest.end(), option); o != std::sregex_iterator(); ++o) {
        const std::string name = (*o)[2];
        if (name != "--help" && name != "--version" && !verb->second.count(name))
          out.push_back(verb->first + " " + name + " | " + line);
      }
    }
  }
  return out;
}

std::string all_docs() {
  const std::filesystem::path root(LAYERJKR_SOURCE_DIR);
  std::string text = slurp((root / "README.md").string());
  for (const auto& entry : std::filesystem::directory_iterator(root / "docs"))
    if (entry.path().extension() == ".md") text += "\n" + slurp(entry.path().string());
  return text;
}

std::map<std::string, std::set<std::string>> options_by_verb() {
  std::map<std::string, std::set<std::string>> out;
  for (const std::string& v : verbs()) out[v] = help_options(run(v + " --help").out);
  return out;
}

}  // namespace

TEST_CASE("the checks find what they look for", "[cli][help]") {
  const std::set<std::string> found = help_options("Options:\n  -h,--help   Print\n  --free TEXT   x\n  --P0 FLOAT  y\n    --not-an-option in text\n");
  CHECK(found == std::set<std::string>{"--free", "--P0", "--not-an-option"});
  CHECK(documented("use `--free E,w` here", "--free"));
  CHECK_FALSE(documented("use `--free-fraction 0.5`", "--free"));
  const std::map<std::string, std::set<std::string>> by_verb{{"fit", {"--free", "--scene"}}, {"export", {"--out"}}};
  // A deliberately broken doc: an option fit does not take, on a continued line, beside a pipe.
  const std::vector<std::string> bad =
      unknown_options("    layerjkr fit a.csv --scene s.json \\\n      --frees E | layerjkr export f --out x\n", by_verb);
  REQUIRE(bad.size() == 1);
  CHECK(bad[0].rfind("fit --frees", 0) == 0);
  CHECK(unknown_options("`layerjkr fit --scene s.json --free E` and `--out` of export", by_verb).empty());
}

TEST_CASE("every option of every verb's help is documented, and every documented option exists", "[cli][help]") {
  const auto by_verb = options_by_verb();
  REQUIRE(by_verb.size() >= 7);  // curve, summary, fit, fit-map, export, discrete, simulate
  const std::string docs = all_docs();
  for (const auto& [verb, options] : by_verb) {
    CHECK(options.size() >= 2);
    for (const std::string& o : options) {
      INFO("layerjkr " << verb << " " << o << ": in --help but in neither README.md nor docs/*.md");
      CHECK(documented(docs, o));
    }
  }
  const std::vector<std::string> unknown = unknown_options(docs, by_verb);
  for (const std::string& u : unknown) INFO("documented but not in that verb's --help: " << u);
  CHECK(unknown.empty());
}

TEST_CASE("what a verb needs is marked REQUIRED in its help", "[cli][help]") {
  for (const std::string& verb : verbs()) {
    // Run bare, each verb names the first thing it needs, on one line, and exits 2.
    const Run bare = run(verb);
    INFO("layerjkr " << verb << ": " << bare.err);
    CHECK(bare.code == 2);
    CHECK(count_lines(bare.err) == 1);
    std::smatch m;
    REQUIRE(std::regex_search(bare.err, m, std::regex("layerjkr: (\\S+) is required")));
    const std::string needed = m[1];
    // The option's whole entry: its description may wrap onto the next lines.
    const std::string help = run(verb + " --help").out;
    const std::size_t at = help.find("\n  " + needed + " ");
    REQUIRE(at != std::string::npos);
    const std::size_t next = std::min(help.find("\n  -", at + 1), help.find("\n\n", at + 1));
    const bool marked = help.substr(at, next - at).find("REQUIRED") != std::string::npos;
    INFO(needed << " is required but not marked REQUIRED in `layerjkr " << verb << " --help`");
    CHECK(marked);
  }
}
