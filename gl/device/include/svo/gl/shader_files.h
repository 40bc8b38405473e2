#pragma once
/// @file shader_files.h
/// @brief svo::gl::ShaderFiles: shader files by name, as a layer embeds them
/// (its CMakeLists.txt's svo_embed_files) and programs look them up.
#include <map>
#include <string>

namespace svo::gl {

/// @brief Files by name, consulted before core's shared ones (a layer's embedded shaders; tests compile their own
/// shaders this way).
using ShaderFiles = std::map<std::string, std::string>;

} // namespace svo::gl
