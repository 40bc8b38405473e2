#pragma once
/// @file option_flags.h
/// @brief The command line's flag for each option the library names in its
/// errors (svo::Error::argument() and the options a message names), so that
/// `svo` prints "--exterior-band 0.5: ..." where the library writes
/// "LevelSetOptions::exteriorBand 0.5: ...". The one table of them.
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
    // The options' rules (svo/voxelizer.h), where the library checks a field the command line set.
    {"LevelSetOptions::exteriorBand", "--exterior-band", "voxelize"},
    {"LevelSetOptions::interiorBand", "--interior-band", "voxelize"},
    {"SignOptions::windingAccuracy", "--winding-accuracy", "voxelize"},
    {"VoxelizeOptions::mode", "--mode", "voxelize"},
    {"svo::kNormals", "--attributes normal", "voxelize"},
    // The octree view (svo/gl/octree_view.h).
    {"svo::gl::namedView", "--view", "view"},
    {"AmbientOcclusion::volumeResolution", "--light-volume", "view"},
    {"AmbientOcclusion::Source::Octree", "--ao-source octree", "view"},
    // The view request (svo/gl/view_request.h).
    {"ViewRequest::render", "--render", "view"},
    {"ViewRequest::surface", "--surface", "view"},
    {"ViewLayers::voxelColor", "--color", "view"},
    {"svo::kColors", "--attributes color", "view"},
    {"svo::kTriangles", "--attributes triangle", "view"},
};

/// @brief The flag for a library identifier; empty when no flag sets it (an
/// identifier that is a flag or a keyword already, or one the command line
/// never passes), and the message then names it as the library does.
inline std::string_view flagFor(std::string_view identifier)
{
    for (const OptionFlag& o : kOptionFlags)
        if (o.identifier == identifier) return o.flag;
    return {};
}

} // namespace svo::app
