#pragma once
/// @file backend.h
/// @brief svo::Backend: where voxelization runs, and its names.
#include "svo/core/enum_names.h"

namespace svo {

/// @brief Where voxelization runs.
enum class Backend {
    Auto,    ///< Compute on a GPU, Cpu on a software renderer (llvmpipe) or without GL: the faster there (docs/design.md §6)
    Raster,  ///< GPU: rasterization along each triangle's dominant axis
    Compute, ///< GPU: triangle-parallel compute shaders; the same voxels as Raster
    Cpu,     ///< the double-precision CPU reference (tests; no GL context needed)
};

/// @brief The names of Backend, as the command line and Python write them.
inline constexpr EnumName<Backend> kBackendNames[] = {
    {Backend::Auto, "auto"}, {Backend::Raster, "raster"}, {Backend::Compute, "compute"}, {Backend::Cpu, "cpu"}};
constexpr const auto& enumNames(Backend) { return kBackendNames; }

} // namespace svo
