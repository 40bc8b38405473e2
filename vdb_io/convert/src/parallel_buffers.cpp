#include "parallel_buffers.h"

#include <algorithm>
#include <sstream>
#include <string>
#include <tbb/parallel_for.h>
#include <vector>

#include <openvdb/io/io.h>
#include <openvdb/openvdb.h>

namespace svo::vdb {
namespace {

/// GridT whose writeBuffers writes chunks of leaves into strings on TBB's
/// threads, then the strings in order. Everything else is GridT's.
template <typename GridT>
class ParallelBuffersGrid final : public GridT {
public:
    explicit ParallelBuffersGrid(GridT& grid) : GridT(grid, openvdb::ShallowCopy()) {}

    void writeBuffers(std::ostream& os) const override
    {
        using LeafT = typename GridT::TreeType::LeafNodeType;
        std::vector<const LeafT*> leaves;
        leaves.reserve(size_t(this->tree().leafCount()));
        // The leaf iterator visits leaves in the order the tree's own
        // writeBuffers recursion does: root table order, then child index.
        for (auto it = this->tree().cbeginLeaf(); it; ++it) leaves.push_back(it.getLeaf());
        const uint32_t compression = openvdb::io::getDataCompression(os);
        const void* background = openvdb::io::getGridBackgroundValuePtr(os);
        const bool half = this->saveFloatAsHalf();
        constexpr size_t kLeavesPerChunk = 256; // enough work per task, few strings
        std::vector<std::string> chunks((leaves.size() + kLeavesPerChunk - 1) / kLeavesPerChunk);
        tbb::parallel_for(size_t(0), chunks.size(), [&](size_t c) {
            std::ostringstream s(std::ios::binary);
            openvdb::io::setDataCompression(s, compression);
            openvdb::io::setGridBackgroundValuePtr(s, background);
            const size_t end = std::min(leaves.size(), (c + 1) * kLeavesPerChunk);
            for (size_t i = c * kLeavesPerChunk; i < end; ++i) leaves[i]->writeBuffers(s, half);
            chunks[c] = std::move(s).str();
        });
        for (const std::string& chunk : chunks) os.write(chunk.data(), std::streamsize(chunk.size()));
    }
};

} // namespace

openvdb::GridBase::Ptr withParallelBuffers(const openvdb::GridBase::Ptr& grid)
{
    openvdb::GridBase::Ptr out = grid;
    grid->apply<openvdb::GridTypes>([&](auto& typed) {
        using GridT = std::decay_t<decltype(typed)>;
        if (GridT::hasMultiPassIO()) return;
        out = std::make_shared<ParallelBuffersGrid<GridT>>(typed);
    });
    return out;
}

} // namespace svo::vdb
