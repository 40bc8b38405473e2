#pragma once
/// @file ply_reader.h (internal)
/// PLY, ASCII and binary of either byte order, read directly: OpenMesh reads
/// coordinates as float, even `double` properties.
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// The mesh in a PLY file: the `vertex` element's x, y, z of any scalar type,
/// in double (text correctly rounded, binary as stored); the `face` element's
/// `vertex_indices` (or `vertex_index`) lists, fan-triangulated. Other
/// properties and elements, lists included, are skipped. Throws svo::Error
/// naming the file and the problem for a malformed header, a count the file
/// cannot hold, a truncated body, a non-finite coordinate or a bad index.
TriangleMesh readPly(const std::string& path, const std::string& bytes);

} // namespace svo::detail
