// libFuzzer target: the PLY reader (fuzz_mesh_reader.h says what must hold).
#include "fuzz_mesh_reader.h"
#include "ply_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    sameInPieces(
        data, size, [](const std::string& b) { return svo::detail::readPly("fuzz.ply", b, size_t(1) << 40); },
        [](const std::string& b) { return svo::detail::readPly("fuzz.ply", b, 1); });
    return fuzzMeshReader(data, size, [](const std::string& bytes) { return svo::detail::readPly("fuzz.ply", bytes); });
}
