#pragma once
/// @file text_chunks.h (internal)
/// Cutting a text file at line ends into pieces that threads parse at once.
#include <cstddef>
#include <cstring>
#include <string_view>
#include <vector>

namespace svo::detail {

/// Pieces of about this many bytes are what the readers parse in parallel
/// (their default `chunkBytes`); a file of fewer than two pieces is read by
/// one thread, on their one-piece path.
constexpr size_t kTextChunkBytes = size_t(1) << 20;

/// `text` cut into consecutive pieces of at least `bytes` bytes, each ending
/// just after a '\n' (the last at the end of the text), where `mayCut(newline)`
/// allows a cut after that newline (OBJ: not inside a `\` continued statement).
template <typename MayCut>
std::vector<std::string_view> cutAtLines(std::string_view text, size_t bytes, MayCut&& mayCut)
{
    std::vector<std::string_view> pieces;
    size_t start = 0;
    while (start < text.size()) {
        size_t cut = text.size();
        for (size_t at = start + bytes; at < text.size();) {
            const void* nl = std::memchr(text.data() + at, '\n', text.size() - at);
            if (!nl) break;
            const size_t pos = size_t(static_cast<const char*>(nl) - text.data());
            if (mayCut(pos)) {
                cut = pos + 1;
                break;
            }
            at = pos + 1;
        }
        pieces.push_back(text.substr(start, cut - start));
        start = cut;
    }
    return pieces;
}

} // namespace svo::detail
