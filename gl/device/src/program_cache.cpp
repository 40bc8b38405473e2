#include "program_cache.h"

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/core/fnv1a.h"

namespace svo::gl {
namespace {

namespace fs = std::filesystem;

constexpr char kMagic[8] = {'S', 'V', 'O', 'P', 'R', 'O', 'G', '1'};

/// An entry: this header, the identity, then the driver's binary. Native
/// byte order: an entry is only ever read where it was written.
struct EntryHeader {
    char magic[8];
    uint32_t format;        ///< the binary's format, from glGetProgramBinary
    uint32_t identityBytes;
    uint64_t binaryBytes;
    uint64_t checksum;      ///< FNV-1a of the identity, then the binary
};
static_assert(sizeof(EntryHeader) == 32, "the entry header has no padding");

std::string readFile(const std::string& path)
{
    std::ifstream in(path, std::ios::binary);
    if (!in) return {};
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

} // namespace

std::string programCacheFolder(const std::string& option)
{
    if (option == "off") return {};
    if (!option.empty()) return option;
    if (const char* env = std::getenv("SVO_PROGRAM_CACHE"))
        return *env && std::strcmp(env, "off") != 0 ? std::string(env) : std::string();
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return (fs::path(xdg) / "svo" / "programs").string();
    if (const char* home = std::getenv("HOME"); home && *home)
        return (fs::path(home) / ".cache" / "svo" / "programs").string();
    return {};
}

ProgramCache::ProgramCache(std::string folder, std::string driver) : folder_(std::move(folder)), driver_(std::move(driver))
{
}

std::string ProgramCache::identity(const ProgramSource& source) const
{
    std::string id = driver_;
    for (const auto& [file, src] : source.stages) {
        id += '\0';
        id += file;
        id += '\0';
        id += src.text;
    }
    return id;
}

std::string ProgramCache::entryPath(const ProgramSource& source) const
{
    const std::string id = identity(source);
    return (fs::path(folder_) / fmt::format("{:016x}.bin", fnv1a(id.data(), id.size()))).string();
}

std::optional<Program> ProgramCache::load(const ProgramSource& source, Lookup& how) const
{
    how = Lookup::Absent;
    if (!enabled()) return std::nullopt;
    const std::string bytes = readFile(entryPath(source));
    if (bytes.empty()) return std::nullopt;
    how = Lookup::Refused;
    EntryHeader h{};
    if (bytes.size() < sizeof h) return std::nullopt;
    std::memcpy(&h, bytes.data(), sizeof h);
    const std::string id = identity(source);
    if (std::memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.identityBytes != id.size() ||
        bytes.size() != sizeof h + h.identityBytes + h.binaryBytes || bytes.compare(sizeof h, id.size(), id) != 0)
        return std::nullopt;
    if (fnv1a(bytes.data() + sizeof h, bytes.size() - sizeof h) != h.checksum) return std::nullopt;
    const std::vector<uint8_t> binary(bytes.begin() + std::ptrdiff_t(sizeof h + id.size()), bytes.end());
    std::optional<Program> program = Program::fromBinary(source, GLenum(h.format), binary);
    if (program) how = Lookup::Loaded;
    return program;
}

std::string ProgramCache::store(const ProgramSource& source, const Program& program)
{
    if (!enabled() || !writable_) return {};
    GLenum format = 0;
    const std::vector<uint8_t> binary = program.binary(format);
    if (binary.empty()) {
        writable_ = false;
        return fmt::format("the driver returns no binary for program {}, so programs are not cached", source.name);
    }
    const std::string id = identity(source);
    EntryHeader h{};
    std::memcpy(h.magic, kMagic, sizeof kMagic);
    h.format = format;
    h.identityBytes = uint32_t(id.size());
    h.binaryBytes = binary.size();
    h.checksum = fnv1a(binary.data(), binary.size(), fnv1a(id.data(), id.size()));
    std::string bytes(reinterpret_cast<const char*>(&h), sizeof h);
    bytes += id;
    bytes.append(reinterpret_cast<const char*>(binary.data()), binary.size());
    try {
        std::error_code ec;
        fs::create_directories(folder_, ec);
        if (ec) throw IoError(fmt::format("{}: {}", folder_, ec.message()));
        writeFileAtomically(entryPath(source), bytes);
    } catch (const std::exception& e) {
        writable_ = false; // one warning; the cache still reads
        return fmt::format("the program cache cannot be written, so programs are compiled on each start ({}); set "
                           "SVO_PROGRAM_CACHE to another folder or to off",
                           e.what());
    }
    return {};
}

} // namespace svo::gl
