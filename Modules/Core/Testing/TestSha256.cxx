#include <vimlop/Core/Error.h>
#include <vimlop/Core/Sha256.h>

#include "ErrorMessage.h"
#include "TestFolders.h"

#include <gtest/gtest.h>

#include <fstream>

using namespace vimlop;

namespace
{

std::string digestOf(const std::string& message)
{
  Sha256 digest;
  digest.update(message);
  return digest.hex();
}

} // namespace

TEST(Sha256, GivesTheDigestsOfTheStandardsExamples)
{
  // FIPS 180-4's examples (one block, two blocks) and the empty message.
  EXPECT_EQ(digestOf(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(digestOf("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(digestOf("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
    "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
}

TEST(Sha256, PiecesOfAnySizeGiveTheDigestOfTheWhole)
{
  // A million 'a', fed in pieces of 1 to 997 bytes that straddle the blocks.
  Sha256 digest;
  std::size_t fed = 0;
  for (std::size_t piece = 1; fed < 1000000; piece = piece % 997 + 1)
  {
    const std::size_t n = std::min(piece, 1000000 - fed);
    digest.update(std::string(n, 'a'));
    fed += n;
  }
  EXPECT_EQ(digest.hex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Sha256, AFileIsIdentifiedByItsBytesAndAMissingOneIsNamed)
{
  const std::string path = (fixtures::freshTestFolder("sha256") / "abc.txt").string();
  std::ofstream(path, std::ios::binary) << "abc";
  EXPECT_EQ(
    Sha256::ofFile(path), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(fixtures::errorMessageOf([&] { Sha256::ofFile(path + ".missing"); }),
    "'" + path + ".missing': cannot read the file to identify it");
}
