#pragma once
// FNV-1a, 64 bit: the one hash of the project (bond tables, checkpoint
// contents); and the hash of an array whose terms add (placed_array_hash),
// for arrays that ranks write in parts. Not cryptographic; they find damaged
// bytes and mismatched inputs.
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace mpsolid {

class Fnv1a {
 public:
  Fnv1a() = default;
  // Goes on from another hash's value: bytes hashed in parts, one after the
  // other (each rank its rows), give the hash of them all.
  explicit Fnv1a(std::uint64_t value) : h_(value) {}
  void bytes(const void* data, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < n; ++k) h_ = (h_ ^ c[k]) * 1099511628211ull;
  }
  template <class T>
  void value(T v) {
    bytes(&v, sizeof v);
  }
  // The length, then the characters: "ab" + "c" and "a" + "bc" differ.
  void text(const std::string& s) {
    value<std::uint64_t>(s.size());
    bytes(s.data(), s.size());
  }
  template <class T>
  void add(const std::vector<T>& values) {
    bytes(values.data(), values.size() * sizeof(T));
  }
  std::uint64_t value() const { return h_; }

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};

// One value's term of an array's hash: its bits mixed with its position
// (splitmix64's finaliser). An array's hash is the sum of its terms modulo
// 2^64, so any split of the positions between ranks, summed in any order,
// gives the same hash; a changed or moved value changes it but for a chance
// of 2^-64.
inline std::uint64_t mix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  return z ^ (z >> 31);
}
inline std::uint64_t placed_term(std::uint64_t position, double value) {
  std::uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return mix64(bits ^ mix64(position));
}
// The hash of a whole array, value k at position k.
inline std::uint64_t placed_array_hash(const std::vector<double>& values) {
  std::uint64_t sum = 0;
  for (std::size_t k = 0; k < values.size(); ++k) sum += placed_term(k, values[k]);
  return sum;
}

}  // namespace mpsolid
