#pragma once
/// @file off_reader.h (internal)
/// ASCII OFF, read directly. OpenMesh's OFF reader stops at comments before
/// the keyword or inside the body (which CGAL's tools write) and then hands
/// over uninitialized indices; OFF is simple enough to read exactly here.
#include <cstddef>
#include <optional>
#include <string>

#include "svo/core/mesh.h"
#include "text_chunks.h"

namespace svo::detail {

/// The mesh in an ASCII OFF/COFF/NOFF/CNOFF/STOFF... file, polygons fan-
/// triangulated; std::nullopt for a binary OFF (left to OpenMesh). Throws
/// svo::Error naming the file and line for anything malformed. A body of
/// more than one `chunkBytes` piece is parsed in pieces in parallel, with the
/// same mesh and the same errors (a piece that finds one hands the file to the
/// one-piece path, which names it).
/// `inPieces`, when set, gets how many pieces gave the body (0: read as one).
std::optional<TriangleMesh> readAsciiOff(const std::string& path, const std::string& bytes,
                                         size_t chunkBytes = kTextChunkBytes, size_t* inPieces = nullptr);

} // namespace svo::detail
