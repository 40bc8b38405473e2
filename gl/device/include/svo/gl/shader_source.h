#pragma once
/// @file shader_source.h
/// @brief svo::gl::ShaderSource: one shader stage's text, from embedded files
/// (shader_files.h) with `#include "name"` lines expanded, and compiler logs
/// mapped back to those files.
#include <cstdint>
#include <string>
#include <vector>

#include "svo/gl/shader_files.h"

namespace svo::gl {

/// @brief One stage's text, ready for glShaderSource, and where each of its
/// lines comes from.
///
/// Each included file's text is preceded, and the including file's text
/// resumed, by a `#line` directive that sets the source-string number to the
/// file's index in `files` (0: the stage itself; GLSL takes integers only).
/// The directives keep the line numbers those of the expanded text, though:
/// Mesa reports most errors (all but syntax errors) as source string 0, so
/// only the line number can be trusted, and `lines` maps it back.
struct ShaderSource {
    /// @brief Where one line of the expanded text comes from.
    struct Origin {
        uint32_t file; ///< index into files
        uint32_t line; ///< 1-based, in that file
    };
    std::string text;                ///< the expanded text
    std::vector<std::string> files;  ///< the stage's file first, then each file it includes
    std::vector<Origin> lines; ///< lines[k - 1]: where line k of text comes from
};

/// @brief The text of file @a name with its `#include "name"` lines (first
/// thing on the line) replaced, recursively, by the named files' text.
/// #line needs #version before it, so a stage's includes must come after its
/// #version.
/// @param extra files looked up before the embedded ones
/// @throw svo::DeviceError for an unknown name or an include cycle
ShaderSource shaderSource(const std::string& name, const ShaderFiles& extra = {});

/// @brief A compiler log with its locations named by file.
/// @return @a log with each location at the start of a line in a known format
///         (Mesa `0:12(3):`, NVIDIA `0(12) :`, `ERROR: 0:12:`) rewritten as
///         file and line of @a source, e.g. `overlap.glsl:7(3):`
std::string nameFilesInLog(const std::string& log, const ShaderSource& source);

} // namespace svo::gl
