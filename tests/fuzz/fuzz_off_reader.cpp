// libFuzzer target: the OFF reader (ASCII and binary) and mesh validation
// must turn any bytes into a valid mesh or into svo::Error, the same whether
// an ASCII body is read whole or in pieces (a binary body is one piece).
#include <cstdint>
#include <string>

#include "fuzz_mesh_reader.h"
#include "off_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    // Read whole and in pieces of 7 bytes: the same.
    auto read = [](size_t chunk) {
        return [chunk](const std::string& b) { return svo::detail::readOff("fuzz.off", b, chunk); };
    };
    sameInPieces(data, size, read(size_t(1) << 40), read(7));
    return fuzzMeshReader(data, size, [](const std::string& bytes) { return svo::detail::readOff("fuzz.off", bytes); });
}
