// SHA-256 of inputs (provenance.hpp) through OpenSSL's libcrypto: the EVP interface, since
// OpenSSL 3 deprecates the SHA256_* functions. Files are streamed, never held whole.
#include <openssl/evp.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <vector>

#include "io/curve_source.hpp"
#include "io/read_file.hpp"
#include "layerjkr/error.hpp"
#include "layerjkr/provenance.hpp"

namespace layerjkr {
namespace {

// One digest in progress; any failure of libcrypto (it has none for SHA-256 short of memory)
// is a NumericalError rather than a wrong hash.
class Sha256 {
 public:
  Sha256() : ctx_(EVP_MD_CTX_new(), &EVP_MD_CTX_free) {
    if (!ctx_ || EVP_DigestInit_ex(ctx_.get(), EVP_sha256(), nullptr) != 1) fail();
  }
  void update(const void* data, std::size_t size) {
    if (size > 0 && EVP_DigestUpdate(ctx_.get(), data, size) != 1) fail();
  }
  std::string hex() {
    unsigned char digest[EVP_MAX_MD_SIZE];
    unsigned int length = 0;
    if (EVP_DigestFinal_ex(ctx_.get(), digest, &length) != 1 || length != 32) fail();
    static const char* const kDigits = "0123456789abcdef";
    std::string out;
    for (unsigned int i = 0; i < length; ++i) {
      out += kDigits[digest[i] >> 4];
      out += kDigits[digest[i] & 15];
    }
    return out;
  }

 private:
  [[noreturn]] static void fail() { throw NumericalError("SHA-256: OpenSSL's libcrypto failed"); }
  std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> ctx_;
};

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

std::string sha256_hex(const void* data, std::size_t size) {
  Sha256 h;
  h.update(data, size);
  return h.hex();
}

InputRecord record_bytes(const std::string& name, const void* data, std::size_t size) {
  return {name, size, sha256_hex(data, size), {}};
}

InputRecord record_file(const std::string& path) {
  InputRecord r;
  std::error_code ec;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
  r.path = ec ? path : absolute.lexically_normal().string();
  // An Asylum map exported per channel (a directory or a pattern): its files, each hashed, in
  // name order; the record's SHA-256 is that of the lines "name SHA-256" (names relative to the
  // path given), its size their total, so that a changed, added or removed wave changes it.
  if (const std::vector<std::string> files = detail::asylum_channel_files(path); !files.empty()) {
    Sha256 list;
    const std::filesystem::path base = path.find_first_of("*?[") == std::string::npos
                                           ? std::filesystem::path(path)
                                           : std::filesystem::path(path).parent_path();
    for (const std::string& f : files) {
      const InputRecord one = record_file(f);
      if (!one.error.empty()) {
        r.error = one.error;
        r.size = 0;
        return r;
      }
      const std::string line = std::filesystem::path(f).lexically_relative(base).string() + " " +
                               one.sha256 + "\n";
      list.update(line.data(), line.size());
      r.size += one.size;
    }
    r.sha256 = list.hex();
    return r;
  }
  r.error = detail::not_a_file(path);
  if (!r.error.empty()) return r;
  const std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file) {
    r.error = path + ": cannot be opened (" + std::strerror(errno) + ")";
    return r;
  }
  // 1 MiB chunks: the measured hash rate is flat from 64 KiB up (docs/provenance.md).
  std::vector<unsigned char> chunk(std::size_t{1} << 20);
  Sha256 h;
  for (;;) {
    const std::size_t n = std::fread(chunk.data(), 1, chunk.size(), file.get());
    h.update(chunk.data(), n);
    r.size += n;
    if (n < chunk.size()) break;
  }
  if (std::ferror(file.get())) {
    r.error = path + ": cannot be read (" + std::strerror(errno) + ")";
    r.size = 0;
    return r;
  }
  r.sha256 = h.hex();
  return r;
}

void verify_input(const InputRecord& recorded) {
  if (!recorded.error.empty())
    throw InputError(recorded.path + ": was not hashed when recorded (" + recorded.error + "); it cannot be verified");
  const InputRecord now = record_file(recorded.path);
  if (!now.error.empty())
    throw InputError(recorded.path + ": the recorded input is missing or unreadable (" + now.error +
                     "); the record says SHA-256 " + recorded.sha256);
  if (now.sha256 != recorded.sha256 || now.size != recorded.size)
    throw InputError(recorded.path + ": SHA-256 is " + now.sha256 + " (" + std::to_string(now.size) +
                     " bytes), the record says " + recorded.sha256 + " (" + std::to_string(recorded.size) +
                     " bytes): the input changed");
}

}  // namespace layerjkr
