#pragma once
/// @file obj_reader.h (internal)
/// ASCII OBJ, read directly so that coordinates are correctly rounded doubles
/// (OpenMesh reads them as float) and faces that repeat a vertex are kept
/// (OpenMesh drops them).
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// The mesh in an OBJ file: `v x y z [w]` or `v x y z r g b` vertices, `f`
/// faces in any of the v, v/vt, v//vn, v/vt/vn forms with absolute or
/// negative (relative) indices, polygons fan-triangulated. Comments, blank
/// lines, CRLF and `\` continuations are accepted; other statements (vt, vn,
/// o, g, s, usemtl, mtllib, l, p, ...) are ignored. Throws svo::Error naming
/// the file and line for anything malformed or out of range.
TriangleMesh readObj(const std::string& path, const std::string& bytes);

} // namespace svo::detail
