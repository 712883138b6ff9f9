#pragma once
// FNV-1a, 64 bit: the one hash of the project (bond tables, checkpoint
// contents). Not cryptographic; it finds damaged bytes and mismatched inputs.
#include <cstdint>
#include <string>
#include <vector>

namespace mpsolid {

class Fnv1a {
 public:
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

}  // namespace mpsolid
