#pragma once
/// @file stl_reader.h (internal)
/// STL, read directly: ASCII coordinates as correctly rounded doubles (OpenMesh
/// reads them as float), binary ones as the floats they are, and corners
/// welded exactly by their bits instead of OpenMesh's ordered map, in which a
/// NaN compares equal to anything.
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// The mesh in an ASCII or binary STL file, one triangle per facet in file
/// order (an ASCII loop of more than 3 vertices is fan-triangulated), corners
/// with bit-identical coordinates shared. Throws svo::Error naming the file
/// and the problem (and the line, for ASCII) for a truncated or malformed
/// file or a non-finite coordinate.
TriangleMesh readStl(const std::string& path, const std::string& bytes);

} // namespace svo::detail
