// layerjkr CLI: fit-map --resume - the rows of an earlier table, matched to this run's curves by
// the file they came from (its canonical path and SHA-256), never by how a path was spelled.
#pragma once

#include <cstddef>
#include <deque>
#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "layerjkr/provenance.hpp"

namespace layerjkr::cli {

/// A file's identity: its canonical path (links and `.`/`..` resolved, std::filesystem::
/// weakly_canonical) and SHA-256. `m/a.csv`, `./m/a.csv` and a link to it are one file.
std::string file_key(const std::string& path, const std::string& sha256);

/// The rows of an earlier table and the curves they belong to. claim() is called by the batch's
/// worker threads (under the object's lock), take() and leftover() one at a time.
class EarlierRows {
 public:
  /// Reads the table `out` (its first line must be `header`), then asks `record` for its record
  /// (the sidecar's JSON; it may refuse the table) and learns from it which file each row's file
  /// cell named. Nothing if the table is missing or empty; InputError naming `out` if it cannot
  /// be read or is damaged. Returns the record (null if none was asked for).
  nlohmann::ordered_json read(const std::string& out, const std::string& header,
                              const std::function<nlohmann::ordered_json()>& record);
  /// This run's inputs: the names as given (a row's file cell) and their records (same order).
  void set_inputs(const std::vector<std::string>& named, const std::vector<InputRecord>& hashed);
  bool empty() const { return rows_.empty(); }

  /// True (and the row reserved) if the earlier table has a row for curve `curve` of the input
  /// named `named` in this run.
  bool claim(const std::string& named, int curve);
  /// The row claim() reserved for that curve (its line, newline included); its status cell in
  /// `*failed` (true for "error").
  std::string take(const std::string& named, int curve, bool* failed);
  /// The rows no input of this run claimed, in table order, and how many of them failed.
  std::vector<std::string> leftover(std::size_t* failed) const;

 private:
  using Key = std::pair<std::string, std::string>;  // file key, curve cell
  Key key_now(const std::string& named, int curve) const;

  struct Row {
    std::string line;
    bool failed = false;
    bool written = false;
  };
  std::vector<Row> rows_;
  std::map<Key, std::deque<std::size_t>> waiting_, claimed_;
  std::map<std::string, std::string> now_;  // a name given in this run -> its file key
  mutable std::mutex lock_;
};

}  // namespace layerjkr::cli
