#include "harness/records/library_file.h"

#include <dlfcn.h>
#include <openssl/evp.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

namespace ib {

std::string file_sha256(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  const std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> context(EVP_MD_CTX_new(), EVP_MD_CTX_free);
  if (!context || EVP_DigestInit_ex(context.get(), EVP_sha256(), nullptr) != 1) return "";
  std::array<char, 1 << 16> buffer;  // a library of tens of megabytes is read in pieces, not whole
  while (in.read(buffer.data(), buffer.size()) || in.gcount() > 0) {
    if (EVP_DigestUpdate(context.get(), buffer.data(), static_cast<std::size_t>(in.gcount())) != 1) return "";
  }
  if (in.bad()) return "";
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int digest_bytes = 0;
  if (EVP_DigestFinal_ex(context.get(), digest.data(), &digest_bytes) != 1) return "";
  std::string hex;
  for (unsigned int i = 0; i < digest_bytes; ++i) {
    char pair[3];
    std::snprintf(pair, sizeof pair, "%02x", digest[i]);
    hex += pair;
  }
  return hex;
}

LibraryFile loaded_library_file(const void* function) {
  LibraryFile file;
  Dl_info info{};
  if (!function || dladdr(function, &info) == 0 || !info.dli_fname || !*info.dli_fname) return file;
  // The canonical path (symbolic links such as libX.so.8 -> libX.so.8.0.2 resolved): the file whose bytes are
  // hashed, and the same text on machines whose /lib is a link to /usr/lib.
  std::error_code error;
  const std::filesystem::path canonical = std::filesystem::canonical(info.dli_fname, error);
  file.path = error ? std::string(info.dli_fname) : canonical.string();
  const std::uintmax_t size = std::filesystem::file_size(file.path, error);
  if (error) return file;
  file.size_bytes = static_cast<long long>(size);
  file.sha256 = file_sha256(file.path);
  return file;
}

}  // namespace ib
