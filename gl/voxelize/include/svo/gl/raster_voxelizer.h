#pragma once
/// @file raster_voxelizer.h
/// @brief The raster backend: conservative voxelization through the GL pipeline.
///
/// Method (raster.geom, raster.frag): each triangle is projected along its
/// dominant axis and enlarged by Hasselgren's edge offsets (or drawn with
/// GL_NV_conservative_raster where available), so every voxel column it
/// touches gets a fragment. The fragment walks the voxels of its column that
/// the triangle's plane can reach and keeps those passing the shared overlap
/// test (overlap.glsl) on the cube grown by epsilon()/2 (thin mode: on the
/// voxel's three centre segments, lengthened and thickened by epsilon()/2).
/// Survivors are
/// appended to a voxel list through an atomic counter; if the list overflows,
/// it is resized to the exact count and the draw runs once more.
///
/// Guarantee: the result holds every voxel whose cube, shrunk by
/// grid.epsilon(), meets a triangle (nothing is missed) and only voxels whose
/// cube, grown by grid.epsilon(), meets one. In thin mode the same holds for
/// the centre segments: every voxel one of whose segments meets a triangle
/// (the exact thin set), and only voxels one of whose segments, lengthened
/// and thickened by grid.epsilon(), meets one.
#include "svo/core/mesh.h"
#include "svo/core/voxelization.h"
#include "svo/gl/context.h"
#include "svo/gl/octree_builder.h"
#include "svo/gl/raster_options.h"

namespace svo::gl {

/// @brief The voxel set as sorted keys: rasterize, read the list back, sort
/// on the CPU. One pass, no tiles.
/// @param context the GL context to run in (made current for the call)
/// @param mesh    a mesh already checked (validateMesh)
/// @param grid    a grid already checked (checkGrid)
/// @param options the pipeline, dilation and mode (the octree-only fields are
///        ignored)
/// @param report  when set, receives the stages (upload, voxelize, readback,
///        sort), the list entries, the retries of an overflowed list and the
///        GPU buffer bytes
/// @return the grid and its voxels as sorted, unique keys
/// @throw svo::DeviceError when the list passes one shader buffer, Hardware
///        dilation is asked for where GL_NV_conservative_raster is missing,
///        or on a GL error
/// @throw svo::Unsupported when the list passes 2^32 entries
/// @throw svo::OutOfMemory when a GPU buffer cannot be allocated
/// @throw svo::Interrupted from options.checkpoint
Voxelization voxelizeRaster(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                            const RasterOptions& options = {}, RunStats* report = nullptr);

/// @brief The voxel set as an octree: rasterize, build the octree on the GPU
/// from the voxel list (octree_builder.h), read back only nodes and bricks.
///
/// The CPU waits once, after all passes are issued (and once more for
/// attribute channels). Out of core: when the list or octree would pass
/// options.gpuMemory (or the 32-bit limits), the grid is cut into tiles
/// (boxes of whole bricks, halved along their longest side until each fits)
/// that clip the same column walk, so each keeps exactly the whole grid's
/// voxels inside it; their bricks and attributes are merged on the host.
/// Programs and buffers come from the context's caches, so a repeated call
/// compiles nothing and allocates only when it needs more room.
/// @param context the GL context to run in (made current for the call)
/// @param mesh    a mesh already checked (validateMesh)
/// @param grid    a grid already checked (checkGrid)
/// @param options the pipeline, dilation, mode, channels, GPU budget,
///        checkpoint, and where to put the voxel list if wanted
/// @param report  when set, receives the stages (upload, voxelize, octree
///        build, readback, attributes, tile merge), the list entries, the
///        retries of overflowed buffers, the GPU buffer bytes and the tiles
/// @return the octree, in canonical order, with the channels asked for
/// @throw svo::OutOfMemory when the mesh alone passes the budget, when one
///        brick's list does not fit, when the merged octree would pass the
///        host's free memory (estimated from triangle areas before any tile
///        runs), or when a GPU buffer cannot be allocated
/// @throw svo::Unsupported for an octree beyond 2^32 bricks, too many voxels
///        for the attribute pass, or a mesh beyond the compute pipeline's
///        indices
/// @throw svo::DeviceError for Hardware dilation where it is missing, a mesh
///        past one shader buffer (compute), or a GL error
/// @throw svo::Interrupted from options.checkpoint
Octree voxelizeToOctree(Context& context, const TriangleMesh& mesh, const GridSpec& grid,
                        const RasterOptions& options = {}, RunStats* report = nullptr);

/// @brief Which dilation voxelizeRaster would use with @a options.
/// @return "hardware", "shader" or "centroid-push (baseline)"; "" for the
///         compute pipeline, which needs none
/// @throw svo::DeviceError for ConservativeMode::Hardware where
///        GL_NV_conservative_raster is missing
const char* conservativeModeName(const Context& context, const RasterOptions& options);

} // namespace svo::gl
