#include "svo/vdb_io/vdb_file.h"
#include "svo/vdb_io/reader_grids.h"

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <type_traits>
#include <sstream>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/vdb_io/grid_builder.h"
#include "parallel_buffers.h"

namespace svo::vdb {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

using openvdb::io::GridDescriptor;

/// Reads a whole .vdb from a stream and checks it, because OpenVDB's reader
/// checks almost nothing: it goes on reading past the end of a cut-short file
/// (the stream fails and values stay unset), ignores bytes after the last
/// grid, and takes the origin of a mask or bool leaf from the data section,
/// where damage moves the leaf away from where the tree holds it. OpenVDB
/// files carry no checksum, so this finds damage to the structure and to
/// what the writer recorded (positions, voxel count, bounding box, the two
/// copies of a mask or bool leaf's mask), not every changed bit.
///
/// Sizes that come from the file are checked against the bytes left (and,
/// for chunks of values, against what the masks call for) before OpenVDB
/// allocates or reads from them: strings, metadata, and, for the grid types
/// svo reads, the whole tree (walkTree). Grids of other types are read by
/// OpenVDB unwalked; whatever it throws becomes svo::Error.
class CheckedReader : public openvdb::io::Archive {
public:
    CheckedReader(std::istream& is, uint64_t size, const std::string& name) : is_(is), size_(size), name_(name) {}
    CheckedReader(const CheckedReader&) = delete;
    CheckedReader& operator=(const CheckedReader&) = delete;
    ~CheckedReader() override
    {
        // The stream holds the address of streamMeta_: leave it none.
        static openvdb::io::StreamMetadata::Ptr none;
        openvdb::io::setStreamMetadataPtr(is_, none, false);
    }

    /// A grid as read, with its descriptor.
    struct Read {
        GridDescriptor gd;
        openvdb::GridBase::Ptr grid;
    };

    /// Header, file metadata and grid descriptors, with the descriptors'
    /// positions checked against each other and the file size.
    void open()
    {
        readFileHeader();
        setUpStreamMetadata();
        openvdb::MetaMap fileMeta;
        readMeta(fileMeta, "the file metadata");
        const int32_t count = readGridCount();
        count_ = count;
        if (!inputHasGridOffsets()) return; // written as a stream: grids follow one another, read by readAll
        for (int32_t i = 0; i < count; ++i) descriptors_.push_back(readPlacedDescriptor(i));
        checkEnd();
    }

    bool sequential() const { return !inputHasGridOffsets(); }
    const std::vector<GridDescriptor>& descriptors() const { return descriptors_; }

    /// Reads one grid of a file with positions and checks it.
    openvdb::GridBase::Ptr read(const GridDescriptor& gd)
    {
        is_.seekg(gd.getGridPos());
        auto grid = readGrid(gd, gd.getBlockPos());
        if (tell() != gd.getEndPos())
            damaged(fmt::format("grid {} should end at byte {} but its data ends at byte {}", quoted(gd),
                                gd.getEndPos(), tell()));
        return grid;
    }

    /// Reads every grid of a file written as a stream (no positions).
    std::vector<Read> readAll()
    {
        std::vector<Read> out;
        for (int32_t i = 0; i < count_; ++i) {
            GridDescriptor gd = readDescriptor(i);
            auto grid = readGrid(gd, -1);
            out.push_back({gd, grid});
        }
        checkEnd();
        return out;
    }

private:
    [[noreturn]] void damaged(const std::string& what) const
    {
        throw IoError(fmt::format("{}: truncated or damaged: {}", name_, what));
    }
    static std::string quoted(const GridDescriptor& gd) { return "'" + gd.gridName() + "'"; }
    int64_t tell() const { return is_ ? int64_t(is_.tellg()) : -1; }
    uint64_t left() const
    {
        const int64_t at = tell();
        return at < 0 || uint64_t(at) > size_ ? 0 : size_ - uint64_t(at);
    }
    void checkEnd() const
    {
        const int64_t at = tell();
        if (at < 0) damaged("reading went past the end of the file");
        if (uint64_t(at) != size_)
            damaged(fmt::format("the last grid ends at byte {} but the file has {} bytes", at, size_));
    }
    // --- the file's header and its grid descriptors -------------------------

    /// The header, refused when cut short or older than svo reads.
    void readFileHeader()
    {
        try {
            readHeader(is_);
        } catch (const std::exception& e) {
            if (!is_) damaged("the header is cut short");
            throw IoError(fmt::format("{}: not a readable VDB file: {}", name_, e.what()));
        }
        if (!is_) damaged("the header is cut short");
        // Older formats store the root as a table whose size comes from the
        // file (up to 2^32 entries); OpenVDB 2 (2013) already wrote 222.
        if (fileVersion() < openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)
            throw IoError(fmt::format("{}: VDB file format {} is older than {}, the oldest svo reads", name_,
                                      fileVersion(), int(openvdb::OPENVDB_FILE_VERSION_NODE_MASK_COMPRESSION)));
    }

    /// The stream state OpenVDB's readers look up, as Archive sets it up.
    void setUpStreamMetadata()
    {
        streamMeta_ = std::make_shared<openvdb::io::StreamMetadata>();
        streamMeta_->setSeekable(true);
        openvdb::io::setStreamMetadataPtr(is_, streamMeta_, /*transfer=*/false);
        setFormatVersion(is_);
        setLibraryVersion(is_);
        setDataCompression(is_);
    }

    /// The grid count, checked against the bytes left.
    int32_t readGridCount()
    {
        int32_t count = 0;
        is_.read(reinterpret_cast<char*>(&count), sizeof count);
        if (!is_) damaged("the file ends before the grid count");
        // A grid takes at least its descriptor: three strings and three positions.
        if (count < 0 || uint64_t(count) > left() / 36)
            damaged(fmt::format("the file declares {} grids in its last {} bytes", count, left()));
        return count;
    }

    /// Grid i's descriptor in a file with positions, the positions checked
    /// against where it sits and the file size; leaves the stream at the grid's end.
    GridDescriptor readPlacedDescriptor(int32_t i)
    {
        GridDescriptor gd = readDescriptor(i);
        const int64_t at = tell();
        const std::string g = quoted(gd);
        if (gd.getGridPos() != at)
            damaged(fmt::format("grid {} should start at byte {}, after its descriptor, but the descriptor says {}",
                                g, at, gd.getGridPos()));
        if (gd.getBlockPos() < gd.getGridPos() || gd.getEndPos() < gd.getBlockPos())
            damaged(fmt::format("grid {} has its positions out of order (start {}, data {}, end {})", g,
                                gd.getGridPos(), gd.getBlockPos(), gd.getEndPos()));
        if (uint64_t(gd.getEndPos()) > size_)
            damaged(fmt::format("grid {} ends at byte {} but the file has {} bytes", g, gd.getEndPos(), size_));
        is_.seekg(gd.getEndPos());
        return gd;
    }

    // --- sizes, strings and metadata, checked against the bytes left --------

    uint32_t readU32(const std::string& what)
    {
        uint32_t v = 0;
        is_.read(reinterpret_cast<char*>(&v), sizeof v);
        if (!is_) damaged(what + " is cut short");
        return v;
    }
    /// A length-prefixed string, its length checked against the bytes left.
    std::string readString(const std::string& what)
    {
        const uint32_t n = readU32(what);
        if (n > left()) damaged(fmt::format("{} declares a string of {} bytes, {} bytes before the end", what, n, left()));
        std::string s(n, '\0');
        if (n) is_.read(s.data(), n);
        if (!is_) damaged(what + " is cut short");
        return s;
    }

    /// Metadata entries, each value parsed from its own bytes so that a size
    /// that does not match its type stops here (OpenVDB's fixed-size types
    /// ignore the stored size and would go on out of step).
    void readMeta(openvdb::MetaMap& out, const std::string& what)
    {
        const uint32_t count = readU32(what);
        if (count > left() / 12) // name, type and size take 12 bytes at least
            damaged(fmt::format("{} declares {} entries in its last {} bytes", what, count, left()));
        for (uint32_t i = 0; i < count; ++i) readMetaEntry(out, what);
    }

    /// One metadata entry: name, type, size and value, into `out` unless its
    /// type only serves reading.
    void readMetaEntry(openvdb::MetaMap& out, const std::string& what)
    {
        const std::string key = readString(what);
        const std::string type = readString(what);
        const uint32_t n = readU32(what);
        if (n > left()) damaged(fmt::format("{}: '{}' declares {} bytes, {} bytes before the end", what, key, n, left()));
        std::string bytes(sizeof n + n, '\0');
        std::memcpy(bytes.data(), &n, sizeof n);
        if (n) is_.read(bytes.data() + sizeof n, n);
        if (!is_) damaged(what + " is cut short");
        // "__" types only serve reading (delayed loading, which svo never
        // does); OpenVDB drops them from the grid too.
        if (type.compare(0, 2, "__") == 0) return;
        const openvdb::Metadata::Ptr m = parseMetaValue(what, key, type, bytes);
        if (key.empty()) damaged(what + " has an entry without a name"); // OpenVDB's insertMeta throws
        out.insertMeta(key, *m);
    }

    /// An entry's value parsed from `bytes` (its size, then the value), which
    /// it must fill exactly.
    openvdb::Metadata::Ptr parseMetaValue(const std::string& what, const std::string& key, const std::string& type,
                                          const std::string& bytes) const
    {
        const uint64_t n = bytes.size() - sizeof(uint32_t);
        openvdb::Metadata::Ptr m;
        if (openvdb::Metadata::isRegisteredType(type)) m = openvdb::Metadata::createMetadata(type);
        else m = std::make_shared<openvdb::UnknownMetadata>(type);
        std::istringstream value(bytes);
        try {
            m->read(value);
        } catch (const std::exception& e) {
            damaged(fmt::format("{}: '{}' of type {}: {}", what, key, type, e.what()));
        }
        if (!value || value.tellg() != std::streamoff(bytes.size()))
            damaged(fmt::format("{}: '{}' has {} bytes, not what type {} holds", what, key, n, type));
        return m;
    }

    GridDescriptor readDescriptor(int32_t i)
    {
        const std::string what = fmt::format("the descriptor of grid {}", i + 1);
        // GridDescriptor::read allocates its strings from the lengths it reads:
        // check them first, then let it read.
        const int64_t at = tell();
        const std::string name = readString(what);
        const std::string type = readString(what);
        if (fileVersion() >= openvdb::OPENVDB_FILE_VERSION_GRID_INSTANCING) readString(what);
        if (left() < 24) damaged(what + " is cut short");
        is_.seekg(at);
        GridDescriptor gd;
        try {
            gd.read(is_);
        } catch (const std::exception& e) {
            // A type this OpenVDB does not register: maybe damage, maybe a newer writer.
            throw IoError(fmt::format("{}: grid '{}' has type '{}', which this OpenVDB cannot read ({})", name_, name,
                                      type, e.what()));
        }
        if (!is_) damaged(what + " is cut short");
        return gd;
    }

    /// Reads the grid at the stream's position as Archive::readGrid does, with
    /// the checks. blockPos: where its topology must end (-1: unknown).
    openvdb::GridBase::Ptr readGrid(const GridDescriptor& gd, int64_t blockPos)
    {
        const std::string g = quoted(gd);
        openvdb::GridBase::Ptr grid;
        try {
            grid = newGrid(gd, g);
            openvdb::io::StreamMetadata::Ptr gridMeta;
            setGridStream(*grid, gridMeta);
            const RestoreStream restore{is_, streamMeta_};
            readTransform(*grid, g);
            if (!gd.isInstance()) readTree(*grid, blockPos, g);
        } catch (const Error&) {
            throw;
        } catch (const std::bad_alloc&) {
            damaged(fmt::format("grid {} declares a size beyond memory", g));
        } catch (const std::exception& e) {
            if (!is_) damaged(fmt::format("grid {} is cut short ({})", g, e.what()));
            damaged(fmt::format("grid {}: {}", g, e.what()));
        }
        return grid;
    }

    /// An empty grid of the descriptor's type with the grid's metadata, read as
    /// Archive::readGrid reads it.
    openvdb::GridBase::Ptr newGrid(const GridDescriptor& gd, const std::string& g)
    {
        openvdb::GridBase::Ptr grid = openvdb::GridBase::createGrid(gd.gridType());
        grid->setSaveFloatAsHalf(gd.saveFloatAsHalf());
        readGridCompression(is_);
        openvdb::MetaMap meta;
        readMeta(meta, "the metadata of grid " + g);
        for (auto it = meta.beginMeta(); it != meta.endMeta(); ++it) grid->insertMeta(it->first, *it->second);
        // As OpenVDB's reader: the descriptor says it; the writer adds it again.
        grid->removeMeta(openvdb::GridBase::META_SAVE_HALF_FLOAT);
        return grid;
    }

    /// Per-grid stream state, as Archive::readGrid sets it up, in `gridMeta`,
    /// which must outlive the grid's reading: the stream keeps its address.
    void setGridStream(const openvdb::GridBase& grid, openvdb::io::StreamMetadata::Ptr& gridMeta)
    {
        gridMeta = std::make_shared<openvdb::io::StreamMetadata>(*streamMeta_);
        gridMeta->setHalfFloat(grid.saveFloatAsHalf());
        gridMeta->gridMetadata() = static_cast<const openvdb::MetaMap&>(grid);
        gridMeta->setLeaf(0);
        openvdb::io::setStreamMetadataPtr(is_, gridMeta, /*transfer=*/false);
        openvdb::io::setGridClass(is_, grid.getGridClass());
        openvdb::io::setGridBackgroundValuePtr(is_, nullptr);
    }

    /// Puts the file's stream state back after a grid's (setGridStream).
    struct RestoreStream { // the stream keeps the address of the pointer
        std::istream& is;
        openvdb::io::StreamMetadata::Ptr& meta;
        ~RestoreStream() { openvdb::io::setStreamMetadataPtr(is, meta, false); }
    };

    void readTransform(openvdb::GridBase& grid, const std::string& g)
    {
        {
            // The transform starts with its map's type name.
            const int64_t at = tell();
            readString("the transform of grid " + g);
            is_.seekg(at);
        }
        grid.readTransform(is_);
        if (!is_) damaged(fmt::format("grid {} is cut short in its transform", g));
    }

    /// The tree: walked first, then its topology (ending at blockPos when
    /// known) and its voxel data, each checked.
    void readTree(openvdb::GridBase& grid, int64_t blockPos, const std::string& g)
    {
        checkTree(grid, g);
        grid.readTopology(is_);
        if (!is_) damaged(fmt::format("grid {} is cut short in its tree", g));
        if (blockPos >= 0 && tell() != blockPos)
            damaged(fmt::format("the tree of grid {} should end at byte {} but ends at byte {}", g, blockPos, tell()));
        const TopologyMasks masks = topologyMasks(grid);
        grid.readBuffers(is_);
        if (!is_) damaged(fmt::format("grid {} is cut short in its voxel data", g));
        checkLeaves(grid, masks, g);
        checkStats(grid, g);
    }

    /// Walks the tree of a grid of a type svo reads (others are left to
    /// OpenVDB unchecked) before OpenVDB reads it.
    void checkTree(const openvdb::GridBase& grid, const std::string& g)
    {
        const uint32_t compression = openvdb::io::getDataCompression(is_);
        grid.apply<GridTypes>([&](const auto& typed) { walkTree(typed, compression, g); });
    }

    // --- a walk over a tree's bytes before OpenVDB reads them ---------------
    // OpenVDB 10 reads a chunk stored uncompressed into a buffer sized from
    // the masks before comparing the sizes (fixed in OpenVDB 12), and hands
    // Blosc chunks to Blosc, which trusts their headers: a damaged size there
    // writes or reads past a buffer. The walk follows the layout OpenVDB
    // reads (Tree4<T, 5, 4, 3>: root, two levels of internal nodes, leaves;
    // then the leaves' data) and checks every such size first.

    void skip(uint64_t n, const std::string& g)
    {
        if (n > left()) damaged(fmt::format("grid {} declares {} bytes, more than the {} left in the file", g, n, left()));
        is_.seekg(std::streamoff(n), std::ios_base::cur);
    }
    template <typename T> T get(const std::string& g)
    {
        T v{};
        is_.read(reinterpret_cast<char*>(&v), sizeof v);
        if (!is_) damaged(fmt::format("grid {} is cut short", g));
        return v;
    }
    template <typename MaskT> MaskT getMask(const std::string& g)
    {
        MaskT m;
        m.load(is_);
        if (!is_) damaged(fmt::format("grid {} is cut short", g));
        return m;
    }

    /// One chunk of values as readData reads it: `bytes` is what the reader expects.
    void walkChunk(uint64_t bytes, uint32_t compression, const std::string& g)
    {
        if (!(compression & (openvdb::io::COMPRESS_BLOSC | openvdb::io::COMPRESS_ZIP))) return skip(bytes, g);
        const int64_t n = get<int64_t>(g);
        if (n <= 0) { // stored as is, its size negated
            const uint64_t stored = uint64_t(0) - uint64_t(n); // INT64_MIN has no int64 negation
            if (stored != bytes)
                damaged(fmt::format("grid {} stores a chunk of {} bytes where its masks call for {}", g, stored, bytes));
            return skip(bytes, g);
        }
        if (compression & openvdb::io::COMPRESS_BLOSC) {
            // Blosc's header: uncompressed size at byte 4, compressed size at byte 12.
            uint32_t head[4] = {0, 0, 0, 0};
            if (n < 16) damaged(fmt::format("grid {} has a compressed chunk of {} bytes, too short", g, n));
            is_.read(reinterpret_cast<char*>(head), sizeof head);
            if (!is_) damaged(fmt::format("grid {} is cut short", g));
            is_.seekg(-std::streamoff(sizeof head), std::ios_base::cur);
            if (head[1] != bytes || head[3] != uint64_t(n))
                damaged(fmt::format("grid {} has a compressed chunk whose header does not match its size", g));
        }
        skip(uint64_t(n), g);
    }

    /// readCompressedValues: a flag, inactive values, a selection mask, the values.
    template <typename ValueT, typename MaskT>
    void walkValues(const MaskT& valueMask, uint32_t compression, bool half, const std::string& g)
    {
        using openvdb::io::RealToHalf;
        const int8_t flag = get<int8_t>(g);
        if (flag < 0 || flag > 6) damaged(fmt::format("grid {} has an unknown value layout {}", g, int(flag)));
        if (flag == 2 || flag == 4 || flag == 5) skip(sizeof(ValueT), g); // one inactive value
        if (flag == 5) skip(sizeof(ValueT), g);                           // a second one
        if (flag == 3 || flag == 4 || flag == 5) skip(MaskT::memUsage(), g);
        const bool maskCompressed = compression & openvdb::io::COMPRESS_ACTIVE_MASK;
        const uint64_t count = maskCompressed && flag != 6 ? valueMask.countOn() : MaskT::SIZE;
        const uint64_t size = half && RealToHalf<ValueT>::isReal ? sizeof(typename RealToHalf<ValueT>::HalfT)
                                                                 : sizeof(ValueT);
        walkChunk(count * size, compression, g);
    }

    template <typename NodeT>
    void walkInternal(uint32_t compression, bool half, std::vector<openvdb::util::NodeMask<3>>& leaves,
                      const std::string& g)
    {
        using ChildT = typename NodeT::ChildNodeType;
        using MaskT = typename NodeT::NodeMaskType;
        const MaskT children = getMask<MaskT>(g);
        const MaskT values = getMask<MaskT>(g);
        walkValues<typename NodeT::ValueType>(values, compression, half, g);
        for (auto it = children.beginOn(); it; ++it) {
            if constexpr (ChildT::LEVEL == 0) leaves.push_back(getMask<openvdb::util::NodeMask<3>>(g));
            else walkInternal<ChildT>(compression, half, leaves, g);
        }
    }

    template <typename GridT> void walkTree(const GridT& grid, uint32_t compression, const std::string& g)
    {
        using TreeT = typename GridT::TreeType;
        using RootT = typename TreeT::RootNodeType;
        using ValueT = typename GridT::ValueType;
        using LeafT = typename TreeT::LeafNodeType;
        const bool half = grid.saveFloatAsHalf();
        const int64_t start = tell();
        if (get<int32_t>(g) != 1) damaged(fmt::format("grid {} has a buffer count other than 1", g)); // OpenVDB warns only
        skip(sizeof(ValueT), g); // background
        const std::vector<openvdb::util::NodeMask<3>> leaves = walkRoot<RootT, ValueT>(compression, half, g);
        walkLeafData<ValueT, LeafT>(leaves, compression, half, g);
        is_.clear();
        is_.seekg(start);
    }

    /// The root's tiles and children, each child's subtree walked; returns
    /// the leaves' masks in the order of their data.
    template <typename RootT, typename ValueT>
    std::vector<openvdb::util::NodeMask<3>> walkRoot(uint32_t compression, bool half, const std::string& g)
    {
        const uint32_t tiles = get<uint32_t>(g), children = get<uint32_t>(g);
        const int32_t dim = RootT::ChildNodeType::DIM;
        for (uint32_t t = 0; t < tiles; ++t) {
            rootOrigin(dim, "tile", g);
            skip(sizeof(ValueT) + 1, g); // value, active
        }
        std::vector<openvdb::util::NodeMask<3>> leaves;
        openvdb::Coord last;
        for (uint32_t c = 0; c < children; ++c) {
            const openvdb::Coord o = rootOrigin(dim, "child", g);
            // The root keeps its children sorted; the data section follows that order.
            if (c && !(last < o))
                damaged(fmt::format("grid {} has a root child at ({}, {}, {}) out of order", g, o[0], o[1], o[2]));
            last = o;
            walkInternal<typename RootT::ChildNodeType>(compression, half, leaves, g);
        }
        return leaves;
    }

    /// A root tile's or child's origin. They sit on the lattice of the root's
    /// child size (`dim`), so origin + DIM - 1 (their last voxel, which
    /// OpenVDB computes when it takes a bounding box) cannot overflow int32.
    openvdb::Coord rootOrigin(int32_t dim, const char* what, const std::string& g)
    {
        int32_t o[3];
        is_.read(reinterpret_cast<char*>(o), sizeof o);
        if (!is_) damaged(fmt::format("grid {} is cut short in its tree", g));
        if ((o[0] & (dim - 1)) || (o[1] & (dim - 1)) || (o[2] & (dim - 1)))
            damaged(fmt::format("grid {} has a root {} at ({}, {}, {}), off the lattice", g, what, o[0], o[1], o[2]));
        return openvdb::Coord(o[0], o[1], o[2]);
    }

    /// The leaves' data section, in the order of `leaves`.
    template <typename ValueT, typename LeafT>
    void walkLeafData(const std::vector<openvdb::util::NodeMask<3>>& leaves, uint32_t compression, bool half,
                      const std::string& g)
    {
        for (const auto& mask : leaves) {
            if constexpr (std::is_same_v<ValueT, bool>) {
                // Mask leaves: mask, origin; bool leaves: mask, origin, values.
                skip(64 + 12 + (std::is_same_v<typename LeafT::BuildType, bool> ? 64 : 0), g);
            } else {
                skip(64, g); // the mask again, which OpenVDB skips
                walkValues<ValueT>(mask, compression, half, g);
            }
        }
    }

    /// Mask and bool leaves store their mask twice, in the tree and in the
    /// voxel data (with the leaf's origin); the second read wins. Kept from
    /// the first read to compare.
    struct TopologyMasks {
        std::vector<const void*> leaves;
        std::vector<openvdb::Coord> origins;
        std::vector<std::array<uint64_t, 8>> words;
    };
    template <typename GridT> static void collect(const openvdb::GridBase& grid, TopologyMasks& out)
    {
        const auto* typed = dynamic_cast<const GridT*>(&grid);
        if (!typed) return;
        for (auto leaf = typed->tree().cbeginLeaf(); leaf; ++leaf) {
            out.leaves.push_back(&*leaf);
            out.origins.push_back(leaf->origin());
            std::array<uint64_t, 8> w;
            for (openvdb::Index i = 0; i < 8; ++i) w[i] = leaf->getValueMask().template getWord<uint64_t>(i);
            out.words.push_back(w);
        }
    }
    static TopologyMasks topologyMasks(const openvdb::GridBase& grid)
    {
        TopologyMasks m;
        collect<openvdb::MaskGrid>(grid, m);
        collect<openvdb::BoolGrid>(grid, m);
        return m;
    }
    template <typename GridT> void compare(const openvdb::GridBase& grid, const TopologyMasks& m, const std::string& g) const
    {
        const auto* typed = dynamic_cast<const GridT*>(&grid);
        if (!typed) return;
        size_t i = 0;
        for (auto leaf = typed->tree().cbeginLeaf(); leaf; ++leaf, ++i) {
            if (i >= m.leaves.size() || &*leaf != m.leaves[i]) damaged(fmt::format("grid {} changed its leaves", g));
            const openvdb::Coord o = m.origins[i];
            if (leaf->origin() != o)
                damaged(fmt::format("a leaf of grid {} says it is at ({}, {}, {}) but the tree holds it at ({}, {}, {})",
                                    g, leaf->origin().x(), leaf->origin().y(), leaf->origin().z(), o.x(), o.y(), o.z()));
            for (openvdb::Index w = 0; w < 8; ++w)
                if (leaf->getValueMask().template getWord<uint64_t>(w) != m.words[i][w])
                    damaged(fmt::format("grid {} stores two different masks for its leaf at ({}, {}, {})", g,
                                        o.x(), o.y(), o.z()));
        }
    }
    void checkLeaves(const openvdb::GridBase& grid, const TopologyMasks& m, const std::string& g) const
    {
        compare<openvdb::MaskGrid>(grid, m, g);
        compare<openvdb::BoolGrid>(grid, m, g);
    }

    /// The active voxel count and bounding box OpenVDB's writer records
    /// (file_voxel_count, file_bbox_min/max), when the file has them.
    void checkStats(const openvdb::GridBase& grid, const std::string& g) const
    {
        if (auto count = grid.getMetadata<openvdb::Int64Metadata>(openvdb::GridBase::META_FILE_VOXEL_COUNT)) {
            const openvdb::Index64 actual = grid.activeVoxelCount();
            if (openvdb::Index64(count->value()) != actual)
                damaged(fmt::format("grid {} has {} active voxels but the file recorded {}", g, actual, count->value()));
        }
        const auto lo = grid.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MIN);
        const auto hi = grid.getMetadata<openvdb::Vec3IMetadata>(openvdb::GridBase::META_FILE_BBOX_MAX);
        if (lo && hi) {
            const openvdb::CoordBBox b = grid.evalActiveVoxelBoundingBox();
            if (b.min().asVec3i() != lo->value() || b.max().asVec3i() != hi->value())
                damaged(fmt::format("grid {} has active voxels in ({}, {}, {}) .. ({}, {}, {}) but the file recorded "
                                    "({}, {}, {}) .. ({}, {}, {})",
                                    g, b.min().x(), b.min().y(), b.min().z(), b.max().x(), b.max().y(), b.max().z(),
                                    lo->value()[0], lo->value()[1], lo->value()[2], hi->value()[0], hi->value()[1],
                                    hi->value()[2]));
        }
    }

    std::istream& is_;
    uint64_t size_;
    std::string name_;
    openvdb::io::StreamMetadata::Ptr streamMeta_;
    int32_t count_ = 0;
    std::vector<GridDescriptor> descriptors_;
};

/// OpenVDB's writer as io::File::write runs it, on a stream svo opens and
/// checks: File::write never looks at its stream, so a full disk or a file
/// size limit left a cut-short file behind an exit status of 0.
class CheckedWriter : public openvdb::io::Archive {
public:
    void writeFile(const std::string& tmp, const std::string& path, const openvdb::GridPtrVec& grids) const
    {
        std::ofstream os;
        os.open(tmp, std::ios_base::out | std::ios_base::binary);
        if (!os) throw IoError(fmt::format("{}: cannot create the file: {}", path, std::strerror(errno)));
        errno = 0;
        Archive::write(os, grids, /*seekable=*/true);
        int err = errno;
        if (os) {
            os.flush();
            err = errno;
        }
        if (os) {
            os.close(); // the last bytes reach the file here
            err = errno;
        }
        if (!os) throw IoError(fmt::format("{}: {}", path, err ? std::strerror(err) : "the write failed"));
    }
};

void writeGrids(const std::string& path, const openvdb::GridPtrVec& grids)
{
    writeAtomically(path, [&](const std::string& tmp) {
        try {
            openvdb::GridPtrVec parallel;
            for (const auto& g : grids) parallel.push_back(withParallelBuffers(g));
            CheckedWriter().writeFile(tmp, path, parallel);
        } catch (const Error&) {
            throw;
        } catch (const std::exception& e) {
            throw IoError(fmt::format("{}: cannot write the VDB file: {}", path, e.what()));
        }
    });
}

} // namespace

std::string validUtf8(const std::string& text)
{
    std::string out;
    out.reserve(text.size());
    const auto* p = reinterpret_cast<const unsigned char*>(text.data());
    const size_t n = text.size();
    for (size_t i = 0; i < n;) {
        const unsigned char c = p[i];
        // The length of a well-formed sequence starting here (RFC 3629: no
        // overlong forms, no surrogates, nothing above U+10FFFF), 0 if none.
        size_t len = 0;
        auto cont = [&](size_t k, unsigned char lo = 0x80, unsigned char hi = 0xBF) {
            return i + k < n && p[i + k] >= lo && p[i + k] <= hi;
        };
        if (c < 0x80) len = 1;
        else if (c >= 0xC2 && c <= 0xDF) len = cont(1) ? 2 : 0;
        else if (c == 0xE0) len = cont(1, 0xA0) && cont(2) ? 3 : 0;
        else if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) len = cont(1) && cont(2) ? 3 : 0;
        else if (c == 0xED) len = cont(1, 0x80, 0x9F) && cont(2) ? 3 : 0;
        else if (c == 0xF0) len = cont(1, 0x90) && cont(2) && cont(3) ? 4 : 0;
        else if (c >= 0xF1 && c <= 0xF3) len = cont(1) && cont(2) && cont(3) ? 4 : 0;
        else if (c == 0xF4) len = cont(1, 0x80, 0x8F) && cont(2) && cont(3) ? 4 : 0;
        if (len) {
            out.append(text, i, len);
            i += len;
        } else {
            out += fmt::format("\\x{:02X}", c);
            ++i;
        }
    }
    return out;
}

WriteStats writeVdb(const std::string& path, const Octree& octree, const WriteOptions& options)
{
    checkWritable(path);
    openvdb::initialize();
    WriteStats stats;
    auto t0 = Clock::now();
    openvdb::GridPtrVec grids = octreeToGrids(octree, options);
    stats.leaves = octree.bricks.size(); // one leaf per occupied brick
    for (auto& g : grids)
        for (const auto& [k, v] : options.metadata) g->insertMeta(validUtf8(k), openvdb::StringMetadata(validUtf8(v)));
    stats.buildMs = msSince(t0);

    t0 = Clock::now();
    if (!options.triangleSidecar.empty()) {
        auto [kept, triangles] = splitTriangleGrids(grids);
        if (!triangles.empty()) {
            markTriangleSidecar(triangles, path);
            writeGrids(options.triangleSidecar, triangles);
            stats.sidecarBytes = outputBytes(options.triangleSidecar);
        }
        grids = std::move(kept);
    }
    writeGrids(path, grids);
    stats.bytes = outputBytes(path); // the staged temporary while an OutputBatch holds it
    stats.writeMs = msSince(t0);
    return stats;
}

WriteStats writeVdbGrids(const std::string& path, const openvdb::GridPtrVec& grids,
                         const std::map<std::string, std::string>& metadata)
{
    checkWritable(path);
    openvdb::initialize();
    for (auto& g : grids)
        for (const auto& [k, v] : metadata) g->insertMeta(validUtf8(k), openvdb::StringMetadata(validUtf8(v)));
    WriteStats stats;
    const auto t0 = Clock::now();
    writeGrids(path, grids);
    stats.bytes = outputBytes(path); // the staged temporary while an OutputBatch holds it
    stats.writeMs = msSince(t0);
    for (const auto& g : grids) stats.leaves += g->baseTree().leafCount();
    return stats;
}

namespace {
VdbBricks readChecked(std::istream& in, uint64_t size, const std::string& name, const std::string& gridName,
                      uint64_t maxTileBricks);
openvdb::GridPtrVec readGridsChecked(std::istream& in, uint64_t size, const std::string& name,
                                     const std::string& gridName);

/// A .vdb path that can be read: it exists and is a regular file (a device
/// such as /dev/zero reads as endless or empty bytes, a FIFO cannot seek).
void checkReadable(const std::string& path)
{
    std::error_code ec;
    const fs::file_status st = fs::status(path, ec);
    if (!fs::exists(st)) throw IoError(fmt::format("{}: no such file", path));
    if (fs::is_directory(st)) throw IoError(fmt::format("{}: is a folder, not a .vdb file", path));
    if (!fs::is_regular_file(st)) {
        const char* kind = fs::is_character_file(st) ? "a character device"
                           : fs::is_block_file(st)   ? "a block device"
                           : fs::is_fifo(st)         ? "a FIFO"
                           : fs::is_socket(st)       ? "a socket"
                                                     : "not a regular file";
        throw IoError(fmt::format("{}: is {}, not a .vdb file; svo reads .vdb files that are regular files", path, kind));
    }
}

/// The size of a whole .vdb stream, rewound; refuses an empty one.
uint64_t streamSize(std::istream& in, const std::string& name)
{
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0);
    if (!in || size < 0) throw IoError(fmt::format("{}: cannot read the file", name));
    if (size == 0) throw IoError(fmt::format("{}: the file is empty", name));
    return uint64_t(size);
}
} // namespace

VdbBricks readVdbBricks(const std::string& path, const std::string& gridName)
{
    checkReadable(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open the file", path));
    return readVdbBricks(in, path, gridName);
}

openvdb::GridPtrVec readVdbGrids(const std::string& path, const std::string& gridName)
{
    checkReadable(path);
    std::ifstream in(path, std::ios::binary);
    if (!in) throw IoError(fmt::format("{}: cannot open the file", path));
    openvdb::initialize();
    const uint64_t size = streamSize(in, path);
    try {
        return readGridsChecked(in, size, path, gridName);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw IoError(fmt::format("{}: truncated or damaged: {}", path, e.what()));
    }
}

openvdb::GridBase::Ptr mainGrid(const openvdb::GridPtrVec& grids)
{
    // Level sets first, then grids of voxels, then per-voxel channels; in
    // name order within each. Metadata and types only: no value is read.
    auto rank = [](const openvdb::GridBase& g) {
        if (g.getGridClass() == openvdb::GRID_LEVEL_SET) return 0;
        const bool voxels = g.isType<openvdb::BoolGrid>() || g.isType<openvdb::MaskGrid>() ||
                            g.isType<openvdb::FloatGrid>() || g.isType<openvdb::DoubleGrid>();
        return voxels ? 1 : 2;
    };
    openvdb::GridBase::Ptr best = grids.front();
    for (const auto& g : grids)
        if (std::make_pair(rank(*g), g->getName()) < std::make_pair(rank(*best), best->getName())) best = g;
    return best;
}

namespace {
template <typename T> bool isOne(const T& v)
{
    if constexpr (std::is_same_v<T, bool>) return v;
    else if constexpr (std::is_arithmetic_v<T>) return v == T(1);
    else return false; // vectors: directions or colours, never a voxel set
}
} // namespace

VdbBricks bricksOfGrid(const openvdb::GridBase& grid, const std::string& name, uint64_t maxTileBricks)
{
    GridBricks gb = gridToBricks(grid, name, maxTileBricks);
    VdbBricks out;
    out.gridName = grid.getName();
    out.gridType = grid.type();
    out.grid = gb.grid;
    out.bricks = std::move(gb.bricks);
    out.tilesExpanded = gb.tilesExpanded;
    out.valuesDropped = valuesBeyondTopology(grid);
    return out;
}

std::string valuesBeyondTopology(const openvdb::GridBase& grid)
{
    const std::string g = fmt::format("grid '{}' ({})", grid.getName(), grid.valueType());
    if (grid.getGridClass() == openvdb::GRID_LEVEL_SET) return fmt::format("the distances of the level set {}", g);
    std::string out;
    const bool known = grid.apply<GridTypes>([&](const auto& typed) {
        using GridT = std::decay_t<decltype(typed)>;
        if constexpr (!std::is_same_v<GridT, openvdb::MaskGrid>) {
            for (auto it = typed.cbeginValueOn(); it; ++it)
                if (!isOne(*it)) {
                    out = fmt::format("the values of {}", g);
                    return;
                }
        }
    });
    if (!known) out = fmt::format("the values of {}", g);
    return out;
}

VdbBricks readVdbBricks(std::istream& in, const std::string& name, const std::string& gridName,
                        uint64_t maxTileBricks)
{
    openvdb::initialize();
    const uint64_t size = streamSize(in, name);
    try {
        return readChecked(in, size, name, gridName, maxTileBricks);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        // Whatever OpenVDB throws where the reader did not expect it.
        throw IoError(fmt::format("{}: truncated or damaged: {}", name, e.what()));
    }
}

namespace {

/// Every grid of the file read and checked; the ones asked for (all when
/// `all`, else the one named, or the mainGrid()) returned, an instance with
/// its parent's tree.
openvdb::GridPtrVec readSelected(std::istream& in, uint64_t size, const std::string& name, const std::string& gridName,
                                 bool all)
{
    CheckedReader reader(in, size, name);
    reader.open();

    std::vector<CheckedReader::Read> grids;
    if (reader.sequential()) grids = reader.readAll();
    else
        for (const auto& gd : reader.descriptors()) grids.push_back({gd, nullptr});
    if (grids.empty()) throw IoError(fmt::format("{}: the file holds no grids", name));
    const CheckedReader::Read* named = nullptr;
    if (!gridName.empty() && !all) {
        for (const auto& r : grids)
            if (!named && r.gd.gridName() == gridName) named = &r;
        const std::string unique = GridDescriptor::stringAsUniqueName(gridName);
        for (const auto& r : grids)
            if (!named && r.gd.uniqueName() == unique) named = &r; // "name[1]": the second grid of that name
        if (!named) throw InvalidInput(fmt::format("{}: no grid named '{}'", name, gridName));
    }
    std::map<std::string, openvdb::GridBase::Ptr> byUniqueName;
    openvdb::GridPtrVec read(grids.size());
    for (size_t i = 0; i < grids.size(); ++i) {
        read[i] = reader.sequential() ? grids[i].grid : reader.read(grids[i].gd);
        byUniqueName[grids[i].gd.uniqueName()] = read[i];
    }
    for (size_t i = 0; i < grids.size(); ++i) {
        if (!grids[i].gd.isInstance()) continue;
        const std::string parent = grids[i].gd.instanceParentName();
        auto it = byUniqueName.find(parent);
        if (it == byUniqueName.end())
            throw IoError(fmt::format("{}: truncated or damaged: grid '{}' shares the tree of a grid '{}' the file lacks",
                                      name, grids[i].gd.gridName(), GridDescriptor::nameAsString(parent)));
        read[i]->setTree(it->second->baseTreePtr());
    }
    if (all) return read;
    if (named) return {read[size_t(named - grids.data())]};
    return {mainGrid(read)};
}

openvdb::GridPtrVec readGridsChecked(std::istream& in, uint64_t size, const std::string& name,
                                     const std::string& gridName)
{
    return readSelected(in, size, name, gridName, gridName.empty());
}

VdbBricks readChecked(std::istream& in, uint64_t size, const std::string& name, const std::string& gridName,
                      uint64_t maxTileBricks)
{
    return bricksOfGrid(*readSelected(in, size, name, gridName, false).front(), name, maxTileBricks);
}

} // namespace

} // namespace svo::vdb
