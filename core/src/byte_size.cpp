#include "svo/core/byte_size.h"

#include <fmt/format.h>

namespace svo {

std::string byteSize(uint64_t bytes)
{
    if (bytes < (uint64_t(1) << 20)) return fmt::format("{:.1f} KiB", double(bytes) / 1024);
    if (bytes < (uint64_t(1) << 30)) return fmt::format("{:.1f} MiB", double(bytes) / (1 << 20));
    return fmt::format("{:.2f} GiB", double(bytes) / (1 << 30));
}

} // namespace svo
