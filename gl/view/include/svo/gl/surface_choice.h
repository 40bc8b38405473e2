#pragma once
/// @file surface_choice.h
/// @brief The surface a picture asks for (ViewRequest::surface): Surface, or Auto.
#include "svo/core/enum_names.h"

namespace svo::gl {

/// @brief The surface asked for (svo view --surface): Surface, or Auto.
enum class SurfaceChoice { Auto, Voxels, Mesh };
inline constexpr EnumName<SurfaceChoice> kSurfaceChoiceNames[] = {
    {SurfaceChoice::Voxels, "voxels"}, {SurfaceChoice::Mesh, "mesh"}, {SurfaceChoice::Auto, "auto"}};
constexpr const auto& enumNames(SurfaceChoice) { return kSurfaceChoiceNames; }

} // namespace svo::gl
