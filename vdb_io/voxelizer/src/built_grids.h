#pragma once
// Where the front door's GPU-built NanoVDB grids go (docs/design.md, "NanoVDB
// grids on the GPU"): read back into host handles, each given NanoVDB's full
// checksum on the host, or kept on the device, with the GPU's checksum, for
// a caller's callback. Private to the front door (nanovdb_calls.cpp).
#include <functional>
#include <vector>

#include "svo/gl/nano_grid_builder.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/voxelizer.h"

namespace svo::detail {

class BuiltGrids {
public:
    /// @param context  the context the grids are built in (current while they live)
    /// @param onDevice keep the grids on the device instead of reading them back
    /// @param stats    receives a stage per step and the warnings
    BuiltGrids(const gl::Context& context, bool onDevice, VoxelizeStats& stats);
    BuiltGrids(const BuiltGrids&) = delete;
    BuiltGrids& operator=(const BuiltGrids&) = delete;
    /// Gives the device grids' buffers back to the context's scratch.
    ~BuiltGrids();

    /// @brief Builds one grid of @a leaves on the GPU. On the host: read
    /// back, then the host's full checksum; a grid past the builder's limits
    /// (svo::Unsupported, thrown before the grid is made) is laid out by
    /// `onHost()` instead (with its checksum), with a warning. On the
    /// device: the GPU's checksum.
    /// @throw svo::Unsupported on the device, for a grid past the builder's
    ///        limits: it cannot stay there
    void add(gl::NanoKind kind, const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header,
             const std::function<vdb::NanoHandle()>& onHost);

    /// Whether the grids stay on the device (the constructor's @a onDevice).
    bool onDevice() const { return onDevice_; }
    std::vector<vdb::NanoHandle>& host() { return host_; }
    const std::vector<gl::NanoGridBuffer>& device() const { return device_; }
    /// The first grid kept on the device: its active voxels and leaves (the
    /// call's counts; the host's handles give theirs themselves).
    std::pair<uint64_t, uint64_t> firstDeviceCounts() const;

private:
    void addOnHost(gl::NanoKind kind, const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header,
                   const std::function<vdb::NanoHandle()>& onHost);
    void addOnDevice(gl::NanoKind kind, const gl::NanoLeaves& leaves, const gl::NanoGridHeader& header);

    const gl::Context& context_;
    bool onDevice_;
    VoxelizeStats& stats_;
    std::vector<vdb::NanoHandle> host_;
    std::vector<gl::NanoGridBuffer> device_;
};

} // namespace svo::detail
