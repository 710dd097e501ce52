#include <vimlop/Core/Sha256.h>

#include <vimlop/Core/FileError.h>

#include <cstring>
#include <fstream>
#include <vector>

namespace vimlop
{

namespace
{

// The first 32 bits of the fractional parts of the cube roots of the first
// 64 primes (FIPS 180-4, 4.2.2).
constexpr std::uint32_t K[64] = { 0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b,
  0x59f111f1, 0x923f82a4, 0xab1c5ed5, 0xd807aa98, 0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74,
  0x80deb1fe, 0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786, 0x0fc19dc6, 0x240ca1cc, 0x2de92c6f,
  0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8, 0xbf597fc7, 0xc6e00bf3,
  0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13, 0x650a7354,
  0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819,
  0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3,
  0x4ed8aa4a, 0x5b9cca4f, 0x682e6ff3, 0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa,
  0xa4506ceb, 0xbef9a3f7, 0xc67178f2 };

std::uint32_t rotr(std::uint32_t x, int n)
{
  return (x >> n) | (x << (32 - n));
}

} // namespace

Sha256::Sha256()
  // The first 32 bits of the fractional parts of the square roots of the
  // first 8 primes (FIPS 180-4, 5.3.3).
  : State{ 0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab,
    0x5be0cd19 }
{
}

void Sha256::block(const unsigned char* data)
{
  std::uint32_t w[64];
  for (int t = 0; t < 16; ++t)
  {
    w[t] = std::uint32_t(data[4 * t]) << 24 | std::uint32_t(data[4 * t + 1]) << 16 |
      std::uint32_t(data[4 * t + 2]) << 8 | std::uint32_t(data[4 * t + 3]);
  }
  for (int t = 16; t < 64; ++t)
  {
    const std::uint32_t s0 = rotr(w[t - 15], 7) ^ rotr(w[t - 15], 18) ^ (w[t - 15] >> 3);
    const std::uint32_t s1 = rotr(w[t - 2], 17) ^ rotr(w[t - 2], 19) ^ (w[t - 2] >> 10);
    w[t] = w[t - 16] + s0 + w[t - 7] + s1;
  }
  std::uint32_t a = State[0], b = State[1], c = State[2], d = State[3];
  std::uint32_t e = State[4], f = State[5], g = State[6], h = State[7];
  for (int t = 0; t < 64; ++t)
  {
    const std::uint32_t t1 =
      h + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + K[t] + w[t];
    const std::uint32_t t2 =
      (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
    h = g;
    g = f;
    f = e;
    e = d + t1;
    d = c;
    c = b;
    b = a;
    a = t1 + t2;
  }
  State[0] += a;
  State[1] += b;
  State[2] += c;
  State[3] += d;
  State[4] += e;
  State[5] += f;
  State[6] += g;
  State[7] += h;
}

void Sha256::update(const void* data, std::size_t size)
{
  const auto* bytes = static_cast<const unsigned char*>(data);
  this->LengthBytes += size;
  while (size > 0)
  {
    const std::size_t take = std::min(size, this->Buffer.size() - this->Buffered);
    std::memcpy(this->Buffer.data() + this->Buffered, bytes, take);
    this->Buffered += take;
    bytes += take;
    size -= take;
    if (this->Buffered == this->Buffer.size())
    {
      this->block(this->Buffer.data());
      this->Buffered = 0;
    }
  }
}

std::string Sha256::hex()
{
  // Padding: a 1 bit, zeros up to 56 bytes of the last block, the length in bits.
  const std::uint64_t bits = this->LengthBytes * 8;
  const unsigned char one = 0x80;
  this->update(&one, 1);
  const unsigned char zero = 0;
  while (this->Buffered != 56)
  {
    this->update(&zero, 1);
  }
  unsigned char length[8];
  for (int i = 0; i < 8; ++i)
  {
    length[i] = static_cast<unsigned char>(bits >> (56 - 8 * i));
  }
  this->update(length, 8);
  static const char digits[] = "0123456789abcdef";
  std::string text;
  for (std::uint32_t word : this->State)
  {
    for (int shift = 28; shift >= 0; shift -= 4)
    {
      text.push_back(digits[(word >> shift) & 0xf]);
    }
  }
  return text;
}

std::uint64_t Sha256::updateFromFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    throwFileError(path, "cannot read the file to identify it");
  }
  std::vector<char> chunk(1 << 20);
  std::uint64_t bytes = 0;
  while (in.read(chunk.data(), static_cast<std::streamsize>(chunk.size())) || in.gcount() > 0)
  {
    this->update(chunk.data(), static_cast<std::size_t>(in.gcount()));
    bytes += static_cast<std::uint64_t>(in.gcount());
  }
  if (in.bad())
  {
    throwFileError(path, "cannot read the file to identify it");
  }
  return bytes;
}

std::string Sha256::ofFile(const std::string& path)
{
  Sha256 digest;
  digest.updateFromFile(path);
  return digest.hex();
}

} // namespace vimlop
