#pragma once
/// @file off_reader.h (internal)
/// OFF, ASCII and binary, read directly. OpenMesh's OFF reader stops at
/// comments before the keyword or inside the body (which CGAL's tools write)
/// and then hands over uninitialized indices, and its binary reader trusts
/// every count in the file (a negative or huge polygon size allocates without
/// bound); OFF is simple enough to read exactly here.
#include <cstddef>
#include <string>

#include "svo/core/mesh.h"
#include "text_chunks.h"

namespace svo::detail {

/// The mesh in an OFF/COFF/NOFF/CNOFF/STOFF... file, polygons fan-triangulated.
/// ASCII, or binary after an `OFF BINARY` header line (the OFF spec's layout:
/// big-endian int32 counts and indices, float32 coordinates; per vertex x y z,
/// then a normal if N, an RGBA colour if C, a texture coordinate if ST; per
/// face a count, its indices, a colour-component count and those floats).
/// Throws svo::Error naming the file (and, for ASCII, the line) for anything
/// malformed, counts the file cannot hold among them, before allocating for
/// them. An ASCII body of more than one `chunkBytes` piece is parsed in pieces
/// in parallel, with the same mesh and the same errors (a piece that finds one
/// hands the file to the one-piece path, which names it); a binary body is
/// read as one piece. `inPieces`, when set, gets how many pieces gave the body
/// (0: read as one).
TriangleMesh readOff(const std::string& path, const std::string& bytes, size_t chunkBytes = kTextChunkBytes,
                     size_t* inPieces = nullptr);

} // namespace svo::detail
