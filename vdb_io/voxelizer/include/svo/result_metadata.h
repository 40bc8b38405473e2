#pragma once
/// @file result_metadata.h
/// @brief The "svo:*" metadata a front end stores on the grids it makes of a
/// mesh, so that a file says where its grids came from whoever wrote it (the
/// command line, Python). No OpenVDB here: the writers store the map as
/// string metadata (svo/vdb_io/vdb_file.h).
#include <map>
#include <string>

#include "svo/core/grid.h"
#include "svo/core/mesh.h"

namespace svo {

/// @brief svo's version, "MAJOR.MINOR.PATCH": the project's version in CMake,
/// the one source of every front end's version (the CLI's, Python's __version__).
const char* version();

/// @brief The metadata of a result made of a file rather than of a mesh (svo
/// convert's grids and octrees): "svo:source" (@a source) and "svo:version".
/// @param source the input file, as given
std::map<std::string, std::string> sourceMetadata(const std::string& source);

/// @brief The metadata of a result made of @a mesh on @a grid: "svo:source"
/// (the mesh's source), "svo:triangles", "svo:grid" (how the grid was asked
/// for: "resolution N", "voxel size H", or "transform" where neither was
/// given), "svo:voxel_size", "svo:version" and, with @a guardBand (surface
/// voxelizations, whose voxels it decides), "svo:epsilon" in voxels. The
/// command line and Python both call it, so that the same call gives the same
/// keys and values from either (only "svo:source" differs: a file's path there,
/// "mesh" for Python's arrays).
/// @param request as the caller asked, before makeGrid filled in a default
std::map<std::string, std::string> resultMetadata(const TriangleMesh& mesh, const GridSpec& grid,
                                                  const GridRequest& request, bool guardBand);

} // namespace svo
