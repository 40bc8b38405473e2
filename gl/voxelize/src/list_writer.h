#pragma once
/// @file list_writer.h (internal)
/// What fills the voxel list on the GPU, for either backend: the mesh
/// uploaded in local float coordinates, and work (raster draws or compute
/// dispatches) that appends every kept voxel through the list's atomic
/// counter. Both backends walk columns with column_walk.glsl.
#include <memory>
#include <vector>

#include "svo/core/voxel_box.h"
#include "svo/gl/buffer.h"
#include "svo/gl/program.h"
#include "svo/gl/timer_query.h"
#include "svo/gl/raster_voxelizer.h"
#include "voxelize_layout.h"

namespace svo::gl {

class ListWriter {
public:
    /// Uploads the mesh (timed as the "upload" stage) and estimates the list size.
    ListWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid, const RasterOptions& options);
    virtual ~ListWriter() = default;
    ListWriter(const ListWriter&) = delete;
    ListWriter& operator=(const ListWriter&) = delete;

    /// Issues the work that fills `list` (room for `capacity` entries) and
    /// counts into `counter`, which keeps counting past the end; `triangles`,
    /// when given, gets each entry's triangle. No wait.
    virtual void write(const Buffer& list, const Buffer& counter, uint64_t capacity,
                       const Buffer* triangles = nullptr) const = 0;
    /// GPU bytes held besides the list: the mesh, and any work buffers.
    virtual uint64_t bytes() const { return meshBytes_; }

    /// The next write()s keep only voxels in `box` (initially the whole grid)
    /// and report progress to `checkpoint`.
    void setClip(const VoxelBox& box, const Checkpoint& checkpoint)
    {
        clip_ = box;
        checkpoint_ = checkpoint;
    }

    uint64_t estimatedEntries() const { return estimate_; }
    StageTime uploadStage() const { return {"upload", uploadTimer_.milliseconds(), uploadWallMs_}; }

protected:
    const Buffer *vertices_ = nullptr, *indices_ = nullptr;
    std::vector<Vec3f> local_; ///< the uploaded positions, for host-side bounds
    uint64_t triangles_ = 0;
    float half_ = 0.5f; ///< voxel half side with the guard band
    float thickness_ = 0.0f; ///< thin mode's segment half width: half the guard band
    bool thin_ = false;      ///< thin (6-separating) test instead of the cube
    std::array<uint32_t, 3> dims_{};
    Checkpoint checkpoint_; ///< the writer's part of the call
    VoxelBox clip_;         ///< the voxels write() keeps

    /// Sets the clip box uniforms column_walk.glsl reads.
    void setClipUniforms(const Program& program) const;

private:
    TimerQuery uploadTimer_;
    double uploadWallMs_ = 0;
    uint64_t estimate_ = 0, meshBytes_ = 0;
};

/// The raster backend's writer (raster.geom, raster.frag).
std::unique_ptr<ListWriter> makeRasterWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                             const RasterOptions& options);
/// The compute backend's writer (voxelize.comp).
std::unique_ptr<ListWriter> makeComputeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                              const RasterOptions& options);
/// The writer options.pipeline asks for.
std::unique_ptr<ListWriter> makeWriter(const Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                                       const RasterOptions& options);

/// A voxel list with room for `capacity` entries (the context's scratch
/// buffer); refused beyond the 2^32 - 1 its atomic counter addresses.
const Buffer& makeList(const Context& context, uint64_t capacity);
/// The list's first `count` entries read back, sorted and unique.
std::vector<uint64_t> readList(const Buffer& list, uint32_t count);

} // namespace svo::gl
