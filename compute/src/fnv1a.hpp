// 64-bit FNV-1a, the cache files' names and keys (pipeline.cpp's folded
// SPIR-V, march.cpp's connection seeds). Not installed.
#pragma once

#include <cstdint>
#include <string_view>

namespace sol::vk::detail {

inline constexpr std::uint64_t kFnvOffset = 0xcbf29ce484222325ull;

/// One byte into the hash.
inline std::uint64_t fnv1a(std::uint64_t hash, unsigned char byte) { return (hash ^ byte) * 0x100000001b3ull; }

/// A 32-bit word, byte by byte (little-endian order).
inline std::uint64_t fnv1a(std::uint64_t hash, std::uint32_t word) {
  for (int byte = 0; byte < 4; ++byte) hash = fnv1a(hash, static_cast<unsigned char>((word >> (8 * byte)) & 0xffu));
  return hash;
}

/// The bytes of a text.
inline std::uint64_t fnv1a(std::uint64_t hash, std::string_view text) {
  for (const char ch : text) hash = fnv1a(hash, static_cast<unsigned char>(ch));
  return hash;
}

}  // namespace sol::vk::detail
