#include "base/file_util.h"

#include <openssl/evp.h>

#include <array>
#include <cstdint>

namespace phongsim {
namespace {

EVP_MD_CTX* context(void* p) { return static_cast<EVP_MD_CTX*>(p); }

std::string hex_of(const unsigned char* digest, unsigned int size) {
  std::string hex;
  hex.reserve(2 * size);
  for (unsigned int i = 0; i < size; ++i) hex += fmt::format("{:02x}", digest[i]);
  return hex;
}

}  // namespace

ContentHash::ContentHash() : ctx_(EVP_MD_CTX_new()) {
  if (ctx_ == nullptr || EVP_DigestInit_ex(context(ctx_), EVP_sha256(), nullptr) != 1) {
    throw Error("SHA-256 is not available (OpenSSL)");
  }
}

ContentHash::~ContentHash() { EVP_MD_CTX_free(context(ctx_)); }

void ContentHash::add(std::string_view bytes) {
  // The field's length first (8 bytes, little-endian): fields cannot run into each other.
  std::array<unsigned char, 8> length{};
  for (std::size_t i = 0; i < length.size(); ++i) {
    length[i] = static_cast<unsigned char>(static_cast<std::uint64_t>(bytes.size()) >> (8 * i));
  }
  EVP_DigestUpdate(context(ctx_), length.data(), length.size());
  EVP_DigestUpdate(context(ctx_), bytes.data(), bytes.size());
}

std::string ContentHash::hex() const {
  EVP_MD_CTX* copy = EVP_MD_CTX_new();
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  const bool ok = copy != nullptr && EVP_MD_CTX_copy_ex(copy, context(ctx_)) == 1 &&
                  EVP_DigestFinal_ex(copy, digest, &size) == 1;
  EVP_MD_CTX_free(copy);
  if (!ok) throw Error("SHA-256 failed (OpenSSL)");
  return hex_of(digest, size);
}

std::string file_hash(const std::filesystem::path& path) {
  const std::string bytes = read_file(path, "file");
  unsigned char digest[EVP_MAX_MD_SIZE];
  unsigned int size = 0;
  if (EVP_Digest(bytes.data(), bytes.size(), digest, &size, EVP_sha256(), nullptr) != 1) {
    throw Error("SHA-256 failed (OpenSSL)");
  }
  return hex_of(digest, size);
}

}  // namespace phongsim
