// libFuzzer target: the OBJ reader (fuzz_mesh_reader.h says what must hold).
#include "fuzz_mesh_reader.h"
#include "obj_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    sameInPieces(
        data, size, [](const std::string& b) { return svo::detail::readObj("fuzz.obj", b, size_t(1) << 40); },
        [](const std::string& b) { return svo::detail::readObj("fuzz.obj", b, 7); });
    return fuzzMeshReader(data, size, [](const std::string& bytes) { return svo::detail::readObj("fuzz.obj", bytes); });
}
