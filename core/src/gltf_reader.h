#pragma once
/// @file gltf_reader.h (internal)
/// glTF 2.0, text (.gltf) and binary (.glb), parsed by tinygltf and, for
/// KHR_draco_mesh_compression primitives, decoded by libdraco. Both stay
/// inside gltf_reader.cpp: this header is all the rest of svo sees.
#include <cstdint>
#include <string>

#include "svo/core/mesh.h"

namespace svo::detail {

/// What readGltf may do beyond parsing the bytes it is given.
struct GltfReadOptions {
    /// Whether buffers may come from files named by relative URIs (beside
    /// the .gltf); off, such a buffer is an error (the fuzz target's setting).
    bool externalFiles = true;
    /// The most vertices the mesh may have once every instance is placed;
    /// more is an error before the memory is taken.
    uint64_t maxVertices = UINT32_MAX - 1;
};

/// The triangles of the default scene (scene 0 when none is named, every
/// root node when the file has no scene), each primitive placed by the
/// transforms of the nodes above it (matrix or translation, rotation, scale),
/// once per node that names its mesh. Triangle lists, strips and fans are
/// read; point and line primitives are skipped with a warning. Vertices are
/// the file's float (or, with KHR_mesh_quantization, integer) positions
/// transformed in double; a transform that mirrors reverses its triangles'
/// order, as glTF defines. Colours: glTF's base colour without textures
/// (COLOR_0 times the material's baseColorFactor) when any primitive has
/// COLOR_0 or a base colour other than white; none otherwise.
/// @param path the file's name for messages; its folder holds external buffers
/// @param bytes the whole file: binary when it starts with "glTF", JSON otherwise
/// @throw svo::IoError naming the file and the problem for a damaged or
///        malformed file, a missing buffer, an index or accessor out of range,
///        a node reached twice, or a required extension svo does not read
///        (meshopt compression, GPU instancing)
TriangleMesh readGltf(const std::string& path, const std::string& bytes, const GltfReadOptions& options = {});

} // namespace svo::detail
