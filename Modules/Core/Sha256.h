#ifndef vimlop_Sha256_h
#define vimlop_Sha256_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>

namespace vimlop
{

/**
 * @brief SHA-256 (FIPS 180-4), fed in pieces: the digest that identifies an
 * input file in a result folder, so that a result names exactly the CT,
 * frames and calibration it came from.
 */
class Sha256
{
public:
  Sha256();
  /// @brief Adds `size` bytes to the message.
  void update(const void* data, std::size_t size);
  void update(const std::string& bytes) { this->update(bytes.data(), bytes.size()); }
  /// @brief Adds a file's bytes; returns how many. @throws vimlop::Error when it cannot be read.
  std::uint64_t updateFromFile(const std::string& path);
  /// @brief The digest of everything added, as 64 lower-case hex digits; ends the message.
  std::string hex();

  /// @brief The digest of a file's bytes. @throws vimlop::Error when it cannot be read.
  static std::string ofFile(const std::string& path);

private:
  void block(const unsigned char* data);

  std::array<std::uint32_t, 8> State;
  std::array<unsigned char, 64> Buffer{};
  std::size_t Buffered = 0;
  std::uint64_t LengthBytes = 0;
};

} // namespace vimlop

#endif
