#pragma once
/// @file option_flags.h
/// @brief The command line's flag for each name the library uses in its
/// errors (svo::Error::argument() and the options a message names) that is
/// not an option declared with forEachOption, so that `svo` prints
/// "--attributes normal ..." where the library writes "svo::kNormals ...".
/// Declared options (LevelSetOptions::exteriorBand -> --exterior-band) take
/// their flags from their declarations (cli_options.h, errorMessage).
#include <string>
#include <string_view>

namespace svo::app {

/// @brief An option's identifier in the library's errors, the flag (and value)
/// that sets it on the command line, and the subcommand whose --help lists it.
struct OptionFlag {
    std::string_view identifier;
    std::string_view flag;
    std::string_view command;
};

/// @brief Every identifier the library names in an error that a flag of `svo` sets.
inline constexpr OptionFlag kOptionFlags[] = {
    // Options declared beside their structs (forEachOption, svo/core/option_info.h) are not
    // here: their flags come from the declarations. These are the other names the library's
    // errors use: values of an option, and the view's settings.
    {"svo::kNormals", "--attributes normal", "voxelize"},
    // The octree view (svo/gl/octree_view.h): its declared options (svo/gl/view_request.h)
    // are not here; these are its errors' other names.
    {"svo::gl::namedView", "--view", "view"},
    {"AmbientOcclusion::volumeResolution", "--light-volume", "view"}, // --light-volume sets both volumes
    {"AmbientOcclusion::Source::Octree", "--ao-source octree", "view"},
    {"svo::kColors", "--attributes color", "view"},
    {"svo::kTriangles", "--attributes triangle", "view"},
};

/// @brief The flag for a library identifier: a declared option's (its
/// forEachOption declaration), else the table's; empty when no flag sets it
/// (an identifier that is a flag or a keyword already, or one the command
/// line never passes), and the message then names it as the library does.
std::string flagFor(std::string_view identifier);

} // namespace svo::app
