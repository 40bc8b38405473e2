#pragma once
/// @file svo.h
/// @brief The whole public API of svo: GPU voxelization of triangle meshes into
/// OpenVDB grids and sparse voxel octrees. See docs/api.md.
///
///   svo/voxelizer.h          svo::Voxelizer: reusable GPU voxelizer (meshes -> grids, octrees)
///   svo/mesh_to_volume.h     one-off free functions (svo::meshToMask, ...)
///   svo/vdb_io/grid_builder.h octrees <-> OpenVDB grids (octreeToGrids, gridToBricks)
///   svo/vdb_io/octree_files.h reading and writing .svo, .vdb and .nvdb files
///   svo/core/mesh_io.h       mesh files (OBJ, PLY, STL, OFF, glTF) in double precision
///   svo/core/octree.h        the linear octree: layout, traversal, checks
///   svo/core/voxel_key.h     voxel keys (octreeKeys) and their local coordinates
///   svo/core/error.h         svo::Error and its kinds (InvalidInput, IoError, ..., Interrupted)
///   svo/core/interrupt.h     Checkpoint: how a call hears its interrupter
#include "svo/core/error.h"
#include "svo/core/interrupt.h"
#include "svo/core/mesh_io.h"
#include "svo/core/octree.h"
#include "svo/core/octree_file.h"
#include "svo/core/voxel_key.h"
#include "svo/mesh_to_volume.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/nanovdb_output.h"
#include "svo/load_octree.h"
#include "svo/vdb_io/octree_files.h"
#include "svo/voxelizer.h"

/// @brief Version of the svo library these headers belong to.
#define SVO_VERSION_MAJOR 0
#define SVO_VERSION_MINOR 1
