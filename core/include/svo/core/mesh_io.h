#pragma once
/// @file mesh_io.h
/// @brief Mesh file input: OBJ, PLY (ASCII, binary), STL (ASCII, binary), OFF
/// and glTF 2.0 (.gltf, .glb). svo reads all but binary OFF (left to OpenMesh)
/// and glTF (tinygltf, with libdraco for Draco-compressed primitives) itself:
/// text coordinates correctly rounded to double, binary ones at the precision
/// they are stored in. Polygons are fan-triangulated. A glTF file gives the
/// triangles of its default scene with the node transforms applied. Faces reach us exactly as the file lists
/// them: degenerate, duplicate and non-manifold faces are kept, since they
/// still cover the voxels they touch.
#include <string>

#include "svo/core/mesh.h"

namespace svo {

/// @brief Reads a mesh file, of the format its extension names.
/// @return the mesh, checked as validateMesh checks; TriangleMesh::source is @a path
/// @throw svo::IoError naming the file and the problem for a missing or
///        unreadable file, an unknown extension, an empty, truncated or
///        malformed file, zero triangles, NaN/Inf coordinates or out-of-range
///        indices (a file that holds a bad mesh is a damaged file)
TriangleMesh loadMesh(const std::string& path);

/// @brief Writes an ASCII .off (COFF when the mesh has colours) or .obj,
/// chosen by the extension, with coordinates in shortest round-trip form,
/// atomically (writeAtomically). The text is formatted on all cores and
/// streamed: memory beyond the mesh stays under 100 MB at any size.
/// @throw svo::IoError naming the path for another extension or a file that
///        cannot be written
void writeMesh(const std::string& path, const TriangleMesh& mesh);

/// @brief The file extensions loadMesh accepts, for help texts.
const char* supportedMeshExtensions();

} // namespace svo
