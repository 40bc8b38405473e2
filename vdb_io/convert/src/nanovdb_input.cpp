#include "svo/vdb_io/nanovdb_input.h"

#include <algorithm>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iterator>
#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/GridHandle.h>
#include <nanovdb/util/GridValidator.h>
#include <nanovdb/util/HostBuffer.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/NanoToOpenVDB.h>
#include <vector>

#include "svo/core/error.h"
#include "svo/vdb_io/grid_builder.h"

#ifdef NANOVDB_USE_ZIP
#include <zlib.h>
#endif
#ifdef NANOVDB_USE_BLOSC
#include <blosc.h>
#endif

namespace svo::vdb {
namespace fs = std::filesystem;
namespace {

[[noreturn]] void damaged(const std::string& name, const std::string& why)
{
    throw IoError(fmt::format("{}: truncated or damaged: {}", name, why));
}

/// A grid's bytes, copied out of the file into a 32-byte aligned buffer, with
/// the segment's record of it.
struct RawGrid {
    nanovdb::io::MetaData meta;
    std::string metaName;
    nanovdb::io::Codec codec;
    uint32_t version;
    nanovdb::HostBuffer buffer;
};

const char* typeName(nanovdb::GridType t)
{
    return uint32_t(t) < uint32_t(nanovdb::GridType::End) ? nanovdb::toStr(t) : "unknown";
}

/// NanoVDB's codecs, as nanovdb/util/IO.h writes them: Zip is one block,
/// Blosc one block per GiB, each block a uint64 byte count and the data.
/// Every count is checked against the file before it is read.
struct CompressedBlock {
    const char* data;
    uint64_t bytes;
};

CompressedBlock nextBlock(const char*& at, const char* end, const std::string& name, const std::string& gn)
{
    uint64_t bytes = 0;
    if (end - at < 8) damaged(name, fmt::format("{} ends inside a compressed block's size", gn));
    std::memcpy(&bytes, at, 8);
    at += 8;
    if (bytes > uint64_t(end - at))
        damaged(name, fmt::format("{}'s compressed block of {} bytes does not fit in its {} bytes", gn, bytes, end - at));
    const CompressedBlock block{at, bytes};
    at += bytes;
    return block;
}

/// Decodes @a bytes (the grid's record in the file) into @a out, sized to the grid.
void decode(nanovdb::io::Codec codec, const char* bytes, uint64_t fileSize, nanovdb::HostBuffer& out,
            const std::string& name, const std::string& gn)
{
    const char* at = bytes;
    const char* end = bytes + fileSize;
    char* dst = reinterpret_cast<char*>(out.data());
    const uint64_t gridSize = out.size();
#ifdef NANOVDB_USE_ZIP
    if (codec == nanovdb::io::Codec::ZIP) {
        const CompressedBlock b = nextBlock(at, end, name, gn);
        uLongf n = uLongf(gridSize);
        if (uncompress(reinterpret_cast<Bytef*>(dst), &n, reinterpret_cast<const Bytef*>(b.data), uLong(b.bytes)) != Z_OK ||
            n != gridSize)
            damaged(name, fmt::format("{}'s Zip data does not decompress to its {} bytes", gn, gridSize));
    }
#endif
#ifdef NANOVDB_USE_BLOSC
    if (codec == nanovdb::io::Codec::BLOSC) {
        constexpr uint64_t kChunk = uint64_t(1) << 30; // IO.h's block size
        for (uint64_t done = 0; done < gridSize;) {
            const CompressedBlock b = nextBlock(at, end, name, gn);
            const uint64_t chunk = std::min(kChunk, gridSize - done);
            size_t raw = 0, packed = 0, blocksize = 0;
            if (b.bytes >= BLOSC_MIN_HEADER_LENGTH) blosc_cbuffer_sizes(b.data, &raw, &packed, &blocksize);
            if (raw != chunk || packed != b.bytes ||
                blosc_decompress_ctx(b.data, dst + done, size_t(chunk), 1) != int(chunk))
                damaged(name, fmt::format("{}'s Blosc data does not decompress to its {} bytes", gn, gridSize));
            done += chunk;
        }
    }
#endif
    if (at != end)
        damaged(name, fmt::format("{}'s compressed data ends {} bytes before its record does", gn, end - at));
}

bool codecBuiltIn(nanovdb::io::Codec codec)
{
    switch (codec) {
    case nanovdb::io::Codec::NONE: return true;
#ifdef NANOVDB_USE_ZIP
    case nanovdb::io::Codec::ZIP: return true;
#endif
#ifdef NANOVDB_USE_BLOSC
    case nanovdb::io::Codec::BLOSC: return true;
#endif
    default: return false;
    }
}

/// The segments of a whole file: headers and records inside the file, sizes
/// consistent, the file ending where its last grid does.
std::vector<RawGrid> splitSegments(const std::string& bytes, const std::string& name)
{
    using nanovdb::io::Codec;
    using nanovdb::io::Header;
    using nanovdb::io::MetaData;
    std::vector<RawGrid> grids;
    const uint64_t size = bytes.size();
    if (size == 0) throw IoError(fmt::format("{}: the file is empty", name));
    uint64_t at = 0;
    while (at < size) {
        if (size - at < sizeof(Header))
            damaged(name, fmt::format("{} bytes after the last grid, too few for a segment header", size - at));
        Header h;
        std::memcpy(&h, bytes.data() + at, sizeof h);
        if (h.magic != NANOVDB_MAGIC_NUMBER) {
            if (at == 0) throw IoError(fmt::format("{}: not a NanoVDB file (no NanoVDB magic number at its start)", name));
            damaged(name, fmt::format("no NanoVDB magic number at byte {}, where a segment should start", at));
        }
        if (h.version.getMajor() != NANOVDB_MAJOR_VERSION_NUMBER)
            throw IoError(fmt::format("{}: NanoVDB file format {} (version {}.{}.{}); svo reads format {}", name,
                                      h.version.getMajor(), h.version.getMajor(), h.version.getMinor(),
                                      h.version.getPatch(), NANOVDB_MAJOR_VERSION_NUMBER));
        if (h.gridCount == 0) damaged(name, fmt::format("the segment at byte {} holds no grids", at));
        if ((h.codec == Codec::ZIP || h.codec == Codec::BLOSC) && !codecBuiltIn(h.codec))
            throw IoError(fmt::format("{}: its grids are compressed with {}, which this svo is built without (it "
                                      "needs libblosc at build time); write the file uncompressed or with Zip",
                                      name, nanovdb::io::toStr(h.codec)));
        if (h.codec != Codec::NONE && h.codec != Codec::ZIP && h.codec != Codec::BLOSC)
            damaged(name, fmt::format("unknown compression codec {} at byte {}", uint16_t(h.codec), at + 14));
        at += sizeof(Header);
        const size_t first = grids.size();
        for (uint16_t i = 0; i < h.gridCount; ++i) {
            if (size - at < sizeof(MetaData))
                damaged(name, fmt::format("the file ends inside the record of grid {} (byte {})", grids.size() + 1, at));
            RawGrid g;
            std::memcpy(&g.meta, bytes.data() + at, sizeof(MetaData));
            at += sizeof(MetaData);
            const uint32_t nameSize = g.meta.nameSize;
            if (nameSize == 0 || nameSize > size - at)
                damaged(name, fmt::format("grid {}'s name of {} bytes does not fit in the file", grids.size() + 1,
                                          nameSize));
            const char* n = bytes.data() + at;
            if (n[nameSize - 1] != '\0' || std::memchr(n, '\0', nameSize) != n + nameSize - 1)
                damaged(name, fmt::format("grid {}'s name is not one string of {} bytes", grids.size() + 1, nameSize));
            g.metaName.assign(n, nameSize - 1);
            at += nameSize;
            g.codec = h.codec;
            g.version = h.version.id();
            grids.push_back(std::move(g));
        }
        for (size_t i = first; i < grids.size(); ++i) {
            RawGrid& g = grids[i];
            const std::string gn = fmt::format("grid '{}'", g.metaName);
            if (g.codec == Codec::NONE && g.meta.fileSize != g.meta.gridSize)
                damaged(name, fmt::format("{} is uncompressed but its size in the file ({}) is not its size ({})", gn,
                                          g.meta.fileSize, g.meta.gridSize));
            if (g.meta.fileSize > size - at)
                damaged(name, fmt::format("{} needs {} bytes, the file has {} left", gn, g.meta.fileSize, size - at));
            if (g.meta.gridSize < sizeof(nanovdb::GridData) + sizeof(nanovdb::TreeData<3>))
                damaged(name, fmt::format("{} is {} bytes, smaller than a grid's header", gn, g.meta.gridSize));
            // No codec packs better than about 1000:1 (zlib's limit): a larger claim is damage, not a grid.
            if (g.meta.gridSize / 1100 > g.meta.fileSize)
                damaged(name, fmt::format("{} claims {} bytes from {} compressed bytes", gn, g.meta.gridSize,
                                          g.meta.fileSize));
            g.buffer = nanovdb::HostBuffer::create(g.meta.gridSize);
            if (g.codec == Codec::NONE)
                std::memcpy(g.buffer.data(), bytes.data() + at, g.meta.gridSize);
            else
                decode(g.codec, bytes.data() + at, g.meta.fileSize, g.buffer, name, gn);
            at += g.meta.fileSize;
        }
    }
    return grids;
}

template <typename T> bool sameBytes(const T& a, const T& b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

/// Checks one grid's layout against its buffer (everything NanoVDB's
/// validator, checksum and converter dereference), then runs the validator.
template <typename BuildT>
const nanovdb::NanoGrid<BuildT>* checkGrid(RawGrid& raw, const std::string& name)
{
    using GridT = nanovdb::NanoGrid<BuildT>;
    using TreeT = typename GridT::TreeType;
    using RootT = typename TreeT::RootType;
    using UpperT = typename RootT::ChildNodeType;
    using LowerT = typename UpperT::ChildNodeType;
    using LeafT = typename LowerT::ChildNodeType;
    using TileT = typename RootT::DataType::Tile;
    static_assert(sizeof(GridT) == sizeof(nanovdb::GridData) && sizeof(TreeT) == sizeof(nanovdb::TreeData<3>));

    const std::string gn = fmt::format("grid '{}'", raw.metaName);
    const uint8_t* base = raw.buffer.data();
    const uint64_t size = raw.buffer.size();
    const auto* gd = reinterpret_cast<const nanovdb::GridData*>(base);
    if (gd->mMagic != NANOVDB_MAGIC_NUMBER) damaged(name, gn + " has no NanoVDB magic number");
    if (gd->mGridSize != size)
        damaged(name, fmt::format("{} says it is {} bytes, its record {}", gn, gd->mGridSize, size));
    if (gd->mGridType != raw.meta.gridType)
        damaged(name, fmt::format("{} is {}, its record says {}", gn, typeName(gd->mGridType),
                                  typeName(raw.meta.gridType)));

    const uint64_t treeOff = sizeof(GridT);
    const auto* td = reinterpret_cast<const nanovdb::TreeData<3>*>(base + treeOff);
    // The root right after the tree, its table inside the grid (NanoVDB's
    // checksum reads grid, tree and root as one run of bytes).
    if (td->mNodeOffset[3] != sizeof(TreeT)) damaged(name, gn + "'s root node is not where the tree says");
    const uint64_t rootOff = treeOff + sizeof(TreeT);
    const auto* rootData = reinterpret_cast<const typename RootT::DataType*>(base + rootOff);
    if (size - rootOff < sizeof(RootT) ||
        (size - rootOff - sizeof(RootT)) / sizeof(TileT) < uint64_t(rootData->mTableSize))
        damaged(name, gn + "'s root table runs past the end of the grid");

    // Node regions: level 0 leaves, 1 lower, 2 upper.
    const uint64_t nodeSize[3] = {sizeof(LeafT), sizeof(LowerT), sizeof(UpperT)};
    uint64_t start[3] = {0, 0, 0};
    std::vector<uint8_t> seen[3];
    for (int l = 0; l < 3; ++l) {
        const uint64_t count = td->mNodeCount[l];
        if (count == 0) continue;
        const uint64_t rel = td->mNodeOffset[l];
        if (rel > size - treeOff || (size - treeOff - rel) / nodeSize[l] < count || (treeOff + rel) % 32 != 0)
            damaged(name, fmt::format("{}'s {} nodes of level {} do not fit in the grid", gn, count, l));
        start[l] = treeOff + rel;
        seen[l].assign(count, 0);
    }
    // A child: inside its level's region, at a node boundary, reached once.
    auto child = [&](int l, uint64_t parentOff, int64_t rel) -> uint64_t {
        const uint64_t count = seen[l].size();
        const bool below = rel < 0 && uint64_t(-(rel + 1)) + 1 > parentOff;
        const uint64_t off = parentOff + uint64_t(rel);
        if (below || rel == 0 || count == 0 || off < start[l] || off - start[l] >= count * nodeSize[l] ||
            (off - start[l]) % nodeSize[l] != 0)
            damaged(name, fmt::format("{} has a child pointer of level {} outside its nodes", gn, l));
        const uint64_t i = (off - start[l]) / nodeSize[l];
        if (seen[l][i]) damaged(name, fmt::format("{} reaches one node of level {} twice", gn, l));
        seen[l][i] = 1;
        return off;
    };
    // An internal node's origin is its active box's corner (NanoVDB's
    // InternalNode::origin). A node with no active value has an empty box
    // (NanoVDB's own GridStats gives it one, as svo's layout does), so its
    // place is its parent's word; once the grid is validated, `unplaced`
    // get that place as their box's corner, for the converter, which reads
    // origin().
    std::vector<std::pair<uint64_t, nanovdb::Coord>> unplaced; // a node's byte offset, its place
    auto placedAt = [&](auto* node, uint64_t off, const nanovdb::Coord& at) {
        if (node->origin() == at) return;
        if (!node->data()->mBBox.empty()) damaged(name, gn + " has a node whose origin is not its place in its parent");
        unplaced.emplace_back(off, at);
    };
    for (uint32_t t = 0; t < rootData->mTableSize; ++t) {
        const TileT* tile = rootData->tile(t);
        if (!tile->isChild()) continue;
        const uint64_t uOff = child(2, rootOff, tile->child);
        const auto* upper = reinterpret_cast<const UpperT*>(base + uOff);
        const nanovdb::Coord upperAt = tile->origin();
        placedAt(upper, uOff, upperAt);
        for (auto it = upper->childMask().beginOn(); it; ++it) {
            const uint32_t n = *it;
            const uint64_t lOff = child(1, uOff, upper->data()->mTable[n].child);
            const auto* lower = reinterpret_cast<const LowerT*>(base + lOff);
            const nanovdb::Coord lowerAt = upperAt + (UpperT::OffsetToLocalCoord(n) << LowerT::TOTAL);
            placedAt(lower, lOff, lowerAt);
            for (auto jt = lower->childMask().beginOn(); jt; ++jt) {
                const uint32_t m = *jt;
                const uint64_t fOff = child(0, lOff, lower->data()->mTable[m].child);
                const auto* leaf = reinterpret_cast<const LeafT*>(base + fOff);
                if (leaf->origin() != lowerAt + (LowerT::OffsetToLocalCoord(m) << LeafT::TOTAL))
                    damaged(name, gn + " has a leaf whose origin is not its place in its parent");
            }
        }
    }
    for (int l = 0; l < 3; ++l)
        if (std::count(seen[l].begin(), seen[l].end(), uint8_t(1)) != std::ptrdiff_t(seen[l].size()))
            damaged(name, fmt::format("{} says it has {} nodes of level {}, its tree reaches fewer", gn,
                                      seen[l].size(), l));

    // The name: 256 bytes in the grid, or (a long name) the last blind data.
    std::string gridName;
    if (gd->mFlags & uint32_t(nanovdb::GridFlags::HasLongGridName)) {
        using BlindT = nanovdb::GridBlindMetaData;
        const uint64_t count = gd->mBlindMetadataCount;
        const int64_t off = gd->mBlindMetadataOffset;
        if (count == 0 || off < int64_t(sizeof(GridT)) || uint64_t(off) > size || uint64_t(off) % alignof(BlindT) != 0 ||
            (size - uint64_t(off)) / sizeof(BlindT) < count)
            damaged(name, gn + "'s long name is not inside the grid");
        const uint64_t lastOff = uint64_t(off) + (count - 1) * sizeof(BlindT);
        const auto* last = reinterpret_cast<const BlindT*>(base + lastOff);
        const int64_t rel = last->mByteOffset;
        const bool below = rel < 0 && uint64_t(-(rel + 1)) + 1 > lastOff;
        const uint64_t at = lastOff + uint64_t(rel);
        if (below || at >= size || !std::memchr(base + at, '\0', size - at))
            damaged(name, gn + "'s long name is not inside the grid");
        gridName = reinterpret_cast<const char*>(base + at);
    } else {
        const void* end = std::memchr(gd->mGridName, '\0', sizeof gd->mGridName);
        if (!end) damaged(name, gn + "'s name has no end");
        gridName = gd->mGridName;
    }

    const auto* grid = reinterpret_cast<const GridT*>(base);
    const std::string why = nanovdb::GridValidator<BuildT>::check(*grid, /*detailed*/ true);
    if (!why.empty()) damaged(name, fmt::format("{} fails NanoVDB's validation: {}", gn, why));
    static_assert(offsetof(typename UpperT::DataType, mBBox) == 0 && offsetof(typename LowerT::DataType, mBBox) == 0,
                  "an internal node begins with its box");
    for (const auto& [off, at] : unplaced) { // still empty, its corner the node's place (after the checksum)
        auto* box = reinterpret_cast<nanovdb::CoordBBox*>(raw.buffer.data() + off);
        *box = nanovdb::CoordBBox(at, at - nanovdb::Coord(1));
    }

    // The segment's record of the grid must say what the grid says.
    const nanovdb::io::MetaData& m = raw.meta;
    const char* field = nullptr;
    if (gridName != raw.metaName) field = "name";
    else if (m.nameKey != nanovdb::io::stringHash(gridName)) field = "name hash";
    else if (m.gridClass != grid->gridClass()) field = "class";
    else if (m.voxelCount != grid->activeVoxelCount()) field = "active voxel count";
    else if (!sameBytes(m.worldBBox, grid->worldBBox())) field = "world bounding box";
    else if (!sameBytes(m.indexBBox, grid->tree().bbox())) field = "index bounding box";
    else if (!sameBytes(m.voxelSize, grid->voxelSize())) field = "voxel size";
    else if (m.nodeCount[0] != td->mNodeCount[0] || m.nodeCount[1] != td->mNodeCount[1] ||
             m.nodeCount[2] != td->mNodeCount[2] || m.nodeCount[3] != 1)
        field = "node counts";
    else if (m.tileCount[0] != td->mTileCount[0] || m.tileCount[1] != td->mTileCount[1] ||
             m.tileCount[2] != td->mTileCount[2])
        field = "tile counts";
    else if (m.codec != raw.codec) field = "codec";
    else if (m.padding != 0) field = "padding";
    else if (m.version.id() != raw.version) field = "version";
    if (field) damaged(name, fmt::format("the file's record of {} does not match the grid: {}", gn, field));
    return grid;
}

template <typename BuildT> openvdb::GridBase::Ptr convert(RawGrid& raw, const std::string& name)
{
    const auto* grid = checkGrid<BuildT>(raw, name);
    try {
        return nanovdb::nanoToOpenVDB(*grid);
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: grid '{}' cannot become an OpenVDB grid: {}", name, raw.metaName, e.what()));
    }
}

openvdb::GridBase::Ptr toOpenVdb(RawGrid& raw, const std::string& name)
{
    using nanovdb::GridType;
    switch (raw.meta.gridType) {
    case GridType::Float: return convert<float>(raw, name);
    case GridType::Double: return convert<double>(raw, name);
    case GridType::Int32: return convert<int32_t>(raw, name);
    case GridType::Int64: return convert<int64_t>(raw, name);
    case GridType::Vec3f: return convert<nanovdb::Vec3f>(raw, name);
    case GridType::Vec3d: return convert<nanovdb::Vec3d>(raw, name);
    case GridType::Boolean: return convert<bool>(raw, name);
    case GridType::Mask: return convert<nanovdb::ValueMask>(raw, name);
    default: break;
    }
    if (uint32_t(raw.meta.gridType) >= uint32_t(GridType::End))
        damaged(name, fmt::format("grid '{}' has an unknown grid type {}", raw.metaName, uint32_t(raw.meta.gridType)));
    throw IoError(fmt::format("{}: grid '{}' is a NanoVDB {} grid; svo reads float, double, int32, int64, Vec3f, Vec3d, "
                              "bool and mask grids",
                              name, raw.metaName, typeName(raw.meta.gridType)));
}

std::string readWholeFile(const std::string& path)
{
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw IoError(fmt::format("{}: no such file", path));
    if (fs::is_directory(st)) throw IoError(fmt::format("{}: is a folder, not a .nvdb file", path));
    if (!fs::is_regular_file(st))
        throw IoError(fmt::format("{}: is not a regular file; svo reads .nvdb files that are regular files", path));
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open the file", path));
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) throw IoError(fmt::format("{}: cannot read the file", path));
    return bytes;
}

} // namespace

openvdb::GridPtrVec readNanoVdbGridsFromBytes(const std::string& bytes, const std::string& name,
                                              const std::string& gridName)
{
    openvdb::initialize();
    std::vector<RawGrid> raws = splitSegments(bytes, name);
    const RawGrid* named = nullptr;
    if (!gridName.empty()) {
        for (const auto& r : raws)
            if (!named && r.metaName == gridName) named = &r;
        if (!named) throw InvalidInput(fmt::format("{}: no grid named '{}'", name, gridName));
    }
    openvdb::GridPtrVec out;
    // Every grid is checked, also when one is asked for.
    for (auto& r : raws) {
        openvdb::GridBase::Ptr g = toOpenVdb(r, name);
        if (!named || named == &r) out.push_back(std::move(g));
    }
    return out;
}

openvdb::GridPtrVec readNanoVdbGrids(const std::string& path, const std::string& gridName)
{
    return readNanoVdbGridsFromBytes(readWholeFile(path), path, gridName);
}

VdbBricks readNanoVdbBricks(const std::string& path, const std::string& gridName)
{
    // Without a name, the file's main grid, as for a .vdb.
    return bricksOfGrid(*mainGrid(readNanoVdbGrids(path, gridName)), path);
}

} // namespace svo::vdb
