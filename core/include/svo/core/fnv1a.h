#pragma once
/// @file fnv1a.h
/// 64-bit FNV-1a: the checksum of .svo files and the key of cached GL program
/// binaries. Fast and stable across runs and platforms; not cryptographic.
#include <cstddef>
#include <cstdint>

namespace svo {

constexpr uint64_t kFnv1aBasis = 0xcbf29ce484222325ull;

/// Continues the hash `h` over `n` bytes at `p` (start with kFnv1aBasis).
inline uint64_t fnv1a(const void* p, size_t n, uint64_t h = kFnv1aBasis)
{
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

} // namespace svo
