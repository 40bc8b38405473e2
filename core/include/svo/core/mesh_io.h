#pragma once
/// @file mesh_io.h
/// Mesh file input: OBJ, PLY (ASCII, binary), STL (ASCII, binary) and OFF.
/// svo reads all but binary OFF (left to OpenMesh) itself: text coordinates
/// correctly rounded to double, binary ones at the precision they are stored
/// in. Polygons are fan-triangulated. Faces reach us exactly as the file lists
/// them: degenerate, duplicate and non-manifold faces are kept, since they
/// still cover the voxels they touch.
#include <string>

#include "svo/core/mesh.h"

namespace svo {

/// Reads a mesh file. Throws svo::Error naming the file and the problem for a
/// missing or unreadable file, an unknown extension, an empty or truncated
/// file, zero triangles, NaN/Inf coordinates or out-of-range indices.
TriangleMesh loadMesh(const std::string& path);

/// Writes an ASCII .off (COFF when the mesh has colours) or .obj, chosen by the
/// extension, with coordinates in shortest round-trip form, atomically.
/// Throws svo::Error naming the path.
void writeMesh(const std::string& path, const TriangleMesh& mesh);

/// The file extensions loadMesh accepts, for help texts.
const char* supportedMeshExtensions();

} // namespace svo
