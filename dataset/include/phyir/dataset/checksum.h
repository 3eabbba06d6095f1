#pragma once
// SHA-256 through OpenSSL's EVP interface (Debian libssl-dev), for the manifest's file
// checksums and for every key the dataset derives from names (splits, per-view seeds).
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace phyir::dataset {

// Lower-case hex digest (64 characters).
std::string sha256_hex(const void* data, size_t size);
inline std::string sha256_hex(const std::string& bytes) { return sha256_hex(bytes.data(), bytes.size()); }

// Streams the file. Throws phyir::Error naming the file when it cannot be read.
std::string sha256_file(const std::filesystem::path& path);

// The first 8 bytes of SHA-256(text), big-endian: a 64-bit key that is the same on every
// machine and compiler (std::hash is not), for splits, seeds and jitter.
uint64_t hash64(const std::string& text);

// hash64 mapped to [0, 1) with 53 random bits (every value an exact double).
double hash_unit(const std::string& text);

}  // namespace phyir::dataset
