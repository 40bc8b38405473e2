// libFuzzer target: the OBJ reader (fuzz_mesh_reader.h says what must hold).
// Every material library an `mtllib` names reads as the input itself, so the
// same bytes drive the .mtl reader and the colouring by material too; a name
// starting with "missing" is not found.
#include "fuzz_mesh_reader.h"
#include "obj_reader.h"

namespace {

svo::detail::MaterialFiles itself(const std::string& bytes)
{
    return [&bytes](const std::string& name) -> std::optional<std::string> {
        if (name.rfind("missing", 0) == 0) return std::nullopt;
        return bytes;
    };
}

} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    sameInPieces(
        data, size,
        [](const std::string& b) { return svo::detail::readObj("fuzz.obj", b, size_t(1) << 40, nullptr, itself(b)); },
        [](const std::string& b) { return svo::detail::readObj("fuzz.obj", b, 7, nullptr, itself(b)); });
    return fuzzMeshReader(data, size, [](const std::string& bytes) {
        return svo::detail::readObj("fuzz.obj", bytes, svo::detail::kTextChunkBytes, nullptr, itself(bytes));
    });
}
