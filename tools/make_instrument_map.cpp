// Big instrument maps for the map-reading benchmark (bench/map_reading.cpp, issue #22): a
// SIDE x SIDE JPK QI archive from the bundled 4-curve QI file, or a SIDE x SIDE NanoScope
// force volume from the bundled 16 x 16 one. Such files are too big to commit, so they are
// made on demand; curve n of the output is a copy of source curve n % (source curves).
//
//   make_instrument_map qi SIDE OUT.jpk-qi-data [--source DIR]
//   make_instrument_map nanoscope SIDE OUT.spm [--source DIR]
//
// DIR holds the source file (default: the QI file bundled in <source dir>/data/instrument; the
// NanoScope force volume in <source dir>/../shared/data/instrument).
// Exit 0 with one line "OUT: N curves, B bytes, T s"; 2 with one line if the arguments are
// bad or the source is absent; 1 if writing fails.
//
// QI: every entry is copied as its compressed bytes (read with libzip's ZIP_FL_COMPRESSED;
// never inflated and deflated again), except the headers that place a curve:
// index/N/header.properties gets position-index N and the position of pixel
// (N % SIDE, N / SIDE), and the top header.properties the grid's ilength = jlength = SIDE,
// indexes.max = SIDE^2 - 1 and the first pixel's start-position; both are deflated again
// at zlib's level 6, as the source's were. ulength / vlength (10 um) are kept: the same
// area scanned on a finer grid, as an instrument would do; positions are
// xcenter - ulength / 2 + (i + 0.5) ulength / SIDE (the source's own pixel centres for
// SIDE = 128). The segment headers are copied as they are, so their xy-scanner position
// keys still name the source curve's pixel: no reader uses them (the map position is the
// curve header's), and copying keeps them raw like the data. The 128 x 128 preview image
// (data-image.jpk-qi-image) and the thumbnail are copied as they are. Directory entries
// are kept where the source has them. The archive is written front to back by a small
// zip writer below (ZIP64 end records past 65535 entries), in a few MB of memory.
//
// NanoScope: the header (text, CR LF lines, ending in `\*File list end` and 0x1A, padded
// with zeros to the size the first `\Data length` states) keeps its size; the keys that
// count curves are set to SIDE - `\Samps/line` and `\Lines` of `\*Ciao scan list` (the
// grid readers multiply) and `\force/line`, `\Samples / line` of `\*Ciao force list` - as
// are those of the height image (`\*Ciao image list`: Samps/line, Number of lines, Valid
// data len X / Y). Each block's `\Data length` is scaled to SIDE^2 curves (pixels) and its
// `\Data offset` moved so the blocks stay one after another in their source order. The
// force data are streamed curve by curve (curve c = source curve c % 256), never held
// whole; the image's pixels are tiled the same way; the source's 3073 bytes after its last
// block, which no header key describes, are copied to the end unchanged.
#include <zip.h>
#include <zlib.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace {

constexpr const char* kQiSource = "fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data";
// The 16 x 16 force volume. (20200904_Egel4-Z1.0_00025.spm beside it is a single curve.)
constexpr const char* kNanoscopeSource = "bruker/20200903_Egel2.0_00023.spm";
constexpr int kMaxSide = 4096;  // 16.7 M curves; beyond that the files would not fit a disk

// A failure while writing: exit 1 with the message.
struct Failure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

// A double as Java's Double.toString writes it (the JPK headers' spelling): the shortest
// digits that read back exactly, plain in [1e-3, 1e7), else d.ddd...E<exp>.
std::string java_double(double v) {
  if (v == 0.0) return std::signbit(v) ? "-0.0" : "0.0";
  char buf[64];
  const auto res = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::scientific);
  const std::string s(buf, res.ptr);
  const std::size_t e = s.find('e');
  const bool negative = s[0] == '-';
  std::string digits;
  for (std::size_t i = negative ? 1 : 0; i < e; ++i)
    if (s[i] != '.') digits += s[i];
  const int exp = std::stoi(s.substr(e + 1));
  std::string out = negative ? "-" : "";
  const double a = std::abs(v);
  if (a >= 1e-3 && a < 1e7) {
    if (exp >= 0) {
      digits.resize(std::max(digits.size(), static_cast<std::size_t>(exp) + 1), '0');
      out += digits.substr(0, static_cast<std::size_t>(exp) + 1) + ".";
      const std::string frac = digits.substr(static_cast<std::size_t>(exp) + 1);
      out += frac.empty() ? "0" : frac;
    } else {
      out += "0." + std::string(static_cast<std::size_t>(-exp - 1), '0') + digits;
    }
    return out;
  }
  out += digits.substr(0, 1) + "." + (digits.size() > 1 ? digits.substr(1) : "0");
  return out + "E" + std::to_string(exp);
}

// Replaces the value of every `key=value` line whose key ends in a suffix of `values`;
// each suffix must match at least one line, so a source of another layout is an error,
// not a map with stale positions.
std::string rewrite_properties(const std::string& text, const std::map<std::string, std::string>& values,
                               const std::string& where) {
  std::map<std::string, int> hits;
  std::string out;
  out.reserve(text.size() + 64);
  std::size_t begin = 0;
  while (begin < text.size()) {
    std::size_t end = text.find('\n', begin);
    end = end == std::string::npos ? text.size() : end + 1;
    const std::string line = text.substr(begin, end - begin);
    const std::size_t eq = line.find('=');
    bool replaced = false;
    if (eq != std::string::npos && line[0] != '#') {
      const std::string key = line.substr(0, eq);
      for (const auto& [suffix, value] : values)
        if (!replaced && ends_with(key, suffix)) {
          out += key + "=" + value + (ends_with(line, "\n") ? "\n" : "");
          ++hits[suffix];
          replaced = true;
        }
    }
    if (!replaced) out += line;
    begin = end;
  }
  for (const auto& [suffix, value] : values)
    if (hits[suffix] == 0) throw Failure(where + " has no key ending in '" + suffix + "'");
  return out;
}

// ---------------------------------------------------------------------------------------
// QI archive

struct ZipCloser {
  void operator()(zip_t* z) const { zip_discard(z); }
};
using ZipPtr = std::unique_ptr<zip_t, ZipCloser>;

// One entry of the source archive as stored: its compressed bytes and what the central
// directory says of them.
struct SourceEntry {
  std::string name;
  std::uint16_t method = 0;  // 0 stored, 8 deflated
  std::uint32_t crc = 0;
  std::uint64_t size = 0;
  std::string stored;  // the compressed bytes
  std::uint16_t dos_time = 0, dos_date = 0;
};

std::pair<std::uint16_t, std::uint16_t> dos_time_date(time_t t) {
  std::tm tm{};
  localtime_r(&t, &tm);  // libzip made t from the DOS fields with mktime (local time)
  const auto time = static_cast<std::uint16_t>((tm.tm_hour << 11) | (tm.tm_min << 5) | (tm.tm_sec / 2));
  const auto date =
      static_cast<std::uint16_t>(((std::max(tm.tm_year, 80) - 80) << 9) | ((tm.tm_mon + 1) << 5) | tm.tm_mday);
  return {time, date};
}

std::vector<SourceEntry> read_source(const std::string& source) {
  int err = 0;
  ZipPtr z(zip_open(source.c_str(), ZIP_RDONLY, &err));
  if (!z) throw Failure(source + ": not a readable zip archive");
  std::vector<SourceEntry> out;
  const zip_int64_t count = zip_get_num_entries(z.get(), 0);
  for (zip_uint64_t i = 0; i < static_cast<zip_uint64_t>(count); ++i) {
    zip_stat_t st;
    if (zip_stat_index(z.get(), i, 0, &st) != 0) throw Failure(source + ": " + zip_strerror(z.get()));
    SourceEntry e;
    e.name = st.name;
    e.method = st.comp_method;
    if (e.method != ZIP_CM_STORE && e.method != ZIP_CM_DEFLATE)
      throw Failure(source + ": " + e.name + " uses compression method " + std::to_string(e.method));
    e.crc = st.crc;
    e.size = st.size;
    std::tie(e.dos_time, e.dos_date) = dos_time_date(st.mtime);
    e.stored.resize(static_cast<std::size_t>(st.comp_size));
    zip_file_t* f = zip_fopen_index(z.get(), i, ZIP_FL_COMPRESSED);
    if (!f) throw Failure(source + ": " + e.name + ": " + zip_strerror(z.get()));
    const zip_int64_t n = zip_fread(f, e.stored.data(), e.stored.size());
    zip_fclose(f);
    if (n < 0 || static_cast<std::uint64_t>(n) != st.comp_size) throw Failure(source + ": " + e.name + ": short read");
    out.push_back(std::move(e));
  }
  return out;
}

std::string unpack(const SourceEntry& e) {
  if (e.method == ZIP_CM_STORE) return e.stored;
  std::string out(static_cast<std::size_t>(e.size), '\0');
  z_stream zs{};
  if (inflateInit2(&zs, -MAX_WBITS) != Z_OK) throw Failure("zlib: inflateInit2 failed");
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(e.stored.data()));
  zs.avail_in = static_cast<uInt>(e.stored.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  const int rc = inflate(&zs, Z_FINISH);
  inflateEnd(&zs);
  if (rc != Z_STREAM_END || zs.total_out != e.size) throw Failure(e.name + ": cannot inflate");
  return out;
}

// A header deflated as the source's were (zlib level 6, "normal"), with its CRC-32.
SourceEntry deflate_text(const SourceEntry& like, const std::string& text) {
  SourceEntry e = like;
  e.method = ZIP_CM_DEFLATE;
  e.size = text.size();
  e.crc = static_cast<std::uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(text.data()), static_cast<uInt>(text.size())));
  z_stream zs{};
  if (deflateInit2(&zs, 6, Z_DEFLATED, -MAX_WBITS, 8, Z_DEFAULT_STRATEGY) != Z_OK)
    throw Failure("zlib: deflateInit2 failed");
  e.stored.resize(deflateBound(&zs, static_cast<uLong>(text.size())));
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  zs.avail_in = static_cast<uInt>(text.size());
  zs.next_out = reinterpret_cast<Bytef*>(e.stored.data());
  zs.avail_out = static_cast<uInt>(e.stored.size());
  const int rc = deflate(&zs, Z_FINISH);
  e.stored.resize(zs.total_out);
  deflateEnd(&zs);
  if (rc != Z_STREAM_END) throw Failure(like.name + ": cannot deflate");
  return e;
}

// A zip archive written front to back: each entry's local header and its stored bytes as
// they come, its central-directory record to a temporary file appended at the end, so that
// memory stays a few MB whatever the number of entries. (libzip's writer keeps every
// entry's source and bookkeeping until zip_close: 700 MB and 17-55 s for the 1.1 M entries
// of a 256 x 256 map.) ZIP64 end records when the entries pass 65535, a ZIP64 extra field
// for an entry that starts past 4 GiB, as the APPNOTE says; no entry is near 4 GiB itself.
class ZipWriter {
 public:
  explicit ZipWriter(const std::string& path)
      : path_(path), out_(std::fopen(path.c_str(), "wb"), &std::fclose), central_(std::tmpfile(), &std::fclose) {
    if (!out_) throw Failure(path + ": cannot create");
    if (!central_) throw Failure("cannot create a temporary file");
    std::setvbuf(out_.get(), buffer_.data(), _IOFBF, buffer_.size());
  }

  void add(const std::string& name, const SourceEntry& e) {
    const bool dir = ends_with(name, "/");
    const std::uint64_t offset = at_;
    std::string h;
    u32(h, 0x04034b50);
    common(h, name, e, 20);
    put(out_.get(), h);
    put(out_.get(), name);
    put(out_.get(), e.stored);
    at_ += h.size() + name.size() + e.stored.size();

    const bool far = offset >= 0xffffffffu;
    std::string c;
    u32(c, 0x02014b50);
    u16(c, (3 << 8) | 20);  // made by: Unix, spec 2.0
    common(c, name, e, far ? 45 : 20, far ? 12 : 0);
    u16(c, 0);                                               // comment
    u16(c, 0);                                               // disk
    u16(c, 0);                                               // internal attributes
    u32(c, dir ? (040755u << 16) | 0x10u : 0100644u << 16);  // Unix mode; MS-DOS directory bit
    u32(c, far ? 0xffffffffu : static_cast<std::uint32_t>(offset));
    c += name;
    if (far) {
      u16(c, 0x0001);
      u16(c, 8);
      u64(c, offset);
    }
    put(central_.get(), c);
    central_size_ += c.size();
    ++entries_;
  }

  void close() {
    const std::uint64_t cd_offset = at_;
    std::rewind(central_.get());
    std::vector<char> chunk(std::size_t{1} << 20);
    for (std::size_t n; (n = std::fread(chunk.data(), 1, chunk.size(), central_.get())) > 0;)
      put(out_.get(), std::string(chunk.data(), n));
    at_ += central_size_;
    const bool zip64 = entries_ >= 0xffff || cd_offset >= 0xffffffffu || central_size_ >= 0xffffffffu;
    std::string end;
    if (zip64) {
      const std::uint64_t record = at_;
      u32(end, 0x06064b50);
      u64(end, 44);  // the record's size after this field
      u16(end, (3 << 8) | 45);
      u16(end, 45);
      u32(end, 0);
      u32(end, 0);
      u64(end, entries_);
      u64(end, entries_);
      u64(end, central_size_);
      u64(end, cd_offset);
      u32(end, 0x07064b50);  // locator
      u32(end, 0);
      u64(end, record);
      u32(end, 1);
    }
    u32(end, 0x06054b50);
    u16(end, 0);
    u16(end, 0);
    u16(end, static_cast<std::uint16_t>(std::min<std::uint64_t>(entries_, 0xffff)));
    u16(end, static_cast<std::uint16_t>(std::min<std::uint64_t>(entries_, 0xffff)));
    u32(end, static_cast<std::uint32_t>(std::min<std::uint64_t>(central_size_, 0xffffffffu)));
    u32(end, static_cast<std::uint32_t>(std::min<std::uint64_t>(cd_offset, 0xffffffffu)));
    u16(end, 0);
    put(out_.get(), end);
    if (std::fflush(out_.get()) != 0) throw Failure(path_ + ": write failed");
  }

 private:
  static void u16(std::string& s, unsigned v) {
    s += static_cast<char>(v & 0xff);
    s += static_cast<char>((v >> 8) & 0xff);
  }
  static void u32(std::string& s, std::uint32_t v) {
    u16(s, v & 0xffff);
    u16(s, v >> 16);
  }
  static void u64(std::string& s, std::uint64_t v) {
    u32(s, static_cast<std::uint32_t>(v));
    u32(s, static_cast<std::uint32_t>(v >> 32));
  }
  // The fields the local header and the central record share, from "version needed" to
  // the extra field's length.
  static void common(std::string& s, const std::string& name, const SourceEntry& e, unsigned version,
                     unsigned extra = 0) {
    u16(s, version);
    u16(s, 0);  // flags: sizes and CRC in the header, no data descriptor
    u16(s, e.method);
    u16(s, e.dos_time);
    u16(s, e.dos_date);
    u32(s, e.crc);
    u32(s, static_cast<std::uint32_t>(e.stored.size()));
    u32(s, static_cast<std::uint32_t>(e.size));
    u16(s, static_cast<unsigned>(name.size()));
    u16(s, extra);
  }
  void put(std::FILE* f, const std::string& bytes) {
    if (std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) throw Failure(path_ + ": write failed");
  }

  std::string path_;
  std::vector<char> buffer_ = std::vector<char>(std::size_t{1} << 20);  // before out_: outlives it
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out_;
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> central_;
  std::uint64_t at_ = 0, central_size_ = 0, entries_ = 0;
};

std::size_t make_qi(const std::string& source, int side, const std::string& out_path) {
  const std::vector<SourceEntry> entries = read_source(source);
  // The source's curves: index/K/<rest> entries grouped by K (in archive order within
  // each); the other entries, "index/" among them, in archive order.
  struct Template {
    std::vector<std::pair<std::string, const SourceEntry*>> entries;  // (rest, entry)
    std::string header;                                               // index/K/header.properties
    const SourceEntry* header_entry = nullptr;
  };
  std::map<int, Template> curves;
  std::vector<const SourceEntry*> others;
  std::size_t curves_at = 0;  // where among `others` the curves go
  const SourceEntry* top = nullptr;
  for (const SourceEntry& e : entries) {
    int k = -1;
    std::size_t slash = std::string::npos;
    if (e.name.rfind("index/", 0) == 0 && (slash = e.name.find('/', 6)) != std::string::npos) {
      const auto [end, ec] = std::from_chars(e.name.data() + 6, e.name.data() + slash, k);
      if (ec != std::errc() || end != e.name.data() + slash) k = -1;
    }
    if (k >= 0) {
      if (curves.empty()) curves_at = others.size();
      Template& t = curves[k];
      const std::string rest = e.name.substr(slash + 1);
      t.entries.emplace_back(rest, &e);
      if (rest == "header.properties") t.header = unpack(e), t.header_entry = &e;
    } else {
      if (e.name == "header.properties") top = &e;
      others.push_back(&e);
    }
  }
  if (curves.empty() || !top) throw Failure(source + ": no index/N/ curves or no header.properties");
  std::vector<const Template*> templates;
  for (const auto& [k, t] : curves) {
    if (!t.header_entry) throw Failure(source + ": index/" + std::to_string(k) + "/ has no header.properties");
    templates.push_back(&t);
  }

  // The grid from the top header: pixel centres across the kept scan size.
  const std::string top_text = unpack(*top);
  auto value = [&](const std::string& suffix) {
    std::istringstream lines(top_text);
    for (std::string line; std::getline(lines, line);) {
      const std::size_t eq = line.find('=');
      if (eq != std::string::npos && ends_with(line.substr(0, eq), suffix)) return std::stod(line.substr(eq + 1));
    }
    throw Failure("header.properties has no key ending in '" + suffix + "'");
  };
  const double u = value(".grid.ulength"), v = value(".grid.vlength");
  const double dx = u / side, dy = v / side;
  const double x0 = value(".grid.xcenter") - 0.5 * u + 0.5 * dx, y0 = value(".grid.ycenter") - 0.5 * v + 0.5 * dy;
  const SourceEntry new_top =
      deflate_text(*top, rewrite_properties(top_text,
                                            {{".grid.ilength", std::to_string(side)},
                                             {".grid.jlength", std::to_string(side)},
                                             {".indexes.max", std::to_string(static_cast<long long>(side) * side - 1)},
                                             {".start-position.x", java_double(x0)},
                                             {".start-position.y", java_double(y0)}},
                                            "header.properties"));

  ZipWriter zip(out_path);
  const std::size_t n_curves = static_cast<std::size_t>(side) * static_cast<std::size_t>(side);
  for (std::size_t o = 0; o <= others.size(); ++o) {
    if (o == curves_at)
      for (std::size_t n = 0; n < n_curves; ++n) {
        const Template& t = *templates[n % templates.size()];
        const std::string prefix = "index/" + std::to_string(n) + "/";
        for (const auto& [rest, e] : t.entries) {
          if (e != t.header_entry) {
            zip.add(prefix + rest, *e);
            continue;
          }
          const std::size_t i = n % static_cast<std::size_t>(side), j = n / static_cast<std::size_t>(side);
          const std::string text =
              rewrite_properties(t.header,
                                 {{".header.position-index", std::to_string(n)},
                                  {".header.position.x", java_double(x0 + static_cast<double>(i) * dx)},
                                  {".header.position.y", java_double(y0 + static_cast<double>(j) * dy)}},
                                 e->name);
          zip.add(prefix + rest, deflate_text(*e, text));
        }
      }
    if (o == others.size()) break;
    zip.add(others[o]->name, others[o] == top ? new_top : *others[o]);
  }
  zip.close();
  return n_curves;
}

// ---------------------------------------------------------------------------------------
// NanoScope force volume

struct Block {
  std::size_t offset_line = 0, length_line = 0;  // header line numbers of its two keys
  std::uint64_t offset = 0, length = 0;          // in the source
  std::uint64_t unit = 0;                        // bytes per curve (pixel) in the source
};

std::string key_of(const std::string& line) {
  const std::size_t colon = line.find(": ");
  return line.substr(0, colon == std::string::npos ? line.find(':') : colon);
}
std::uint64_t number_of(const std::string& line) {
  const std::size_t colon = line.find(':');
  return std::stoull(line.substr(colon + 1));
}

std::size_t make_nanoscope(const std::string& source, int side, const std::string& out_path) {
  std::ifstream in(source, std::ios::binary);
  if (!in) throw Failure(source + ": cannot read");
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string end_mark = "\\*File list end\r\n\x1a";
  const std::size_t end = bytes.find(end_mark);
  if (end == std::string::npos) throw Failure(source + ": no '\\*File list end'");
  std::vector<std::string> lines;
  for (std::size_t b = 0; b < end;) {
    const std::size_t e = bytes.find("\r\n", b);
    lines.push_back(bytes.substr(b, e - b));
    b = e + 2;
  }
  // Sections in order; the keys to change are looked up in their own section only, since
  // `\Samps/line` means curves per line in one and samples per curve in another.
  std::string section;
  std::uint64_t header_size = 0, grid_lines = 0, grid_samps = 0;
  std::vector<Block> blocks;
  std::vector<std::size_t> count_lines;  // lines whose value becomes SIDE
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& l = lines[i];
    if (l.rfind("\\*", 0) == 0) {
      section = l;
      if (section == "\\*Ciao force image list" || section == "\\*Ciao image list") blocks.emplace_back();
      continue;
    }
    const std::string key = key_of(l);
    if (section == "\\*Force file list" && key == "\\Data length" && header_size == 0) header_size = number_of(l);
    if (section == "\\*Ciao scan list" && (key == "\\Samps/line" || key == "\\Lines")) {
      (key == "\\Lines" ? grid_lines : grid_samps) = number_of(l);
      count_lines.push_back(i);
    }
    if (section == "\\*Ciao force list" && (key == "\\force/line" || key == "\\Samples / line"))
      count_lines.push_back(i);
    if (section == "\\*Ciao image list" && (key == "\\Samps/line" || key == "\\Number of lines" ||
                                            key == "\\Valid data len X" || key == "\\Valid data len Y"))
      count_lines.push_back(i);
    if (!blocks.empty() && (section == "\\*Ciao force image list" || section == "\\*Ciao image list")) {
      if (key == "\\Data offset") blocks.back().offset_line = i, blocks.back().offset = number_of(l);
      if (key == "\\Data length") blocks.back().length_line = i, blocks.back().length = number_of(l);
    }
  }
  const std::uint64_t curves = grid_lines * grid_samps;
  if (header_size == 0 || curves == 0 || blocks.empty())
    throw Failure(source + ": not a force volume (no header size, scan list Lines x Samps/line, or data blocks)");
  std::sort(blocks.begin(), blocks.end(), [](const Block& a, const Block& b) { return a.offset < b.offset; });
  std::uint64_t at = header_size;
  for (Block& b : blocks) {
    if (b.offset != at || b.length % curves != 0 || b.offset + b.length > bytes.size())
      throw Failure(source + ": data blocks not one after another from the header's end, or not " +
                    std::to_string(curves) + " equal parts");
    at += b.length;
    b.unit = b.length / curves;
  }
  const std::uint64_t n = static_cast<std::uint64_t>(side) * static_cast<std::uint64_t>(side);
  std::uint64_t new_at = header_size;
  for (const Block& b : blocks) {
    lines[b.offset_line] = key_of(lines[b.offset_line]) + ": " + std::to_string(new_at);
    lines[b.length_line] = key_of(lines[b.length_line]) + ": " + std::to_string(b.unit * n);
    new_at += b.unit * n;
  }
  for (std::size_t i : count_lines) lines[i] = key_of(lines[i]) + ": " + std::to_string(side);
  std::string header;
  for (const std::string& l : lines) header += l + "\r\n";
  header += end_mark;
  if (header.size() > header_size)
    throw Failure("the new header does not fit in " + std::to_string(header_size) + " bytes");
  header.resize(header_size, '\0');  // the source pads with zeros too

  // Curve by curve through a 1 MiB stdio buffer (declared first: it must outlive the
  // stream): the output is never held whole.
  std::vector<char> buffer(std::size_t{1} << 20);
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> out(std::fopen(out_path.c_str(), "wb"), &std::fclose);
  if (!out) throw Failure(out_path + ": cannot create");
  std::setvbuf(out.get(), buffer.data(), _IOFBF, buffer.size());
  auto put = [&](const char* p, std::size_t len) {
    if (std::fwrite(p, 1, len, out.get()) != len) throw Failure(out_path + ": write failed");
  };
  put(header.data(), header.size());
  for (const Block& b : blocks)
    for (std::uint64_t c = 0; c < n; ++c) put(bytes.data() + b.offset + (c % curves) * b.unit, b.unit);
  put(bytes.data() + at, bytes.size() - at);
  if (std::fflush(out.get()) != 0) throw Failure(out_path + ": write failed");
  return n;
}

int usage(const std::string& why) {
  std::fprintf(stderr, "make_instrument_map: %s (usage: make_instrument_map qi|nanoscope SIDE OUT [--source DIR])\n",
               why.c_str());
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> args;
  std::string dir;  // empty: each kind's default (above)
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--source") {
      if (i + 1 == argc) return usage("--source needs a directory");
      dir = argv[++i];
    } else {
      args.push_back(a);
    }
  }
  if (args.size() != 3) return usage("expected 3 arguments, got " + std::to_string(args.size()));
  const std::string& kind = args[0];
  if (kind != "qi" && kind != "nanoscope") return usage("unknown kind '" + kind + "'");
  int side = 0;
  const auto [end, ec] = std::from_chars(args[1].data(), args[1].data() + args[1].size(), side);
  if (ec != std::errc() || end != args[1].data() + args[1].size() || side < 1 || side > kMaxSide)
    return usage("SIDE '" + args[1] + "' is not a whole number in [1, " + std::to_string(kMaxSide) + "]");
  if (dir.empty())
    dir = std::string(LAYERJKR_SOURCE_DIR) + (kind == "qi" ? "/data/instrument" : "/../shared/data/instrument");
  const std::string source = dir + "/" + (kind == "qi" ? kQiSource : kNanoscopeSource);
  if (!std::ifstream(source).good()) return usage("the source " + source + " is absent");
  const auto t0 = std::chrono::steady_clock::now();
  try {
    const std::size_t n = kind == "qi" ? make_qi(source, side, args[2]) : make_nanoscope(source, side, args[2]);
    const double t = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::ifstream written(args[2], std::ios::binary | std::ios::ate);
    std::printf("%s: %zu curves, %lld bytes, %.2f s\n", args[2].c_str(), n, static_cast<long long>(written.tellg()), t);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_instrument_map: %s\n", e.what());
    return 1;
  }
  return 0;
}
