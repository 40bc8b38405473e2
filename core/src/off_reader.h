#pragma once
/// @file off_reader.h (internal)
/// ASCII OFF, read directly. OpenMesh's OFF reader stops at comments before
/// the keyword or inside the body (which CGAL's tools write) and then hands
/// over uninitialized indices; OFF is simple enough to read exactly here.
#include <optional>
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// The mesh in an ASCII OFF/COFF/NOFF/CNOFF/STOFF... file, polygons fan-
/// triangulated; std::nullopt for a binary OFF (left to OpenMesh). Throws
/// svo::Error naming the file and line for anything malformed.
std::optional<TriangleMesh> readAsciiOff(const std::string& path, const std::string& bytes);

} // namespace svo::detail
