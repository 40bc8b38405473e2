#include "svo/core/octree_file.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <vector>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/core/fnv1a.h"

namespace svo {
namespace {

constexpr char kMagic[8] = {'S', 'V', 'O', 'C', 'T', 'R', 'E', 'E'};

uint64_t bytesPerVoxel(uint32_t channels)
{
    return (channels & kNormals ? 12 : 0) + (channels & kTriangles ? 4 : 0) + (channels & kColors ? 12 : 0);
}

uint64_t payloadBytes(uint64_t levels, uint64_t nodes, uint64_t bricks)
{
    return 4 * levels + sizeof(OctreeNode) * nodes + sizeof(Brick) * bricks;
}

/// Voxels of the bricks in a payload, before the tree is checked.
uint64_t voxelsIn(const unsigned char* bricks, uint64_t count)
{
    uint64_t n = 0;
    for (uint64_t b = 0; b < count; ++b) {
        Brick brick;
        std::memcpy(&brick, bricks + b * sizeof(Brick), sizeof(Brick));
        n += brick.count();
    }
    return n;
}

} // namespace

void writeOctreeFile(const std::string& path, const Octree& input)
{
    const Octree o = canonicalOrder(input);
    OctreeFileHeader h{};
    std::memcpy(h.magic, kMagic, 8);
    h.version = kOctreeFileVersion;
    h.headerBytes = sizeof h;
    h.voxelSize = o.grid.voxelSize;
    for (int a = 0; a < 3; ++a) h.shift[a] = o.grid.shift[a], h.anchor[a] = o.grid.anchor[a], h.dims[a] = o.grid.dims[a];
    h.brickLevel = o.brickLevel;
    h.nodeCount = o.nodes.size();
    h.brickCount = o.bricks.size();
    h.channels = o.channels();
    h.fileBytes = sizeof h + payloadBytes(o.levelStart.size(), h.nodeCount, h.brickCount) +
                  bytesPerVoxel(h.channels) * o.voxelCount();

    std::vector<unsigned char> bytes(h.fileBytes);
    unsigned char* p = bytes.data() + sizeof h;
    auto put = [&](const void* src, size_t n) {
        if (n) std::memcpy(p, src, n);
        p += n;
    };
    put(o.levelStart.data(), 4 * o.levelStart.size());
    put(o.nodes.data(), sizeof(OctreeNode) * o.nodes.size());
    put(o.bricks.data(), sizeof(Brick) * o.bricks.size());
    put(o.attributes.normals.data(), sizeof(Vec3f) * o.attributes.normals.size());
    put(o.attributes.triangles.data(), sizeof(int32_t) * o.attributes.triangles.size());
    put(o.attributes.colors.data(), sizeof(Vec3f) * o.attributes.colors.size());
    std::memcpy(bytes.data(), &h, sizeof h); // checksum still zero
    h.checksum = fnv1a(bytes.data(), bytes.size());
    std::memcpy(bytes.data() + offsetof(OctreeFileHeader, checksum), &h.checksum, 8);

    writeFileAtomically(path, std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

Octree parseOctree(const void* data, size_t size, const std::string& name)
{
    auto fail = [&](const std::string& what) { return IoError(fmt::format("{}: not a valid .svo file: {}", name, what)); };
    const auto* bytes = static_cast<const unsigned char*>(data);
    if (size < sizeof(kMagic) || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
        throw fail("bad magic number (expected \"SVOCTREE\")");
    if (size < 16) throw fail(fmt::format("truncated header ({} bytes)", size));
    OctreeFileHeader h{};
    std::memcpy(&h, bytes, std::min(size, sizeof h));
    if (h.version != kOctreeFileVersion)
        throw fail(fmt::format("version {} is not supported (this svo reads version {})", h.version, kOctreeFileVersion));
    if (size < sizeof h) throw fail(fmt::format("truncated header ({} of {} bytes)", size, sizeof h));
    if (h.headerBytes != sizeof h) throw fail(fmt::format("header size {} (expected {})", h.headerBytes, sizeof h));
    if (h.brickLevel > 18) throw fail(fmt::format("brick level {} exceeds 18", h.brickLevel));
    if (h.nodeCount > (uint64_t(1) << 32) || h.brickCount > (uint64_t(1) << 32))
        throw fail(fmt::format("{} nodes and {} bricks exceed 32-bit indices", h.nodeCount, h.brickCount));
    if (h.channels & ~uint32_t(kNormals | kTriangles | kColors) || h.reserved)
        throw fail(fmt::format("unknown attribute channels {:#x}", h.channels));
    const uint64_t tree = sizeof h + payloadBytes(h.brickLevel + 2, h.nodeCount, h.brickCount);
    if (size < tree)
        throw fail(fmt::format("{} bytes, but the header's counts need at least {} (truncated)", size, tree));
    const uint64_t voxels = voxelsIn(bytes + tree - sizeof(Brick) * h.brickCount, h.brickCount);
    const uint64_t expected = tree + bytesPerVoxel(h.channels) * voxels;
    if (h.fileBytes != expected)
        throw fail(fmt::format("header says {} bytes, but its counts need {}", h.fileBytes, expected));
    if (size != h.fileBytes)
        throw fail(fmt::format("{} bytes, expected {} ({})", size, h.fileBytes, size < h.fileBytes ? "truncated" : "trailing data"));
    uint64_t sum = fnv1a(bytes, offsetof(OctreeFileHeader, checksum));
    const unsigned char zeros[8] = {};
    sum = fnv1a(zeros, 8, sum);
    sum = fnv1a(bytes + sizeof h, size - sizeof h, sum);
    if (sum != h.checksum) throw fail(fmt::format("checksum mismatch (stored {:016x}, computed {:016x})", h.checksum, sum));

    Octree o;
    o.grid.voxelSize = h.voxelSize;
    for (int a = 0; a < 3; ++a)
        o.grid.shift[a] = h.shift[a], o.grid.anchor[a] = h.anchor[a], o.grid.dims[a] = h.dims[a];
    try {
        checkGrid(o.grid, name + ": not a valid .svo file");
    } catch (const InvalidInput& e) {
        throw IoError(e.what()); // the file's grid, not the caller's
    }
    o.brickLevel = h.brickLevel;
    const unsigned char* p = bytes + sizeof h;
    o.levelStart.resize(h.brickLevel + 2);
    std::memcpy(o.levelStart.data(), p, 4 * o.levelStart.size());
    p += 4 * o.levelStart.size();
    o.nodes.resize(h.nodeCount);
    if (h.nodeCount) std::memcpy(o.nodes.data(), p, sizeof(OctreeNode) * h.nodeCount);
    p += sizeof(OctreeNode) * h.nodeCount;
    o.bricks.resize(h.brickCount);
    if (h.brickCount) std::memcpy(o.bricks.data(), p, sizeof(Brick) * h.brickCount);
    p += sizeof(Brick) * h.brickCount;
    auto take = [&](auto& channel, uint32_t bit) {
        if (!(h.channels & bit)) return;
        channel.resize(voxels);
        std::memcpy(channel.data(), p, sizeof(channel[0]) * voxels);
        p += sizeof(channel[0]) * voxels;
    };
    take(o.attributes.normals, kNormals);
    take(o.attributes.triangles, kTriangles);
    take(o.attributes.colors, kColors);
    o.attributes.computed = h.channels; // also where no voxel holds them
    const auto problems = checkOctree(o, 1);
    if (!problems.empty()) throw fail(problems.front());
    return o;
}

Octree readOctreeFile(const std::string& path)
{
    std::error_code ec;
    const auto size = std::filesystem::file_size(path, ec);
    if (ec) throw IoError(fmt::format("{}: cannot open the file: {}", path, ec.message()));
    if (size == 0) throw IoError(fmt::format("{}: the file is empty", path));
    std::ifstream in(path, std::ios::binary);
    std::vector<char> bytes(size);
    if (!in || !in.read(bytes.data(), std::streamsize(size))) throw IoError(fmt::format("{}: read error", path));
    return parseOctree(bytes.data(), bytes.size(), path);
}

} // namespace svo
