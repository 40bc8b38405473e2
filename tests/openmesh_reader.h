#pragma once
/// @file openmesh_reader.h (the tests')
/// Any format through OpenMesh's readers. svo reads every format itself; the
/// tests use this to hold svo's readers to what OpenMesh reads.
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// The mesh OpenMesh's reader for the file's format delivers, faces as it
/// reports them (fan-triangulated, none refused), not validated. Throws
/// svo::Error with OpenMesh's diagnostics when it fails.
TriangleMesh readWithOpenMesh(const std::string& path);

} // namespace svo::detail
