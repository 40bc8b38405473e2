#pragma once
/// @file openmesh_reader.h (internal)
/// Binary OFF through OpenMesh, the one format svo does not read itself.
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// The mesh OpenMesh's reader for the file's format delivers, faces as it
/// reports them (fan-triangulated, none refused), not validated. Throws
/// svo::Error with OpenMesh's diagnostics when it fails. The tests also use
/// it to hold svo's readers to what OpenMesh reads from the same files.
TriangleMesh readWithOpenMesh(const std::string& path);

} // namespace svo::detail
