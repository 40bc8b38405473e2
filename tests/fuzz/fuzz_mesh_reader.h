#pragma once
// What every mesh-reader fuzz target asserts: any bytes through the reader and
// mesh validation give a mesh whose indices are in range (and colours, if
// any, one per vertex), or svo::Error; anything else aborts.
#include <cstdint>
#include <cstdlib>
#include <string>

#include "svo/core/error.h"
#include "svo/core/mesh.h"

template <typename Read>
int fuzzMeshReader(const uint8_t* data, size_t size, Read read)
{
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    try {
        const svo::TriangleMesh mesh = read(bytes);
        svo::validateMesh(mesh);
        for (const auto& t : mesh.triangles)
            for (uint32_t v : t)
                if (v >= mesh.positions.size()) std::abort(); // validation let a bad index through
        if (!mesh.colors.empty() && mesh.colors.size() != mesh.positions.size()) std::abort();
    } catch (const svo::Error&) {
    }
    return 0;
}
