#pragma once
/// @file fields_shaders.h (internal)
/// This layer's shaders, embedded in the library by svo_embed_files
/// (gl/fields/CMakeLists.txt) and passed to Context::program.
#include "svo/gl/shader_files.h"

namespace svo::gl {
const ShaderFiles& fieldsShaders();
} // namespace svo::gl
