#include "io/zip_archive.hpp"

#include <algorithm>
#include <cstdio>
#include <set>

#include <zip.h>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {
namespace {

std::string mib(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return std::to_string(bytes) + " bytes (" + text + " MiB)";
}

}  // namespace

// Owns the libzip archive, so that a constructor that throws after opening it (an entry
// name given twice) still closes it: the ZipArchive destructor would not run then.
struct ZipArchive::Handle {
  zip_t* zip = nullptr;
  std::string bytes;  // an archive opened from memory: libzip reads it in place
  Handle() = default;
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (zip) zip_discard(zip);
  }
};

namespace {

[[noreturn]] void not_a_zip(const std::string& path, zip_error_t* error) {
  const std::string why = zip_error_strerror(error);
  zip_error_fini(error);
  throw InputError(path + ": cannot read it as a zip archive (" + why + ")");
}

}  // namespace

ZipArchive::ZipArchive(const std::string& path, const ReadLimits& limits)
    : path_(path), limits_(limits), handle_(std::make_unique<Handle>()) {
  int code = 0;
  handle_->zip = zip_open(path.c_str(), ZIP_RDONLY, &code);
  if (!handle_->zip) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    not_a_zip(path, &error);
  }
  list_names();
}

ZipArchive::ZipArchive(std::string bytes, const std::string& path, const ReadLimits& limits)
    : path_(path), limits_(limits), handle_(std::make_unique<Handle>()) {
  handle_->bytes = std::move(bytes);
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(handle_->bytes.data(), handle_->bytes.size(), 0, &error);
  if (source) handle_->zip = zip_open_from_source(source, ZIP_RDONLY, &error);
  if (!handle_->zip) {
    zip_source_free(source);  // the archive did not take it over
    not_a_zip(path, &error);
  }
  zip_error_fini(&error);
  list_names();
}

void ZipArchive::list_names() {
  const zip_int64_t n = zip_get_num_entries(handle_->zip, 0);
  std::set<std::string> seen;
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* name = zip_get_name(handle_->zip, static_cast<zip_uint64_t>(i), 0);
    if (!name) continue;
    // A second entry of one name would be read in place of the first or never: ambiguous.
    if (!seen.insert(name).second) throw InputError(path_ + ": the archive holds the entry '" + name + "' twice");
    names_.emplace_back(name);
  }
}

ZipArchive::~ZipArchive() = default;

bool ZipArchive::contains(const std::string& name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

std::optional<std::uint64_t> ZipArchive::declared_size(const std::string& name) const {
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(handle_->zip, name.c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE)) return std::nullopt;
  return st.size;
}

std::string ZipArchive::read(const std::string& name) const {
  const std::string where = path_ + ": entry '" + name + "'";
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(handle_->zip, name.c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
    throw InputError(path_ + ": the archive has no entry '" + name + "'");
  // The declared size bounds the allocation: check it before allocating anything.
  if (st.size > limits_.max_member_bytes)
    throw InputError(where + " declares " + mib(st.size) + " uncompressed, over the limit of " +
                     mib(limits_.max_member_bytes) + " per entry; raise it with " + kMaxMemberEnv +
                     "=<MiB> (ReadLimits::max_member_bytes in the library) if the file is genuine");
  if (st.size > limits_.max_archive_bytes - std::min(bytes_read_, limits_.max_archive_bytes))
    throw InputError(where + " declares " + mib(st.size) + " uncompressed, which with the " + mib(bytes_read_) +
                     " read before passes the limit of " + mib(limits_.max_archive_bytes) + " per archive; raise it with " +
                     kMaxArchiveEnv + "=<MiB> (ReadLimits::max_archive_bytes in the library) if the file is genuine");
  std::string data(static_cast<std::size_t>(st.size), '\0');  // before zip_fopen: nothing to close if it throws
  zip_file_t* file = zip_fopen(handle_->zip, name.c_str(), 0);
  if (!file) throw InputError(where + ": cannot open it (" + zip_strerror(handle_->zip) + ")");
  std::size_t got = 0;
  zip_int64_t n = 1;
  while (got < data.size() && (n = zip_fread(file, data.data() + got, data.size() - got)) > 0)
    got += static_cast<std::size_t>(n);
  // libzip checks the CRC-32 and the size only when a read reaches the end of the entry, so
  // read once more: it must report the end (0), not more data and not a CRC error.
  char extra = 0;
  if (n > 0) n = zip_fread(file, &extra, 1);
  const std::string why = n < 0 ? zip_file_strerror(file) : "";
  zip_fclose(file);
  bytes_read_ += got;
  if (n < 0)
    throw InputError(where + " is corrupt (" + why + ")" +
                     (why.find("CRC") != std::string::npos ? ": its data do not match the checksum stored in the archive" : ""));
  if (got != data.size())
    throw InputError(where + " is truncated: " + std::to_string(got) + " of its declared " + std::to_string(data.size()) +
                     " bytes");
  if (n > 0) throw InputError(where + " is corrupt: it holds more than its declared " + std::to_string(data.size()) + " bytes");
  return data;
}

}  // namespace layerjkr::detail
