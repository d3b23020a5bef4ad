#pragma once
/// \file bytes.hpp
/// Native-order byte packing of plain values, shared by the binary formats of the sweep
/// (journal records, scenario records, messages between ranks and between a rank and its
/// scenario process). Every format that uses these is read back on the host that wrote it
/// or on one of the same endianness (x86-64, aarch64); record.cpp states that for its CRC.
#include <cstring>
#include <type_traits>
#include <vector>

namespace hexdyn {

/// Appends the bytes of `v` to `b`.
template <class T>
void put_pod(std::vector<char>& b, const T& v) {
  static_assert(std::is_trivially_copyable_v<T>);
  const std::size_t at = b.size();
  b.resize(at + sizeof v);
  std::memcpy(b.data() + at, &v, sizeof v);
}

/// The value whose bytes start at `p` (no alignment needed). Precondition: sizeof(T)
/// readable bytes at p.
template <class T>
T get_pod(const char* p) {
  static_assert(std::is_trivially_copyable_v<T>);
  T v;
  std::memcpy(&v, p, sizeof v);
  return v;
}

}  // namespace hexdyn
