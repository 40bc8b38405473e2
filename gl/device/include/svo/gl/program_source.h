#pragma once
/// @file program_source.h
/// @brief svo::gl::ProgramSource: a program's stages with their includes
/// expanded (shader_source.h), which a Program compiles and a cached binary
/// of it is keyed by.
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "svo/gl/shader_files.h"
#include "svo/gl/shader_source.h"

namespace svo::gl {

/// @brief A program's stages with their #include lines expanded: what the
/// driver compiles, and so what a cached binary of it is keyed by.
struct ProgramSource {
    std::string name;                                        ///< "a.vert, a.frag", for messages
    std::vector<std::pair<std::string, ShaderSource>> stages; ///< file name, expanded text
};

/// @brief The expanded stages of a program.
/// @param files the stage files, by name
/// @param extra files looked up before the embedded ones
/// @throw svo::DeviceError for an unknown file, an include cycle, or a file
///        whose extension names no stage
ProgramSource programSource(std::initializer_list<const char*> files, const ShaderFiles& extra = {});

} // namespace svo::gl
