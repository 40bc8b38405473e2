#pragma once
/// @file fnv1a.h
/// @brief 64-bit FNV-1a: the checksum of .svo files and the key of cached GL program
/// binaries. Fast and stable across runs and platforms; not cryptographic.
#include <cstddef>
#include <cstdint>

namespace svo {

/// @brief The FNV-1a offset basis: the hash of no bytes.
constexpr uint64_t kFnv1aBasis = 0xcbf29ce484222325ull;

/// @brief Continues a hash over @a n bytes at @a p.
/// @param h the hash so far (kFnv1aBasis to start)
/// @return the hash of the bytes hashed into @a h followed by these
inline uint64_t fnv1a(const void* p, size_t n, uint64_t h = kFnv1aBasis)
{
    const auto* b = static_cast<const unsigned char*>(p);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
    return h;
}

} // namespace svo
