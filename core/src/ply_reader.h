#pragma once
/// @file ply_reader.h (internal)
/// PLY, ASCII and binary of either byte order, read directly: OpenMesh reads
/// coordinates as float, even `double` properties.
#include <cstddef>
#include <string>

#include "svo/core/mesh.h"
#include "text_chunks.h"

namespace svo::detail {

/// The mesh in a PLY file: the `vertex` element's x, y, z of any scalar type,
/// in double (text correctly rounded, binary as stored); the `face` element's
/// `vertex_indices` (or `vertex_index`) lists, fan-triangulated. Other
/// properties and elements, lists included, are skipped. Throws svo::Error
/// naming the file and the problem for a malformed header, a count the file
/// cannot hold, a truncated body, a non-finite coordinate or a bad index.
/// An ASCII body of `parallelFrom` bytes or more is cut into records, one a
/// line, read in parallel, with the same mesh and errors (anything that
/// reading refuses, or a record that is not one line, sends the body to the
/// one-piece path, which names it); `inParallel` says whether it was.
TriangleMesh readPly(const std::string& path, const std::string& bytes, size_t parallelFrom = kTextChunkBytes,
                     bool* inParallel = nullptr);

} // namespace svo::detail
