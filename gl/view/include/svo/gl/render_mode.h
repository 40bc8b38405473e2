#pragma once
/// @file render_mode.h
/// @brief What a picture of an octree shows (ViewRequest::render), and its names.
#include "svo/core/enum_names.h"

namespace svo::gl {

/// @brief What a picture shows (svo view --render).
enum class RenderMode {
    Layers,           ///< "debug": the layers as asked (voxels coloured, outlines, bricks, mesh; AO when it has cones)
    AmbientOcclusion, ///< "ao": the surface as its ambient occlusion, grey
    Direct,           ///< "direct": lit, with shadows
    Global,           ///< "gi": lit, and one diffuse bounce
};
inline constexpr EnumName<RenderMode> kRenderModeNames[] = {{RenderMode::Layers, "debug"},
                                                             {RenderMode::AmbientOcclusion, "ao"},
                                                             {RenderMode::Direct, "direct"},
                                                             {RenderMode::Global, "gi"}};
constexpr const auto& enumNames(RenderMode) { return kRenderModeNames; }

/// @brief True for RenderMode::Direct and RenderMode::Global.
inline bool isLit(RenderMode mode) { return mode == RenderMode::Direct || mode == RenderMode::Global; }

} // namespace svo::gl
