#pragma once
/// @file city_scene.h
/// @brief A procedural city of any size, from a thousand to a billion
/// triangles, the same on every platform for a seed: the large test scene of
/// tiled and distributed voxelization.
///
/// @details The city is a square grid of blocks 120 m apart (one unit is one
/// metre, y is up). Each block has two road strips (open, flat), a curb
/// around it (a closed slab 0.15 m high), street trees, and lots holding
/// towers and low buildings (closed boxes whose facades have recessed
/// windows), courtyard buildings (closed rings whose walls are 0.2-0.6 m
/// thick), plain boxes, and parks (trees inside garden walls that are closed
/// slabs 0.25 m thick). A tree is an open hexagonal trunk and a crown that is
/// an 80-face sphere-like soup with four faces missing, each face on vertices
/// of its own, pierced by the trunk. Closed and open parts are mixed on
/// purpose: a level set's sign treats open meshes differently.
///
/// Thin parts are thin at the resolutions such a city is voxelized at: at
/// 10^7 triangles the city is about 1.8 km wide, so 8192 voxels across make
/// 0.22 m voxels, and the walls are one to three voxels thick.
///
/// Blocks are added on square shells (the first n*n fill an n x n square),
/// so a larger city is a smaller one with blocks added on two sides: the
/// same seed gives the same first blocks at every size. When the next block
/// does not fit in the target, the parts of it that fit are taken in order,
/// and of as many more blocks as it takes to come within 1% under the
/// target.
#include <cstdint>
#include <string>

#include "svo/core/mesh.h"
#include "svo/core/option_info.h"

namespace svo {

/// @brief What cityScene builds.
struct CityOptions {
    uint64_t triangles = 100'000; ///< the target count (checkCityTriangles)
    uint64_t seed = 1;            ///< any number; each gives another city
};

/// @brief The rule of CityOptions::triangles: a whole number from 1,000 to
/// 1,000,000,000 (above it the vertices would outgrow 32-bit indices).
/// @param name the value's name for the caller (a flag, a keyword, a field)
/// @throw svo::InvalidInput "<name> must be ..., got <value>" (argument() @a name)
void checkCityTriangles(int64_t triangles, const std::string& name);

/// @brief The rule of CityOptions::seed: every value is a seed. Throws nothing.
void checkCitySeed(int64_t seed, const std::string& name);

/// @brief Each option of CityOptions, declared once for every front end
/// (svo/core/option_info.h).
template <typename Visit>
void forEachOption(CityOptions& o, Visit&& visit)
{
    visit(OptionInfo{"CityOptions::triangles", "triangles",
                     "Triangles the city scene aims at, 1,000 to 1,000,000,000: it ends within 1% below"},
          CheckedInteger<uint64_t>{o.triangles, checkCityTriangles});
    visit(OptionInfo{"CityOptions::seed", "seed",
                     "The city scene's seed: the same seed and count give the same mesh on every platform"},
          CheckedInteger<uint64_t>{o.seed, checkCitySeed});
}

/// @brief Generates the city described in this file's details, on all
/// cores; the result does not depend on the number of threads.
///
/// @param options the target triangle count and the seed
/// @return a mesh of at most @a options.triangles and at least 99% of them
///         from 5,000 up (below, it may end a few dozen short), with no
///         degenerate triangle and no colours; source "city (seed S, N
///         triangles)" names the target N. Memory is the mesh's own (about
///         28 bytes a triangle) and a plan of a few hundredths of that; time
///         is linear in the count.
/// @throw svo::InvalidInput for a target outside checkCityTriangles' range
/// @throw std::bad_alloc when the mesh does not fit in memory
TriangleMesh cityScene(const CityOptions& options);

} // namespace svo
