#include "built_grids.h"

#include <fmt/format.h>

#include "svo/core/error.h"
#include "svo/gl/timer_query.h"
#include "svo/vdb_io/nanovdb_checksum.h"
#include "voxelizer_state.h"

namespace svo::detail {
namespace {

/// Gives @a h NanoVDB's full checksum on the host.
void fullChecksum(vdb::NanoHandle& h, gl::NanoKind kind)
{
    switch (kind) {
    case gl::NanoKind::Float: return vdb::updateFullChecksum(*h.grid<float>());
    case gl::NanoKind::Int32: return vdb::updateFullChecksum(*h.grid<int32_t>());
    case gl::NanoKind::Vec3f: return vdb::updateFullChecksum(*h.grid<nanovdb::Vec3f>());
    case gl::NanoKind::Mask: return vdb::updateFullChecksum(*h.grid<nanovdb::ValueMask>());
    case gl::NanoKind::Bool: return vdb::updateFullChecksum(*h.grid<bool>());
    }
}

} // namespace

BuiltGrids::BuiltGrids(const gl::Context& context, bool onDevice, VoxelizeStats& stats)
    : context_(context), onDevice_(onDevice), stats_(stats)
{
}

BuiltGrids::~BuiltGrids()
{
    if (device_.empty()) return;
    const gl::Context::Scope scope(context_);
    for (gl::NanoGridBuffer& g : device_) context_.returnScratch(gl::kNanoGridScratch, std::move(g.grid));
}

void BuiltGrids::add(gl::NanoKind kind, const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header,
                     const std::function<vdb::NanoHandle()>& onHost)
{
    if (onDevice_) addOnDevice(kind, leaves, header);
    else addOnHost(kind, leaves, header, onHost);
}

// The host hashes the copy it has to read anyway (docs/design.md compares
// it with the GPU's checksum).
void BuiltGrids::addOnHost(gl::NanoKind kind, const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header,
                           const std::function<vdb::NanoHandle()>& onHost)
{
    auto t0 = Clock::now();
    gl::TimerQuery timer;
    timer.begin();
    gl::NanoGridBuffer built;
    gl::NanoGridHeader noChecksumYet = header;
    noChecksumYet.checksum = false;
    try {
        built = gl::buildNanoGridGpu(context_, kind, leaves, noChecksumYet);
    } catch (const Unsupported& e) {
        stats_.warnings.push_back(fmt::format("{}; grid \"{}\" laid out on the CPU instead", e.what(), header.name));
        t0 = Clock::now();
        host_.push_back(onHost());
        stats_.stages.push_back({"nanovdb grid (cpu)", -1, msSince(t0)});
        return;
    }
    timer.end();
    stats_.stages.push_back({"nanovdb grid (gpu)", timer.milliseconds(), msSince(t0)});
    t0 = Clock::now();
    nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(built.bytes);
    built.grid.readBulk(0, built.bytes, buffer.data());
    context_.returnScratch(gl::kNanoGridScratch, std::move(built.grid)); // the next grid's memory
    vdb::NanoHandle out(std::move(buffer));
    stats_.stages.push_back({"nanovdb readback", -1, msSince(t0)});
    t0 = Clock::now();
    fullChecksum(out, kind);
    stats_.stages.push_back({"nanovdb checksum", -1, msSince(t0)});
    host_.push_back(std::move(out));
}

void BuiltGrids::addOnDevice(gl::NanoKind kind, const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header)
{
    const auto t0 = Clock::now();
    gl::TimerQuery timer;
    timer.begin();
    gl::NanoGridHeader withChecksum = header;
    withChecksum.checksum = true;
    gl::NanoGridBuffer g;
    try {
        g = gl::buildNanoGridGpu(context_, kind, leaves, withChecksum);
    } catch (const Unsupported& e) {
        throw Unsupported(fmt::format("{}; grid \"{}\" cannot stay on the GPU", e.what(), header.name));
    }
    timer.end();
    stats_.stages.push_back({"nanovdb grid (gpu)", timer.milliseconds(), msSince(t0)});
    if (!g.nodes[0]) { // a grid of no leaves: the GPU leaves the checksum of its headers to the host
        nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(g.bytes);
        g.grid.read(0, g.bytes, buffer.data());
        vdb::NanoHandle h(std::move(buffer));
        fullChecksum(h, kind);
        g.grid.write(0, g.bytes, h.data());
    }
    device_.push_back(std::move(g));
}

std::pair<uint64_t, uint64_t> BuiltGrids::firstDeviceCounts() const
{
    if (device_.empty()) return {0, 0};
    // The grid's and tree's headers; the active voxel count is where every grid type keeps it.
    alignas(64) uint8_t head[sizeof(nanovdb::GridData) + sizeof(nanovdb::NanoTree<float>::DataType)];
    device_.front().grid.readBulk(0, sizeof head, head); // read() can copy the whole grid on some drivers
    return {reinterpret_cast<const nanovdb::NanoGrid<float>*>(head)->activeVoxelCount(), device_.front().nodes[0]};
}

} // namespace svo::detail
