// layerjkr: provenance - what a result was made from, recorded so it can be made again.
//
//   std::vector<layerjkr::InputRecord> inputs{layerjkr::record_file("curve.csv")};
//   std::string text = layerjkr::provenance_json(scene, options, &csv, inputs);
//   ...
//   layerjkr::ProvenanceRecord r = layerjkr::parse_provenance(text, "report.json");
//   for (const auto& in : r.inputs) layerjkr::verify_input(in);   // same bytes, or InputError
//   layerjkr::fit(layerjkr::read_curve_csv(r.inputs[0].path, *r.csv), *r.scene, r.options);
//
// A provenance record is one JSON object (docs/provenance.md):
//   {"layerjkr_version": "0.1.0",
//    "scene": {"json": {...the scene as parsed...} | null, "file": PATH | null,
//              "sha256": HEX | null, "model": "two_term", "profile": "paraboloid(R=1e-05)"},
//    "options": {...every FitOptions field...},
//    "csv": {...every CsvOptions field...}          (absent where no file was read),
//    "inputs": [{"path": ABSOLUTE PATH, "size": BYTES, "sha256": HEX}, ...]}
// plus what the caller adds (the CLI: the command line). Doubles are written in the shortest
// form that reads back to the same bits, so options and scenes round-trip exactly. Options read
// back strictly: an unknown key is an error (a record from a newer layerjkr with options this
// one lacks cannot be reproduced here); a missing key keeps its default (an older layerjkr had
// no such option, and new options default to the old behaviour).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "layerjkr/curve_data.hpp"
#include "layerjkr/fit.hpp"
#include "layerjkr/scene.hpp"

namespace layerjkr {

/// The layerjkr version, "MAJOR.MINOR.PATCH": CMake's project(layerjkr VERSION ...), the one
/// place it is written (Python's layerjkr.__version__ returns this).
const char* version();

/// SHA-256 of `size` bytes at `data`, as 64 lowercase hex digits (OpenSSL's libcrypto).
std::string sha256_hex(const void* data, std::size_t size);

/// One input of a result: a file (absolute path, size [bytes], SHA-256 of its bytes), or an
/// array given in memory (path: its name, e.g. "delta (float64 array)"; size and SHA-256 of its
/// bytes as stored, little-endian IEEE doubles on every supported platform).
struct InputRecord {
  std::string path;
  std::uint64_t size = 0;
  std::string sha256;  ///< 64 lowercase hex digits; empty with `error`
  /// Why the input could not be hashed (not a regular file, missing, unreadable); empty if hashed.
  std::string error;
};

/// Hashes the file at `path`, streamed in 1 MiB chunks (a map of gigabytes is never held).
/// Only regular files (links followed) are opened: anything else - a FIFO, a directory, a
/// missing file - is recorded with `error` saying what it is, never opened (a FIFO would block).
InputRecord record_file(const std::string& path);

/// An array given in memory: `name`, its byte count and its SHA-256.
InputRecord record_bytes(const std::string& name, const void* data, std::size_t size);

/// Throws InputError naming the file unless it exists as a regular file and its size and
/// SHA-256 equal the record's: "PATH: SHA-256 is X, the record says Y" (or: is missing).
void verify_input(const InputRecord& recorded);

/// FitOptions / CsvOptions as a JSON object holding every field (enums by their registry
/// names, doubles exact), and back. Reading throws InputError naming `source` and the key for
/// an unknown key, a wrong type or an unknown name, and DomainError for invalid values.
std::string to_json(const FitOptions& options);
std::string to_json(const CsvOptions& options);
FitOptions fit_options_from_json(const std::string& json_text, const std::string& source = "options");
CsvOptions csv_options_from_json(const std::string& json_text, const std::string& source = "csv options");

/// The scene's record: its JSON as parsed (Scene::origin) with, for a scene file, the file and
/// the SHA-256 of the bytes parsed; its model and profile described. A scene built in code, or
/// changed after parsing (its fields no longer those its JSON gives), has "json": null and a
/// "note" saying why: it is described, not reproducible.
std::string scene_json(const Scene& scene);

/// The provenance object above (JSON text). `csv` may be null (arrays given directly).
std::string provenance_json(const Scene& scene, const FitOptions& options, const CsvOptions* csv,
                            const std::vector<InputRecord>& inputs);

/// A provenance object read back.
struct ProvenanceRecord {
  std::string version;  ///< the layerjkr version that wrote it
  /// The scene parsed from the recorded JSON; nullopt if the record has none (built in code).
  std::optional<Scene> scene;
  std::string scene_note;  ///< why there is no scene JSON (the record's note), if none
  FitOptions options;
  std::optional<CsvOptions> csv;
  std::vector<InputRecord> inputs;
};

/// Reads a provenance object (JSON text, e.g. the "provenance" value of a fit report);
/// `source` names it in errors. Throws InputError for a missing or malformed key.
ProvenanceRecord parse_provenance(const std::string& json_text, const std::string& source);

}  // namespace layerjkr
