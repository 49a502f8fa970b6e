// fit-map --tiff DIR (map_tiffs.hpp): the fields of the results table, as images of each map.
#include "map_tiffs.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "layerjkr/error.hpp"
#include "layerjkr/instrument.hpp"
#include "layerjkr/map_image.hpp"
#include "layerjkr/types.hpp"
#include "output_file.hpp"

namespace layerjkr::cli {

namespace fs = std::filesystem;

namespace {

constexpr const char* kMarker = "layerjkr fit-map";

struct Field {
  std::string name, unit;
  std::function<double(const FitSummary&)> value;
};

std::vector<Field> fields_of(const std::vector<FitParameter>& free) {
  std::vector<Field> fields;
  for (FitParameter q : free) {
    auto pick = [q](bool error) {
      return [q, error](const FitSummary& s) {
        for (const auto& e : s.parameters)
          if (e.parameter == q && e.curve < 0) return error ? e.standard_error : e.value;
        return std::nan("");
      };
    };
    fields.push_back({to_string(q), unit_of(q), pick(false)});
    fields.push_back({std::string(to_string(q)) + "_stderr", unit_of(q), pick(true)});
  }
  fields.push_back({"pull_off", "N", [](const FitSummary& s) { return s.pull_off_force; }});
  fields.push_back({"rms_residual", "N", [](const FitSummary& s) { return s.rms_residual; }});
  return fields;
}

// Each input's file-name prefix: none for one input, else its stem and a dot - made unique, as
// two maps of the same stem in two folders would overwrite each other's images: the later ones
// get _2, _3, ... (the first free), in the order given.
std::vector<std::string> prefixes(const std::vector<std::string>& inputs) {
  std::vector<std::string> out;
  if (inputs.size() == 1) return {std::string()};
  std::set<std::string> taken;
  for (const std::string& in : inputs) {
    const std::string stem = fs::path(in).stem().string();
    std::string name = stem;
    for (int k = 2; taken.count(name); ++k) name = stem + "_" + std::to_string(k);
    taken.insert(name);
    out.push_back(name + ".");
  }
  return out;
}

// A file layerjkr wrote: a little-endian TIFF whose description, which write_tiff puts just
// before the IFD, holds the marker. Only the bytes before the IFD are read, not the image.
bool is_our_tiff(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  unsigned char head[8] = {};
  if (!f.read(reinterpret_cast<char*>(head), 8) || std::memcmp(head, "II*\0", 4) != 0) return false;
  const std::uint32_t ifd = head[4] | head[5] << 8 | head[6] << 16 | static_cast<std::uint32_t>(head[7]) << 24;
  const std::uint32_t from = ifd > 8 + 4096 ? ifd - 4096 : 8;
  if (ifd <= from) return false;
  std::string tail(ifd - from, '\0');
  if (!f.seekg(from) || !f.read(tail.data(), static_cast<std::streamsize>(tail.size()))) return false;
  return tail.find(kMarker) != std::string::npos;
}

bool belongs(const std::string& source, const std::string& input) {
  return source == input || (source.size() > input.size() && source.compare(0, input.size(), input) == 0 &&
                             source[input.size()] == '#');
}

}  // namespace

std::vector<std::string> map_tiff_names(const std::vector<std::string>& inputs, const std::vector<FitParameter>& free) {
  std::vector<std::string> names;
  const std::vector<std::string> prefix = prefixes(inputs);
  for (std::size_t k = 0; k < inputs.size(); ++k)
    for (const Field& f : fields_of(free)) names.push_back(prefix[k] + f.name + ".tiff");
  return names;
}

bool may_carry_map_positions(const std::vector<std::string>& inputs) {
  return std::any_of(inputs.begin(), inputs.end(),
                     [](const std::string& in) { return is_instrument_file(in) || is_asylum_map_export(in); });
}

void prepare_tiff_dir(const std::string& dir, const std::vector<std::string>& inputs, const std::vector<std::string>& names,
                      bool force) {
  // Curve files carry no map position: refused now, before the work, not after every fit.
  if (!may_carry_map_positions(inputs))
    throw InputError("--tiff: no input carries map positions (CSV curve files do not; instrument force maps and QI "
                     "files do)");
  // A grid too large for an image is refused now too. A file that cannot be opened is left to the
  // batch, which reports it as that file's failure and goes on.
  for (const std::string& in : inputs) {
    if (!is_instrument_file(in) && !is_asylum_map_export(in)) continue;
    std::optional<InstrumentReader> reader;
    try {
      reader.emplace(in);
    } catch (const InputError&) {
      continue;
    }
    const InstrumentFile& h = reader->header();
    const double pixels = static_cast<double>(std::max(h.grid_shape_x, 0)) * static_cast<double>(std::max(h.grid_shape_y, 0));
    if (pixels > static_cast<double>(kMaxMapImagePixels))
      throw InputError("--tiff: " + in + " has a map grid of " + std::to_string(h.grid_shape_x) + " x " +
                       std::to_string(h.grid_shape_y) + " pixels; an image holds at most " +
                       std::to_string(kMaxMapImagePixels) + " (8192 x 8192): drop --tiff for this map");
  }
  prepare_derived_dir(dir, "--tiff", names, force, is_our_tiff, "a TIFF layerjkr wrote");
}

std::size_t write_map_tiffs(const std::vector<BatchItem>& items, const std::vector<std::string>& inputs,
                            const std::vector<FitParameter>& free, const std::string& dir) {
  std::size_t written = 0;
  const std::vector<Field> fields = fields_of(free);
  const std::vector<std::string> prefix = prefixes(inputs);
  for (std::size_t k = 0; k < inputs.size(); ++k) {
    std::vector<const BatchItem*> mine;
    for (const BatchItem& it : items)
      if (belongs(it.source, inputs[k]) && it.grid_x >= 0 && it.grid_y >= 0) mine.push_back(&it);
    if (mine.empty()) continue;
    std::vector<int> gx, gy;
    gx.reserve(mine.size());
    gy.reserve(mine.size());
    for (const BatchItem* it : mine) {
      gx.push_back(it->grid_x);
      gy.push_back(it->grid_y);
    }
    for (const Field& f : fields) {
      std::vector<double> values;
      values.reserve(mine.size());
      for (const BatchItem* it : mine) values.push_back(it->ok ? f.value(it->summary) : std::nan(""));
      const MapImage image = map_image(gx, gy, values);
      OutputFile out((fs::path(dir) / (prefix[k] + f.name + ".tiff")).string());
      write_tiff(image, out.temporary(), std::string(kMarker) + ": " + f.name + (f.unit.empty() ? "" : " [" + f.unit + "]") +
                                  " of " + fs::path(inputs[k]).filename().string() + "; NaN where no fit");
      out.commit();
      ++written;
    }
  }
  return written;
}

}  // namespace layerjkr::cli
