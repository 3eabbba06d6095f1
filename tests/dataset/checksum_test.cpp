// SHA-256 through OpenSSL against the FIPS 180-2 test vectors, files streamed in chunks,
// and the 64-bit keys derived from it (stable values, so seeds and splits never drift).
#include <gtest/gtest.h>

#include "dataset_test_helpers.h"
#include "phyir/core/error.h"
#include "phyir/dataset/checksum.h"

namespace phyir::dataset {
namespace {

TEST(Checksum, KnownVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Checksum, FileMatchesBytesAcrossChunks) {
  const auto dir = test::fresh_test_dir();
  std::string big(3 * (1 << 20) + 17, '\0');  // spans several 1 MiB reads
  for (size_t i = 0; i < big.size(); ++i) big[i] = static_cast<char>((i * 131) % 251);
  write_file_atomic(dir / "big.bin", big);
  EXPECT_EQ(sha256_file(dir / "big.bin"), sha256_hex(big));
  EXPECT_THROW(sha256_file(dir / "absent.bin"), Error);
}

TEST(Checksum, Hash64IsTheDigestPrefix) {
  // "abc" -> ba7816bf8f01cfea...
  EXPECT_EQ(hash64("abc"), 0xba7816bf8f01cfeaull);
  const double u = hash_unit("abc");
  EXPECT_GE(u, 0.0);
  EXPECT_LT(u, 1.0);
  EXPECT_DOUBLE_EQ(u, double(0xba7816bf8f01cfeaull >> 11) * 0x1p-53);
}

}  // namespace
}  // namespace phyir::dataset
