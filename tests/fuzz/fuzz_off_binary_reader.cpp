// libFuzzer target: binary OFF bodies (fuzz_mesh_reader.h says what must
// hold). The first byte picks the header line, so that mutations spend
// themselves on the big-endian counts, vertices and faces rather than on
// finding the one keyword line that makes a body binary.
#include <cstdint>
#include <string>

#include "fuzz_mesh_reader.h"
#include "off_reader.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    if (size == 0) return 0;
    // Every layout the reader knows, and a few it must refuse.
    static const char* const headers[] = {"OFF",    "COFF",    "NOFF",     "STOFF",  "CNOFF",
                                          "STCOFF", "STCNOFF", "NCOFF",    "CCOFF",  "4OFF",
                                          "XOFF",   "OFF",     "# c\nOFF", "nOFF"};
    const std::string header = std::string(headers[data[0] % (sizeof headers / sizeof *headers)]) + " BINARY\n";
    std::string bytes = header;
    bytes.append(reinterpret_cast<const char*>(data) + 1, size - 1);
    return fuzzMeshReader(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(),
                          [](const std::string& b) { return svo::detail::readOff("fuzz.off", b); });
}
