#pragma once
/// @file lights.h
/// @brief The lights of a reference: svo's lights (svo/core/lights.h), the
/// same ones the cone-traced view injects, under the reference's names.
#include "svo/core/lights.h"

namespace svo::reference {

/// @brief svo's lights under the reference's names.
using DirectionalLight = svo::DirectionalLight;
using PointLight = svo::PointLight;
using Lighting = svo::Lights;

} // namespace svo::reference
