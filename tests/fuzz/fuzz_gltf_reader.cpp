// libFuzzer target: the glTF reader, text and binary (fuzz_mesh_reader.h says
// what must hold). No external files are read; the scene is capped at 2^20
// vertices so that instancing cannot ask for more memory than a run has.
#include "fuzz_mesh_reader.h"
#include "gltf_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    svo::detail::GltfReadOptions options;
    options.externalFiles = false;
    options.maxVertices = 1 << 20;
    return fuzzMeshReader(data, size,
                          [&](const std::string& bytes) { return svo::detail::readGltf("fuzz.gltf", bytes, options); });
}
