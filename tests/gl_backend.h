#pragma once
// The suites about the GL passes name them: Backend::Auto runs on the CPU
// where the GL device is a software renderer (CI's llvmpipe), so a suite left
// on Auto there would test the CPU path against itself.
#include "svo/voxelizer.h"

namespace svo::test {

/// The GL passes: raster runs on every GL 4.5 device, llvmpipe included.
constexpr Backend kGl = Backend::Raster;

/// Options that run a call's GL passes, with @a stats filled when given.
inline VoxelizeOptions onGl(VoxelizeStats* stats = nullptr)
{
    VoxelizeOptions o;
    o.backend = kGl;
    o.stats = stats;
    return o;
}

} // namespace svo::test
