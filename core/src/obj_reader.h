#pragma once
/// @file obj_reader.h (internal)
/// ASCII OBJ, read directly so that coordinates are correctly rounded doubles
/// (OpenMesh reads them as float) and faces that repeat a vertex are kept
/// (OpenMesh drops them).
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "svo/core/mesh.h"
#include "text_chunks.h"

namespace svo::detail {

/// A material library's bytes by the name an `mtllib` statement gives, or
/// nullopt when there is no such file.
using MaterialFiles = std::function<std::optional<std::string>(const std::string& name)>;

/// The mesh in an OBJ file: `v x y z [w]` or `v x y z r g b` vertices, `f`
/// faces in any of the v, v/vt, v//vn, v/vt/vn forms with absolute or
/// negative (relative) indices, polygons fan-triangulated. Comments, blank
/// lines, CRLF and `\` continuations are accepted; other statements (vt, vn,
/// o, g, s, l, p, ...) are ignored. Colours: the vertex colours when every
/// vertex has one; otherwise, when every face lies under a `usemtl` whose
/// material has a diffuse colour (Kd) in an `mtllib` library, that colour
/// (a vertex on faces of different colours is split into one per colour).
/// A library that is not found is a warning, as are faces without a Kd
/// among faces with one (then no colours are used); a malformed library is
/// an error naming it. `materialFiles` reads the libraries (default: files
/// beside `path`). Throws svo::Error naming
/// the file and line for anything malformed or out of range. Files of more
/// than one `chunkBytes` piece are parsed in pieces in parallel and give the
/// same mesh, warnings and errors (an error, or a relative index, which needs
/// the vertices before its piece, sends the file to the one-piece path).
/// `inPieces`, when set, gets how many pieces gave the mesh (0: read as one).
TriangleMesh readObj(const std::string& path, std::string_view bytes, size_t chunkBytes = kTextChunkBytes,
                     size_t* inPieces = nullptr, const MaterialFiles& materialFiles = {});

/// Blocks of an OBJ file read at a time by readObjFile.
constexpr size_t kObjBlockBytes = size_t(16) << 20;

/// The mesh of the OBJ file at `path`, as readObj gives it from the file's
/// bytes, read `blockBytes` at a time and parsed in pieces as it is read, so
/// that the file's text is never all in memory (a file that needs reading in
/// order, for a relative index or to name an error's line, is read whole).
/// Throws svo::IoError when the file cannot be read, and as readObj.
TriangleMesh readObjFile(const std::string& path, size_t blockBytes = kObjBlockBytes,
                         size_t chunkBytes = kTextChunkBytes, const MaterialFiles& materialFiles = {});

} // namespace svo::detail
