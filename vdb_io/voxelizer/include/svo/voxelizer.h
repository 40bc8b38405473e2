#pragma once
/// @file voxelizer.h
/// @brief svo::Voxelizer: triangle meshes to OpenVDB grids and sparse voxel
/// octrees on the GPU (OpenGL 4.5 core through headless EGL).
///
/// @details Method. Each vertex goes to the index space of the given transform
/// in double precision on the CPU (relative to an integer anchor near the
/// mesh, so a mesh far from the origin loses nothing). The GPU rasterizes each
/// triangle along its dominant axis, enlarged so that every voxel column it
/// touches gets a fragment, and keeps each voxel of the column that passes the
/// shared triangle/box overlap test on a cube grown by a small guard band that
/// covers float rounding. Compute shaders then build a linear octree of 8^3
/// bricks (OpenVDB leaf masks) from the voxels, and only the octree comes back.
/// Grids are made from the bricks by copying masks into leaves.
///
/// Guarantees.
/// - Conservative coverage (the default mode): the result holds every voxel
///   whose closed cube [i-1/2, i+1/2]^3 (index space) meets a triangle, so a
///   closed mesh gives a watertight (26-separating) shell. Voxels beyond that
///   set are only those within the guard band of a triangle
///   (VoxelizeStats::epsilon voxels).
/// - Thin coverage (VoxelMode::Thin): every voxel one of whose three
///   axis-aligned centre segments (closed, one voxel long) meets a triangle,
///   a subset of the conservative voxels that is still 6-separating (no
///   6-connected path crosses a closed mesh's shell). Voxels beyond it are
///   only those whose segments, grown by the guard band, meet a triangle.
/// - Exact in the transform's index space: any affine transform works
///   (uniform or non-uniform scale, rotation, shear, translation), because
///   the voxels are cubes of index space; the output grid carries the
///   transform it was given.
/// - Degenerate triangles (needles, points) still cover what they touch.
/// - Deterministic: the same input gives the same voxels on every call.
///
/// Reuse. A Voxelizer owns its GL context, the linked programs and the
/// scratch buffers, so only the first call pays for EGL start-up and making
/// programs (loaded from the program cache, DeviceOptions::programCache, or
/// compiled), and a warm call pays only for its work. Scratch buffers stay
/// at their largest size until releaseScratch(), and so does the last
/// winding tree: a call over the same triangles on the same grid (another
/// region or tile of it) reuses it (svo/core/winding_tree_cache.h).
///
/// Host contexts. The Voxelizer's context is current only inside a call; the
/// context the calling thread had current before (EGL, or GLX such as a
/// GLFW window's) is current again on every path out, errors included.
///
/// Threads. One thread at a time per Voxelizer (calls are not synchronized).
/// Several Voxelizers may run in parallel on different threads, on the same
/// device or on different ones.
///
/// Errors. Every exception is an svo::Error (svo/core/error.h) naming the
/// problem and the offending value, of a class that says what failed:
/// svo::InvalidInput for bad meshes (index out of range, NaN/Inf vertices),
/// impossible grids, a non-linear transform or a bad option; svo::DeviceError
/// for no usable GPU or a GL failure; svo::OutOfMemory for GPU or host memory
/// (or the budget) exhausted; svo::Unsupported for a request svo has no
/// method for; svo::Interrupted for an interrupted call. After any exception
/// the Voxelizer is usable for the next call.
#include <openvdb/openvdb.h>
#include <openvdb/util/NullInterrupter.h>
#include <openvdb/util/Util.h> // INVALID_IDX

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "svo/core/mesh.h"
#include "svo/core/octree.h"
#include "svo/core/voxel_mode.h"
#include "svo/core/voxelization.h"
#include "svo/gl/device.h"            // gl::Device, DeviceOptions, StartupStats
#include "svo/gl/field_pipeline.h"    // SignMethod, SignOptions, LevelSetOptions and their rules
#include "svo/gl/nano_grid_builder.h" // gl::NanoGridBuffer
#include "svo/gl/voxelize_settings.h" // Backend, Dilation, VoxelizeSettings
#include "svo/gl/voxelize_stats.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/grid_options.h"
#include "svo/vdb_io/nanovdb_grids.h"

namespace svo {

/// @brief Options of one call: what to compute and where (VoxelizeSettings), and
/// how the call reports. Plain values; the defaults suit most uses.
struct VoxelizeOptions : VoxelizeSettings {
    /// Polled between stages and between tiles with the percentage done;
    /// returning true cancels the call (svo::Interrupted). start() and end()
    /// bracket the call. Must outlive the call.
    openvdb::util::NullInterrupter* interrupter = nullptr;
    /// When set, filled with the call's statistics.
    VoxelizeStats* stats = nullptr;
};

/// @brief Takes NanoVDB grids kept on the GPU (the `...NanoVdbOnDevice`
/// calls), each in a GL buffer of the Voxelizer's context, which is current
/// during the call: bind them, copy them, register them with CUDA-GL interop
/// or read them back there. They are freed when it returns.
using NanoGridsOnDevice = std::function<void(const std::vector<gl::NanoGridBuffer>&)>;

struct IndexSpaceMesh;

/// @brief A reusable voxelizer: meshes to grids, octrees, level sets and
/// solids, and grids to octrees. Owns its GL context (see the file comment:
/// reuse, host contexts, threads, errors). Movable, not copyable.
class Voxelizer {
public:
    /// @brief Creates no GL context yet: the first GPU call does (so a
    /// Cpu-backend user never needs one). Throws nothing.
    /// @param device which GPU, GL debug output, the program cache
    explicit Voxelizer(const DeviceOptions& device = {});
    ~Voxelizer();
    Voxelizer(Voxelizer&&) noexcept;
    Voxelizer& operator=(Voxelizer&&) noexcept;

    /// @brief The voxels of a mesh as a MaskGrid whose transform is @a xform.
    /// @param points     vertices in world units
    /// @param triangles  vertex indices; each must be < points.size()
    /// @param xform      any linear (affine) transform; voxels are index-space cubes of it
    /// @param options    backend, channels, interrupter, statistics
    /// @return the grid, named "surface", class GRID_UNKNOWN
    /// @throw svo::InvalidInput for an empty mesh, an index out of range, a NaN/Inf
    ///        vertex, a non-linear or singular transform, a grid beyond
    ///        OpenVDB's 32-bit coordinates or svo's 2^21 voxels a side, or
    ///        an option that contradicts another
    /// @throw svo::DeviceError for no usable GPU or a GL failure
    /// @throw svo::OutOfMemory when GPU or host memory (or the budget) runs out
    /// @throw svo::Unsupported for a result beyond one octree's 32-bit indices
    /// @throw svo::Interrupted when options.interrupter asks to stop
    openvdb::MaskGrid::Ptr meshToMask(const std::vector<openvdb::Vec3s>& points,
                                      const std::vector<openvdb::Vec3I>& triangles,
                                      const openvdb::math::Transform& xform, const VoxelizeOptions& options = {});
    /// @brief Double-precision vertices: a mesh far from the origin is not
    /// rounded before svo maps it.
    /// @throw as above
    openvdb::MaskGrid::Ptr meshToMask(const std::vector<openvdb::Vec3d>& points,
                                      const std::vector<openvdb::Vec3I>& triangles,
                                      const openvdb::math::Transform& xform, const VoxelizeOptions& options = {});
    /// @brief Triangles and quads, as OpenVDB's meshToVolume takes them: a quad
    /// whose fourth index is openvdb::util::INVALID_IDX is a triangle; others
    /// are split along their 0-2 diagonal.
    /// @throw as above
    openvdb::MaskGrid::Ptr meshToMask(const std::vector<openvdb::Vec3s>& points,
                                      const std::vector<openvdb::Vec3I>& triangles,
                                      const std::vector<openvdb::Vec4I>& quads,
                                      const openvdb::math::Transform& xform, const VoxelizeOptions& options = {});
    /// @brief Triangles and quads with double-precision vertices.
    /// @throw as above
    openvdb::MaskGrid::Ptr meshToMask(const std::vector<openvdb::Vec3d>& points,
                                      const std::vector<openvdb::Vec3I>& triangles,
                                      const std::vector<openvdb::Vec4I>& quads,
                                      const openvdb::math::Transform& xform, const VoxelizeOptions& options = {});

    /// @brief The same voxels as a BoolGrid (true on active voxels; what pyopenvdb reads).
    /// @throw as meshToMask
    template <typename PointT>
    openvdb::BoolGrid::Ptr meshToBool(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                      const openvdb::math::Transform& xform, const VoxelizeOptions& options = {});
    /// @brief The same voxels as a fog volume: FloatGrid, 1 on voxels,
    /// background 0, class GRID_FOG_VOLUME.
    /// @throw as meshToMask
    template <typename PointT>
    openvdb::FloatGrid::Ptr meshToFog(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                      const openvdb::math::Transform& xform, const VoxelizeOptions& options = {});
    /// @brief The topology grid, then the fog grid and the attribute channels
    /// (options.attributes) as grids "normal" (Vec3SGrid), "triangle_id"
    /// (Int32Grid) and "color" (Vec3SGrid), as @a grids asks.
    /// @throw as meshToMask
    template <typename PointT>
    openvdb::GridPtrVec meshToGrids(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                    const openvdb::math::Transform& xform, const VoxelizeOptions& options = {},
                                    const GridOptions& grids = {});

    /// @brief The voxels of a mesh as an octree.
    /// @details The octree's GridSpec is the transform's lattice when @a xform is
    /// a uniform scale plus a whole-voxel translation (what .svo files and
    /// octreeToGrids(octree) describe); for any other transform it is the
    /// transform's index space itself (voxel size 1), and the caller keeps
    /// @a xform to turn the octree into grids (octreeToGrids(octree, xform)).
    /// @param quads as meshToMask takes them; may be empty
    /// @throw as meshToMask
    template <typename PointT>
    Octree meshToOctree(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                        const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform,
                        const VoxelizeOptions& options = {});

    /// @brief svo's own types: a double-precision mesh on a grid chosen by
    /// makeGrid/makeGridOnLattice (what the CLI and the Python module use).
    /// @param grid      a grid from makeGrid or makeGridOnLattice
    /// @param voxelList when set, also receives the backend's voxel set read back
    ///        apart from the octree (sorted, unique keys), for consistency checks.
    /// @return the octree, in canonical order, with the channels asked for
    /// @throw svo::InvalidInput for a mesh that fails validateMesh or a grid
    ///        that fails checkGrid; otherwise as meshToMask
    Octree voxelize(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options = {},
                    std::vector<uint64_t>* voxelList = nullptr);

    /// @brief The active voxels of any grid (bool, mask, float, double, int32,
    /// int64, vec3; active tiles expanded) as an octree, built on the GPU
    /// (or the CPU with Backend::Cpu).
    /// @throw svo::InvalidInput for an unsupported type, a transform other than a
    ///        uniform scale plus a whole-voxel translation, or an extent beyond 2^21
    /// @throw svo::DeviceError, svo::OutOfMemory, svo::Unsupported,
    ///        svo::Interrupted as meshToMask
    Octree gridToOctree(const openvdb::GridBase& grid, const VoxelizeOptions& options = {});
    /// @brief Whole bricks (brick-origin key, mask) on a grid, built into an
    /// octree on the GPU (or the CPU with Backend::Cpu).
    /// @throw svo::InvalidInput for a grid that fails checkGrid or a brick
    ///        outside it; otherwise as meshToMask
    Octree bricksToOctree(const GridSpec& grid, std::vector<std::pair<uint64_t, Brick>> bricks,
                          const VoxelizeOptions& options = {});

    /// @brief A narrow-band signed distance field of a mesh: OpenVDB's
    /// meshToLevelSet, on the GPU.
    /// @details Method: each triangle's box grown by the band, cut to the
    /// slab about its plane, gives the band's bricks (no voxelization: the
    /// options' backend only refuses Backend::Cpu); the GPU computes, for every voxel centre in
    /// them, the exact distance to the closest triangle in double precision
    /// (rounded once to float), and its side: by parity along voxel columns
    /// for closed meshes (svo/gl/distance_field.h), by the winding number for
    /// others (svo/gl/winding_number.h; SignMethod). Values are world units
    /// (index distance times the voxel size), negative inside. Voxels closer
    /// than the band on their side are active; other voxels hold +/- the
    /// background, the exterior band times the voxel size, signed as OpenVDB's
    /// signedFloodFill signs them (parity) or as the winding number says.
    /// The grid has class GRID_LEVEL_SET and is named "surface".
    /// Guarantees: every active distance is within 1e-6 voxel of the exact
    /// distance (the float rounding of a double result); parity signs are
    /// exact for voxel centres farther than that from the surface on closed
    /// meshes.
    /// @param xform      a linear transform with uniform scale (distances are world units)
    /// @param exteriorBand, interiorBand  band half widths in voxels, each >= 1
    /// @return the grid, named "surface", class GRID_LEVEL_SET
    /// @throw everything meshToMask throws
    /// @throw svo::InvalidInput for a band that fails checkBand (NaN
    ///        included), a VoxelizeOptions::mode other than Conservative
    ///        (checkFieldMode) or a winding accuracy that fails
    ///        checkWindingAccuracy, or parity signs asked for a mesh with
    ///        holes (boundary edges: a column through a hole would flip every
    ///        sign beyond it; winding and Auto sign such meshes)
    /// @throw svo::Unsupported for a transform without uniform scale, or the
    ///        CPU backend (this is GPU work)
    template <typename PointT>
    openvdb::FloatGrid::Ptr meshToLevelSet(const std::vector<PointT>& points,
                                           const std::vector<openvdb::Vec3I>& triangles,
                                           const openvdb::math::Transform& xform, float exteriorBand = 3.0f,
                                           float interiorBand = 3.0f, const VoxelizeOptions& options = {});
    /// @brief Unsigned distances within @a band voxels (class GRID_UNKNOWN,
    /// named "distance", background band times the voxel size); needs no
    /// closed mesh.
    /// @throw as meshToLevelSet, but for the sign
    template <typename PointT>
    openvdb::FloatGrid::Ptr meshToUnsignedDistanceField(const std::vector<PointT>& points,
                                                        const std::vector<openvdb::Vec3I>& triangles,
                                                        const openvdb::math::Transform& xform, float band = 3.0f,
                                                        const VoxelizeOptions& options = {});
    /// @brief The solid a mesh bounds: every voxel whose centre is inside (by
    /// parity or winding number, as meshToLevelSet), plus the surface voxels
    /// (as meshToMask). Whole regions inside
    /// are active tiles at the largest tree level they fill, so memory follows
    /// the surface. Named "solid".
    /// @param sign how inside is decided (SignMethod)
    /// @throw as meshToLevelSet
    template <typename PointT>
    openvdb::MaskGrid::Ptr meshToSolid(const std::vector<PointT>& points, const std::vector<openvdb::Vec3I>& triangles,
                                       const openvdb::math::Transform& xform, const VoxelizeOptions& options = {},
                                       const SignOptions& sign = {});

    /// @brief The voxels whose centres are nearer than @a band voxels to a
    /// triangle: the active voxels of meshToUnsignedDistanceField() with that
    /// band, exactly, computed as only the set asks (a voxel found nearer
    /// than the band takes no more triangles; gl::bandTopologyBricks), on
    /// every backend. Needs no closed mesh.
    /// @param grid  a grid from makeGrid or makeGridOnLattice; the band may reach beyond grid.dims
    /// @param band  the band half width in voxels (checkBand: 1 to 1000)
    /// @param xform as for levelSet()
    /// @return the grid, named "band", class GRID_UNKNOWN
    /// @throw as levelSet()
    openvdb::MaskGrid::Ptr band(const TriangleMesh& mesh, const GridSpec& grid, double band,
                                const VoxelizeOptions& options = {}, openvdb::math::Transform::Ptr xform = nullptr);

    /// @brief Level set (or unsigned field) of svo's own mesh on a grid from
    /// makeGrid. The band may reach beyond grid.dims.
    /// @param levelSet the bands, sign, and whether to add closest triangles
    /// @return the distance grid, then "closest_triangle" when asked
    /// @param xform  the output's transform: null for the grid's own lattice
    ///        (makeTransform), or the transform whose index space prepareMesh
    ///        mapped the mesh to (uniform scale)
    /// @throw as meshToLevelSet, and svo::InvalidInput for a mesh that fails
    ///        validateMesh or a grid that fails checkGrid
    openvdb::GridPtrVec levelSet(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& levelSet = {},
                                 const VoxelizeOptions& options = {}, openvdb::math::Transform::Ptr xform = nullptr);
    /// @brief Solid of svo's own mesh on a grid from makeGrid (see meshToSolid).
    /// @param xform as for levelSet()
    /// @throw as levelSet()
    openvdb::MaskGrid::Ptr solid(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options = {},
                                 const SignOptions& sign = {}, openvdb::math::Transform::Ptr xform = nullptr);

    /// @brief voxelize() as NanoVDB grids (octreeToNanoGrids): laid out from
    /// the octree's bricks, with no OpenVDB tree.
    /// @param grids which grids (topology type and name, fog, channels)
    /// @throw as voxelize()
    std::vector<vdb::NanoHandle> voxelizeNanoVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                                 const VoxelizeOptions& options = {}, const GridOptions& grids = {});
    /// @brief An octree from voxelize() as NanoVDB grids, the same bytes as
    /// vdb::octreeToNanoGrids: every grid (topology, fog, channels) laid out
    /// on the GPU where @a options' backend runs on a GL device.
    /// @param octree  voxelize()'s result
    /// @param grids   which grids (topology type and name, fog, channels)
    /// @param options the backend (as given to voxelize()); its stats, if any, get the stages
    /// @throw svo::DeviceError or svo::OutOfMemory from the GPU
    std::vector<vdb::NanoHandle> octreeNanoVdb(const Octree& octree, const GridOptions& grids = {},
                                               const VoxelizeOptions& options = {});
    /// @brief levelSet() as NanoVDB grids, laid out from the field's bricks
    /// with no OpenVDB tree (levelSetNanoGrids), on the grid's own lattice;
    /// a field cut into regions (a GPU memory budget, or past one shader
    /// buffer) joins their bricks (joinFields) and is laid out from them,
    /// the whole grid's bytes; with a region, the region's bricks cut to it
    /// (clipField). Equal, voxel for voxel and value for value, to levelSet()'s.
    /// On a GL backend the field is laid out on the GPU
    /// (gl::buildNanoGridGpu, the band never read back; a parity-signed
    /// level set flood filled there, a winding-signed one's whole inside
    /// bricks as tiles), the same bytes.
    /// @throw as levelSet()
    std::vector<vdb::NanoHandle> levelSetNanoVdb(const TriangleMesh& mesh, const GridSpec& grid,
                                                 const LevelSetOptions& levelSet = {}, const VoxelizeOptions& options = {});
    /// @brief levelSetNanoVdb()'s grids left on the GPU ("distance" or
    /// "surface", then "closest_triangle" when asked), byte for byte with
    /// their full checksums (made on the GPU), each in a GL buffer of this
    /// Voxelizer's context (gl::NanoGridBuffer: the buffer, the grid's
    /// bytes), handed to @a use while that context is current. They are freed
    /// when @a use returns; the context the thread had current before is
    /// current again after the call, as after every call.
    /// @param use called once, on this thread, with the grids
    /// @throw svo::Unsupported unless the call can keep the grids on the GPU:
    ///        a GL backend, no region or GPU memory budget, and a grid within
    ///        the GPU builder's limits (a parity-signed level set's flood
    ///        fill within the driver's loop limit);
    ///        otherwise as levelSet() (svo::OutOfMemory where one shader
    ///        buffer cannot hold the field: levelSetNanoVdb() cuts it into
    ///        regions), and whatever @a use throws
    void levelSetNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& levelSet,
                                 const VoxelizeOptions& options, const NanoGridsOnDevice& use);
    /// @brief levelSetNanoVdbOnDevice() for an unsigned field only.
    /// @throw svo::Unsupported for a signed field; otherwise as levelSetNanoVdbOnDevice()
    void unsignedFieldNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& levelSet,
                                      const VoxelizeOptions& options, const NanoGridsOnDevice& use);
    /// @brief octreeNanoVdb()'s grids (topology, fog, channels) left on the
    /// GPU, as levelSetNanoVdbOnDevice() leaves a field's.
    /// @throw svo::Unsupported off a GL backend, or for a grid past the GPU
    ///        builder's limits; svo::DeviceError or svo::OutOfMemory from the
    ///        GPU, and whatever @a use throws
    void octreeNanoVdbOnDevice(const Octree& octree, const GridOptions& grids, const VoxelizeOptions& options,
                               const NanoGridsOnDevice& use);
    /// @brief band() as the NanoVDB grid "band" (bandNanoGrid), as
    /// levelSetNanoVdb() lays out an unsigned field (regions joined, or on
    /// the GPU from leaves that never leave it, without values, computed as
    /// only the set asks: a voxel already nearer than the band takes no
    /// more distances), the same bytes on every backend.
    /// @param topology ValueMask, class Topology (Mask), or bool true on the voxels (Bool)
    /// @throw as band()
    vdb::NanoHandle bandNanoVdb(const TriangleMesh& mesh, const GridSpec& grid, double band,
                                const VoxelizeOptions& options = {},
                                GridOptions::Topology topology = GridOptions::Topology::Mask);
    /// @brief bandNanoVdb()'s grid left on the GPU, as
    /// levelSetNanoVdbOnDevice() leaves a field's.
    /// @throw svo::Unsupported off a GL backend, with a region or a GPU
    ///        memory budget; otherwise as band(), and whatever @a use throws
    void bandNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, double band,
                             const VoxelizeOptions& options, GridOptions::Topology topology,
                             const NanoGridsOnDevice& use);
    /// @brief solid() as the NanoVDB grid "solid" (solidNanoGrid), as
    /// levelSetNanoVdb (regions joined by joinSolids); on a GL backend laid
    /// out on the GPU from the solid's leaves and 8³ tiles (vdb::solidVoxels,
    /// uploaded), the same bytes.
    /// @param topology ValueMask (Mask) or bool true on inside voxels (Bool), as withTopology gives
    /// @throw as solid()
    vdb::NanoHandle solidNanoVdb(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options = {},
                                 const SignOptions& sign = {},
                                 GridOptions::Topology topology = GridOptions::Topology::Mask);
    /// @brief solidNanoVdb()'s grid left on the GPU, as
    /// levelSetNanoVdbOnDevice() leaves a field's.
    /// @throw svo::Unsupported off a GL backend, with a region or a GPU
    ///        memory budget, or for a grid past the GPU builder's limits;
    ///        otherwise as solid(), and whatever @a use throws
    void solidNanoVdbOnDevice(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                              const SignOptions& sign, GridOptions::Topology topology, const NanoGridsOnDevice& use);

    /// @brief The backend a voxelize call with @a options runs on: Backend::Auto
    /// resolved (a dilation mode's raster backend when one is asked for; else
    /// compute on a hardware GPU, raster on a software rasterizer such as
    /// llvmpipe). Creates no GL context: before one exists, EGL is asked
    /// whether the device is software, without making a context.
    /// @return never Backend::Auto
    /// @throw svo::InvalidInput for a dilation mode with Backend::Compute.
    Backend backendFor(const VoxelizeOptions& options);
    /// @brief The GPU's vendor, renderer and version (creates the context if needed).
    /// @throw svo::DeviceError for no usable GPU or driver
    std::string deviceDescription();
    /// @brief Creates the GL context now, rather than in the first GPU call.
    /// @details EGL set-up is a large part of a cold start (docs/design.md,
    /// Start-up, gives figures), so a caller may run it on another thread
    /// while it reads its mesh: the context is
    /// left current nowhere, and later calls may come from any one thread.
    /// No other call on this Voxelizer may run meanwhile. The first call's
    /// statistics still report the set-up (StartupStats::eglMs).
    /// @throw svo::DeviceError as the first GPU call would: no usable GPU or driver.
    void startDevice();
    /// @brief Frees the scratch buffers and the winding tree kept for the next call.
    void releaseScratch();

private:
    /// voxelize() after the mesh and grid were checked.
    Octree voxelizeChecked(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                           std::vector<uint64_t>* voxelList);
    /// levelSet()/solid() after the mesh and grid were checked; `xform` is the
    /// output transform and `worldPerVoxel` its uniform scale.
    openvdb::GridPtrVec levelSetChecked(const TriangleMesh& mesh, const GridSpec& grid, const LevelSetOptions& ls,
                                        const VoxelizeOptions& options, openvdb::math::Transform::Ptr xform,
                                        double worldPerVoxel);
    openvdb::MaskGrid::Ptr solidChecked(const TriangleMesh& mesh, const GridSpec& grid, const VoxelizeOptions& options,
                                        const SignOptions& sign, openvdb::math::Transform::Ptr xform);
    gl::Device device_;
};

/// @brief A mesh in OpenVDB's types as svo's double-precision mesh, in world
/// units: what loadMesh gives for a file, so that makeGrid and
/// Voxelizer::voxelize treat it exactly as `svo voxelize` treats the file
/// (what the Python module does with a resolution or voxel size). Quads as
/// meshToMask splits them.
/// @throw svo::InvalidInput for an index out of range or a NaN/Inf vertex, naming the first.
TriangleMesh toTriangleMesh(const std::vector<openvdb::Vec3d>& points, const std::vector<openvdb::Vec3I>& triangles,
                            const std::vector<openvdb::Vec4I>& quads);
/// @brief The same from single-precision vertices.
/// @throw as above
TriangleMesh toTriangleMesh(const std::vector<openvdb::Vec3s>& points, const std::vector<openvdb::Vec3I>& triangles,
                            const std::vector<openvdb::Vec4I>& quads);
/// @brief A mesh in the index space of a transform, with the grid it
/// voxelizes on (prepareMesh).
struct IndexSpaceMesh {
    TriangleMesh mesh; ///< in the transform's index space, or on its lattice
    GridSpec grid;     ///< the grid the mesh voxelizes on
};
/// @brief A mesh in OpenVDB's types as svo's double-precision mesh in the index
/// space of @a xform, with the grid it voxelizes on (see Voxelizer::meshToOctree
/// for which lattice that is).
/// @throw svo::InvalidInput for a non-linear or singular transform, an index
///        out of range, a NaN/Inf vertex, or a grid beyond svo's limits
IndexSpaceMesh prepareMesh(const std::vector<openvdb::Vec3d>& points, const std::vector<openvdb::Vec3I>& triangles,
                           const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform);
/// @brief The same from single-precision vertices.
/// @throw as above
IndexSpaceMesh prepareMesh(const std::vector<openvdb::Vec3s>& points, const std::vector<openvdb::Vec3I>& triangles,
                           const std::vector<openvdb::Vec4I>& quads, const openvdb::math::Transform& xform);

} // namespace svo

