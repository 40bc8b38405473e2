// libFuzzer target: the .svo reader must turn any bytes into an octree that
// passes checkOctree, or into svo::Error; nothing else (no crash, no other
// exception, no out-of-bounds access under AddressSanitizer). Each input is
// also tried with its checksum recomputed, so that mutations get past the
// checksum to the header and structure checks behind it.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "one_thread.h"
#include "svo/core/error.h"
#include "svo/core/octree_file.h"

namespace {

void parse(const uint8_t* data, size_t size)
{
    try {
        const svo::Octree o = svo::parseOctree(data, size, "fuzz.svo");
        if (!svo::checkOctree(o).empty()) std::abort(); // accepted an unsound octree
        (void)svo::octreeKeys(o);
        (void)svo::canonicalOrder(o);
    } catch (const svo::Error&) {
    }
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    parse(data, size);
    if (size >= sizeof(svo::OctreeFileHeader)) {
        std::vector<uint8_t> signed_(data, data + size);
        const size_t at = offsetof(svo::OctreeFileHeader, checksum);
        std::memset(signed_.data() + at, 0, 8);
        uint64_t h = 0xcbf29ce484222325ull; // FNV-1a 64, as octree_file.h specifies
        for (uint8_t b : signed_) h = (h ^ b) * 0x100000001b3ull;
        std::memcpy(signed_.data() + at, &h, 8);
        parse(signed_.data(), signed_.size());
    }
    return 0;
}
