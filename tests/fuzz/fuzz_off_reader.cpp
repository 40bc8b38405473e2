// libFuzzer target: the ASCII OFF reader and mesh validation must turn any
// bytes into a valid mesh or into svo::Error, the same whether the body is
// read whole or in pieces.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "fuzz_mesh_reader.h"
#include "off_reader.h"
#include "svo/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    // Read whole and in pieces of 7 bytes: the same (a binary OFF reads as an empty mesh in both).
    auto read = [](size_t chunk) {
        return [chunk](const std::string& b) {
            auto m = svo::detail::readAsciiOff("fuzz.off", b, chunk);
            return m ? std::move(*m) : svo::TriangleMesh{};
        };
    };
    sameInPieces(data, size, read(size_t(1) << 40), read(7));
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        auto mesh = svo::detail::readAsciiOff("fuzz.off", bytes);
        if (mesh) {
            svo::validateMesh(*mesh);
            for (const auto& t : mesh->triangles)
                for (uint32_t v : t)
                    if (v >= mesh->positions.size()) std::abort(); // validation let a bad index through
        }
    } catch (const svo::Error&) {
    }
    return 0;
}
