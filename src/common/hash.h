#pragma once
// A stable 64-bit content hash (FNV-1a over explicit little-endian bytes), identical on every
// machine; used for scene hashes that are pinned in tests and carried into every report.
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace bsp {

class Hasher {
 public:
  void add_u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) add_byte(static_cast<unsigned char>(v >> (8 * i)));
  }
  void add_double(double d) {
    if (d == 0.0) d = 0.0;  // -0 and +0 hash alike
    add_u64(std::bit_cast<std::uint64_t>(d));
  }
  void add_string(std::string_view s) {
    add_u64(s.size());
    for (char c : s) add_byte(static_cast<unsigned char>(c));
  }
  std::uint64_t value() const { return h_; }
  std::string hex() const;

 private:
  void add_byte(unsigned char b) {
    h_ ^= b;
    h_ *= 0x100000001b3ULL;
  }
  std::uint64_t h_ = 0xcbf29ce484222325ULL;
};

inline std::string Hasher::hex() const {
  static const char* digits = "0123456789abcdef";
  std::string s(16, '0');
  for (int i = 0; i < 16; ++i) s[15 - i] = digits[(h_ >> (4 * i)) & 0xf];
  return s;
}

}  // namespace bsp
