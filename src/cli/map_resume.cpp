// fit-map --resume: earlier rows matched by file identity (map_resume.hpp).
#include "map_resume.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "layerjkr/error.hpp"
#include "layerjkr/text.hpp"
#include "results_table.hpp"

namespace layerjkr::cli {

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

std::string row_curve(int curve) { return curve >= 0 ? std::to_string(curve) : std::string(); }

// An absolute, lexically normal path for a name (as record_file makes them).
std::string absolute_path(const std::string& name) {
  std::error_code ec;
  const fs::path p = fs::absolute(name, ec);
  return ec ? name : p.lexically_normal().string();
}

}  // namespace

std::string file_key(const std::string& path, const std::string& sha256) {
  std::error_code ec;
  const fs::path canonical = fs::weakly_canonical(path, ec);
  return (ec ? path : canonical.string()) + '\n' + sha256;
}

json EarlierRows::read(const std::string& out, const std::string& header, const std::function<json()>& record) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return json();
  std::ifstream f(out, std::ios::binary);
  std::stringstream text;
  text << f.rdbuf();
  if (!f) throw InputError("--resume: cannot read " + out);
  std::vector<ResultsRow> rows = parse_results_table(text.str(), header, out);
  if (rows.empty()) return json();
  json earlier_record = record();  // returned: not const, so it moves
  // Which file each name the earlier run gave stood for (its record's inputs: the name as given,
  // the absolute path and the SHA-256, all escaped as written).
  std::map<std::string, std::string> by_name, sha_by_path;
  for (const auto& in : earlier_record.value("inputs", json::array())) {
    if (!in.is_object() || !in.contains("path") || !in["path"].is_string()) continue;
    const std::string path = unescape_bytes(in["path"].get<std::string>());
    const std::string sha = in.value("sha256", json()).is_string() ? in["sha256"].get<std::string>() : std::string();
    sha_by_path[path] = sha;
    if (in.contains("named") && in["named"].is_string()) by_name[in["named"].get<std::string>()] = file_key(path, sha);
  }
  for (ResultsRow& r : rows) {
    std::string key;
    if (const auto found = by_name.find(r.file); found != by_name.end()) {
      key = found->second;
    } else {  // a record without the names as given (layerjkr 0.1): the cell is the path
      const std::string path = absolute_path(unescape_bytes(r.file));
      const auto sha = sha_by_path.find(path);
      key = file_key(path, sha == sha_by_path.end() ? std::string() : sha->second);
    }
    waiting_[{key, r.curve}].push_back(rows_.size());
    rows_.push_back({std::move(r.line), r.status == "error", false});
  }
  return earlier_record;
}

void EarlierRows::set_inputs(const std::vector<std::string>& named, const std::vector<InputRecord>& hashed) {
  for (std::size_t k = 0; k < named.size() && k < hashed.size(); ++k)
    now_[named[k]] = file_key(hashed[k].path, hashed[k].sha256);
}

EarlierRows::Key EarlierRows::key_now(const std::string& named, int curve) const {
  const auto found = now_.find(named);
  return {found == now_.end() ? file_key(absolute_path(named), "") : found->second, row_curve(curve)};
}

bool EarlierRows::claim(const std::string& named, int curve) {
  const std::lock_guard<std::mutex> guard(lock_);
  const Key key = key_now(named, curve);
  const auto found = waiting_.find(key);
  if (found == waiting_.end() || found->second.empty()) return false;
  claimed_[key].push_back(found->second.front());
  found->second.pop_front();
  return true;
}

std::string EarlierRows::take(const std::string& named, int curve, bool* failed) {
  const std::lock_guard<std::mutex> guard(lock_);
  auto& mine = claimed_[key_now(named, curve)];
  if (mine.empty()) throw Error("fit-map --resume: a row was taken that was not claimed");  // a bug, not input
  Row& r = rows_[mine.front()];
  mine.pop_front();
  r.written = true;
  *failed = r.failed;
  return r.line;
}

std::vector<std::string> EarlierRows::leftover(std::size_t* failed) const {
  const std::lock_guard<std::mutex> guard(lock_);
  std::vector<std::string> lines;
  *failed = 0;
  for (const Row& r : rows_)
    if (!r.written) {
      lines.push_back(r.line);
      *failed += r.failed ? 1 : 0;
    }
  return lines;
}

}  // namespace layerjkr::cli
