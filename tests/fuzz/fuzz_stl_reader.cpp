// libFuzzer target: the STL reader and mesh validation must turn any bytes
// into a valid mesh or into svo::Error.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "stl_reader.h"
#include "svo/core/error.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const auto mesh = svo::detail::readStl("fuzz.stl", bytes);
        svo::validateMesh(mesh);
        for (const auto& t : mesh.triangles)
            for (uint32_t v : t)
                if (v >= mesh.positions.size()) std::abort(); // validation let a bad index through
        if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) std::abort();
    } catch (const svo::Error&) {
    }
    return 0;
}
