#pragma once
// Fixed-width signed integers for the exact fallback of the exact kernel's predicates
// (geometry/exact_predicates.h): the determinants there need up to 380 bits, more than any
// built-in type, and their width is bounded by construction, so a fixed width with wrap-around
// arithmetic is exact as long as the final result fits (arithmetic modulo 2^(64L) is a ring, so
// intermediate wrap-around cancels), which the callers prove (never checked
// at run time: the bound is the contract).
//
// Notation: a WideInt<L> holds L little-endian 64-bit limbs in two's complement, so it represents
// every integer in [-2^(64L-1), 2^(64L-1)); +, - and * are computed modulo 2^(64L).
#include <array>
#include <cstdint>

namespace bsp {

using Int128 = __int128;

template <int Limbs>
class WideInt {
  static_assert(Limbs >= 2);

 public:
  constexpr WideInt() : limb_{} {}
  constexpr WideInt(Int128 v) : limb_{} {  // NOLINT: widening, never loses a value
    limb_[0] = static_cast<std::uint64_t>(v);
    limb_[1] = static_cast<std::uint64_t>(v >> 64);
    const std::uint64_t fill = v < 0 ? ~std::uint64_t{0} : 0;
    for (int i = 2; i < Limbs; ++i) limb_[i] = fill;
  }

  // Sign-extends a narrower integer (same value).
  template <int Narrower>
  constexpr explicit WideInt(const WideInt<Narrower>& v) : limb_{} {
    static_assert(Narrower <= Limbs, "widening only");
    for (int i = 0; i < Narrower; ++i) limb_[i] = v.limb(i);
    const std::uint64_t fill = v.sign() < 0 ? ~std::uint64_t{0} : 0;
    for (int i = Narrower; i < Limbs; ++i) limb_[i] = fill;
  }

  constexpr WideInt operator+(const WideInt& o) const {
    WideInt r;
    unsigned carry = 0;
    for (int i = 0; i < Limbs; ++i) {
      const unsigned __int128 s = static_cast<unsigned __int128>(limb_[i]) + o.limb_[i] + carry;
      r.limb_[i] = static_cast<std::uint64_t>(s);
      carry = static_cast<unsigned>(s >> 64);
    }
    return r;
  }
  constexpr WideInt operator-() const {
    WideInt r;
    for (int i = 0; i < Limbs; ++i) r.limb_[i] = ~limb_[i];
    return r + WideInt(1);
  }
  constexpr WideInt operator-(const WideInt& o) const { return *this + -o; }
  // Schoolbook product, truncated to Limbs limbs: the true product when it fits (two's complement
  // multiplication modulo 2^(64L) needs no sign handling).
  constexpr WideInt operator*(const WideInt& o) const {
    WideInt r;
    for (int i = 0; i < Limbs; ++i) {
      std::uint64_t carry = 0;
      for (int j = 0; i + j < Limbs; ++j) {
        const unsigned __int128 p =
            static_cast<unsigned __int128>(limb_[i]) * o.limb_[j] + r.limb_[i + j] + carry;
        r.limb_[i + j] = static_cast<std::uint64_t>(p);
        carry = static_cast<std::uint64_t>(p >> 64);
      }
    }
    return r;
  }

  // -1, 0 or +1.
  constexpr int sign() const {
    if (limb_[Limbs - 1] >> 63) return -1;
    for (int i = 0; i < Limbs; ++i)
      if (limb_[i] != 0) return 1;
    return 0;
  }
  constexpr std::uint64_t limb(int i) const { return limb_[i]; }
  // The nearest double within a few units in the last place (for output, never for a decision).
  double to_double() const {
    if (sign() < 0) return -(-*this).to_double();
    double v = 0;
    for (int i = Limbs - 1; i >= 0; --i) v = v * 0x1p64 + static_cast<double>(limb_[i]);
    return v;
  }

 private:
  std::array<std::uint64_t, Limbs> limb_;
};

}  // namespace bsp
