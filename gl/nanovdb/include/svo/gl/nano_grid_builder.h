#pragma once
/// @file nano_grid_builder.h
/// @brief NanoVDB grids built on the GPU from sparse 8³ leaves, byte for byte
/// the grid that the CPU layout builder (svo::vdb::buildNanoGrid,
/// svo/vdb_io/nanovdb_layout.h) makes from the same leaves: the same
/// breadth-first order (root tiles by origin, nodes by parent and index in
/// it), masks, child offsets, bounding boxes and minimum/maximum statistics.
///
/// Passes (gl/nanovdb/shaders, docs/design.md "NanoVDB grids on the GPU"):
/// sort keys from the origins, a bitonic sort by (upper node, lower index,
/// leaf index), one scan that ranks lower and upper nodes, then the leaves
/// (a leaf's statistics folded over its voxels in bit order) and their
/// values, the lower and the upper nodes (a node's statistics an
/// order-keeping reduction over its children, so ties such as -0 and +0
/// resolve as the CPU's sequential fold does), and the headers, which the
/// host writes from the upper nodes' statistics it reads back (a few words
/// per upper node).
///
/// Tiles: 8³ tiles of lower nodes (a solid's whole inside bricks, a
/// winding-signed level set's inside bricks beyond its band), lower nodes
/// of tiles alone included, for the scalar kinds; not 128³ tiles of upper nodes, nor the values a
/// signed flood fill gives (a parity-signed level set's are flood filled on
/// the host copy, svo::vdb::signedFloodFill). The
/// checksum only when NanoGridHeader::checksum asks (nano_crc.comp, a CRC
/// per node); otherwise the grid's checksum field says "none" (all bits
/// set, as nanovdb::ChecksumMode::Disable leaves it) and
/// svo::vdb::updateFullChecksum on the host copy gives
/// nanovdb::ChecksumMode::Full's.
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "svo/core/octree.h"
#include "svo/gl/buffer.h"
#include "svo/gl/context.h"

namespace svo::gl {

/// @brief The grid's value type (nanovdb::GridType): Float and Int32 carry
/// 512 values per leaf and min/max statistics, Vec3f 512 vectors of 3 words
/// and min/max by squared length; Mask (ValueMask, topology only) and Bool
/// carry none.
enum class NanoKind : uint32_t { Float = 1, Int32 = 4, Vec3f = 6, Mask = 8, Bool = 11 };

/// @brief An 8³ tile of a lower node: one value for its whole brick.
struct NanoTile {
    std::array<int32_t, 3> origin{0, 0, 0}; ///< a multiple of 8, on no leaf
    uint32_t value = 0;                     ///< the value's word (Bool, Mask: non-zero is true)
    uint32_t active = 0;                    ///< 1: its 512 voxels are active
};

/// @brief The leaves, in any order, on the host or on the device, and
/// 8³ tiles on the host.
struct NanoLeaves {
    uint32_t count = 0; ///< number of leaves
    /// Host input (used when `origins` is set): per leaf its origin (a
    /// multiple of 8, unique), its active voxels in OpenVDB's bit order, and
    /// optionally 512 values (float or int32 bits, a word each; Vec3f three
    /// float words each; Bool: non-zero is on).
    const std::array<int32_t, 3>* origins = nullptr;
    const Brick* masks = nullptr;
    const uint32_t* values = nullptr;
    /// Device input (used when `origins` is null): the same, 3 ints, 16 uints
    /// and 512 values per leaf; `valueBuffer` may be null.
    const Buffer* originBuffer = nullptr;
    const Buffer* maskBuffer = nullptr;
    const Buffer* valueBuffer = nullptr;
    /// Float and Int32 leaves without values: when set, the word every
    /// active voxel holds (a fog volume's 1.0f bits), the background the
    /// others; when not (and for Vec3f), every voxel holds the background.
    std::optional<uint32_t> activeWord;
    uint32_t tileCount = 0;           ///< number of 8³ tiles (scalar kinds only)
    const NanoTile* tiles = nullptr;  ///< the tiles, in any order (host)
};

/// @brief What a grid holds besides its voxels (svo::vdb::NanoGridInfo's facts).
struct NanoGridHeader {
    std::string name;                                 ///< at most 255 bytes
    uint32_t gridClass = 0;                           ///< nanovdb::GridClass (Mask grids: Topology whatever is given)
    double voxelSize = 1.0;                           ///< index -> world scale
    std::array<double, 3> translation{0.0, 0.0, 0.0}; ///< world position of index (0, 0, 0)
    double background = 0.0;                          ///< converted to the kind's value (Bool: non-zero is true; Vec3f: every component)
    /// NanoVDB's full checksum (nanovdb::ChecksumMode::Full), the nodes'
    /// CRCs on the GPU, the headers' and the list's on the host; else (and
    /// for a grid of no leaves) the checksum field says "none".
    bool checksum = false;
    /// Float level sets: the inactive values signed as OpenVDB's
    /// tools::signedFloodFill signs them (svo::vdb::signedFloodFill's bits),
    /// on the GPU, before the checksum.
    bool signedFloodFill = false;
};

/// @brief The context's scratch buffer (Context::lendScratch) that a grid
/// of leaves is laid out in. A caller done with a grid gives its buffer
/// back (Context::returnScratch) so that the next grid reuses its memory.
inline constexpr const char* kNanoGridScratch = "nanovdb grid";

/// @brief A grid on the device, and its bytes on the host when asked for.
/// Like every gl::Buffer, `grid` is used and destroyed with its context
/// current (inside a Context::Scope).
struct NanoGridBuffer {
    Buffer grid;               ///< the whole grid at byte 0 (its buffer may be larger)
    uint64_t bytes = 0;        ///< the grid's size (GridData::mGridSize)
    std::array<uint32_t, 3> nodes{0, 0, 0}; ///< leaves, lower and upper nodes
    std::vector<uint8_t> host; ///< the grid's bytes, when asked for
};

/// @brief The 32-bit word a grid of @a kind stores for @a background: float
/// or int32 bits (Vec3f: each component's), 1 or 0 for Bool and Mask (a bool's byte).
/// @param kind       the value type
/// @param background the background, as NanoGridHeader holds it
/// @return the word
uint32_t backgroundWord(NanoKind kind, double background);

/// @brief Builds a NanoVDB grid of one kind from leaves on the GPU.
/// @param context    a GL 4.5 context (made current here)
/// @param kind       the value type
/// @param leaves     the leaves (host or device)
/// @param header     name, class, transform and background
/// @param hostCopy   also read the grid back into NanoGridBuffer::host
/// @return the grid, with every byte svo::vdb::buildNanoGrid writes for the
///         same leaves, the checksum only when the header asks (see the file
///         comment); a grid of leaves in the buffer lent as kNanoGridScratch
/// @throw svo::InvalidInput for a leaf or tile origin that is not a multiple
///        of 8, a repeated leaf or tile, a tile on a leaf, a name of 256 bytes
///        or more, inconsistent leaves (missing masks or tiles, device
///        buffers too small), tiles or an active word with Vec3f, or a
///        flood fill of a kind other than Float
/// @throw svo::Unsupported for a grid beyond 32-bit word addressing (16 GiB),
///        or a checksum or flood fill past the driver's loop limit
/// @throw svo::OutOfMemory or svo::DeviceError on a GL error
NanoGridBuffer buildNanoGridGpu(const Context& context, NanoKind kind, const NanoLeaves& leaves,
                                const NanoGridHeader& header, bool hostCopy = false);

} // namespace svo::gl
