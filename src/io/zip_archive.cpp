#include "io/zip_archive.hpp"

#include <algorithm>

#include <zip.h>

#include "layerjkr/error.hpp"

namespace layerjkr::detail {

struct ZipArchive::Handle {
  zip_t* zip = nullptr;
};

ZipArchive::ZipArchive(const std::string& path) : path_(path), handle_(std::make_unique<Handle>()) {
  int code = 0;
  handle_->zip = zip_open(path.c_str(), ZIP_RDONLY, &code);
  if (!handle_->zip) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string why = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw InputError(path + ": cannot read it as a zip archive (" + why + ")");
  }
  const zip_int64_t n = zip_get_num_entries(handle_->zip, 0);
  for (zip_int64_t i = 0; i < n; ++i) {
    const char* name = zip_get_name(handle_->zip, static_cast<zip_uint64_t>(i), 0);
    if (name) names_.emplace_back(name);
  }
}

ZipArchive::~ZipArchive() {
  if (handle_ && handle_->zip) zip_discard(handle_->zip);
}

bool ZipArchive::contains(const std::string& name) const {
  return std::find(names_.begin(), names_.end(), name) != names_.end();
}

std::string ZipArchive::read(const std::string& name) const {
  zip_stat_t st;
  zip_stat_init(&st);
  if (zip_stat(handle_->zip, name.c_str(), 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
    throw InputError(path_ + ": the archive has no entry '" + name + "'");
  zip_file_t* file = zip_fopen(handle_->zip, name.c_str(), 0);
  if (!file) throw InputError(path_ + ": cannot open entry '" + name + "' (" + zip_strerror(handle_->zip) + ")");
  std::string data(static_cast<std::size_t>(st.size), '\0');
  const zip_int64_t got = data.empty() ? 0 : zip_fread(file, data.data(), st.size);
  std::string why = got < 0 ? zip_file_strerror(file) : "";
  zip_fclose(file);
  if (got < 0 || static_cast<zip_uint64_t>(got) != st.size)
    throw InputError(path_ + ": entry '" + name + "' is truncated or corrupt" + (why.empty() ? "" : " (" + why + ")"));
  return data;
}

}  // namespace layerjkr::detail
