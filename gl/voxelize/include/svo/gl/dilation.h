#pragma once
/// @file dilation.h
/// @brief svo::Dilation: how the raster backend enlarges triangles, and its names.
#include "svo/core/enum_names.h"

namespace svo {

/// @brief How the raster backend enlarges triangles so no touched column is missed.
enum class Dilation {
    Auto,         ///< Hardware where GL_NV_conservative_raster exists, else Shader
    Hardware,     ///< GL_NV_conservative_raster; an error where it is missing
    Shader,       ///< edge offsets in the geometry shader
    CentroidPush, ///< an early vertex-push method; misses voxels; benchmarks only
};

/// @brief The names of Dilation, as the command line and Python write them.
inline constexpr EnumName<Dilation> kDilationNames[] = {{Dilation::Auto, "auto"},
                                                        {Dilation::Hardware, "hardware"},
                                                        {Dilation::Shader, "shader"},
                                                        {Dilation::CentroidPush, "centroid"}};
constexpr const auto& enumNames(Dilation) { return kDilationNames; }

} // namespace svo
