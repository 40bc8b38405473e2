#pragma once
/// @file nanovdb_shaders.h (internal)
/// This layer's shaders, embedded in the library by svo_embed_files
/// (gl/nanovdb/CMakeLists.txt) and passed to Context::program.
#include "svo/gl/shader_files.h"

namespace svo::gl {
const ShaderFiles& nanovdbShaders();
} // namespace svo::gl
