#pragma once
/// @file field_options.h
/// @brief What a level set, unsigned distance field or solid is asked for:
/// plain values shared by the GPU (svo/gl/field_pipeline.h) and CPU paths,
/// with the rules their numbers follow.
#include <string>

#include "svo/core/enum_names.h"
#include "svo/core/option_info.h"

namespace svo {

/// How level sets and solids tell inside from outside.
enum class SignMethod {
    /// Parity when the mesh is closed and consistently oriented (after welding
    /// vertices at equal positions), the winding number otherwise; the
    /// statistics say which and why.
    Auto,
    /// Crossings counted along voxel columns, with exact tie rules: a voxel
    /// centre on a face, edge or vertex never flips the result. Correct for
    /// closed meshes, including nested shells; used as asked on others.
    Parity,
    /// The generalized winding number (svo/core/winding_tree.h) thresholded at
    /// 1/2: sensible insides for holes, soups and overlapping parts. At every
    /// voxel of the band, and of any brick beyond it whose centre's winding
    /// number is within 1/4 of 1/2; other bricks beyond the band take the
    /// side of their centre.
    Winding,
};

/// The names of SignMethod, as the command line and Python write them.
inline constexpr EnumName<SignMethod> kSignMethodNames[] = {
    {SignMethod::Auto, "auto"}, {SignMethod::Parity, "parity"}, {SignMethod::Winding, "winding"}};
constexpr const auto& enumNames(SignMethod) { return kSignMethodNames; }

/// The sign method and its accuracy.
struct SignOptions {
    SignMethod method = SignMethod::Auto;
    /// Winding numbers: tree nodes farther than this many times their radius
    /// add their far field, expanded to second order, instead of their
    /// triangles (Barill et al. 2018's beta; larger is slower and more exact;
    /// positive and finite, checkWindingAccuracy: 1e300 evaluates every triangle).
    double windingAccuracy = 1.5;
    /// The mesh is the part of a closed mesh that a region's z columns meet,
    /// top to bottom (every triangle whose box, grown by the band and 2
    /// voxels, meets the region's columns in x and y; svo.distributed cuts
    /// meshes so): parity signs without the closedness check, which the part,
    /// cut at its sides, would fail. The caller vouches for the whole mesh;
    /// with a region, the result is the whole mesh's in that region.
    bool partOfClosedMesh = false;
    SignOptions(SignMethod m = SignMethod::Auto, double accuracy = 1.5) : method(m), windingAccuracy(accuracy) {}
};

/// What a level set (or unsigned distance field) holds.
struct LevelSetOptions {
    double exteriorBand = 3.0;     ///< active band outside the surface, in voxels (>= 1)
    double interiorBand = 3.0;     ///< active band inside, in voxels (>= 1); unused when unsigned
    bool unsignedDistance = false; ///< distances without sign: no inside/outside needed
    bool closestTriangle = false;  ///< also an Int32Grid "closest_triangle" on the band
    SignOptions sign;
};

/// @brief Each option of SignOptions and LevelSetOptions, declared once for
/// every front end (svo/core/option_info.h).
template <typename Visit>
void forEachOption(SignOptions& o, Visit&& visit);
template <typename Visit>
void forEachOption(LevelSetOptions& o, Visit&& visit);

/// @name The rules of the options' numbers
/// One rule per number, for every front door: the library checks its options
/// with them (naming the field, e.g. LevelSetOptions::exteriorBand), and the
/// command line and the Python module check what they are given with the same
/// functions, naming their own flag or keyword (`name`). Each throws
/// svo::InvalidInput with one line, "<name> <value>: <the rule>", whose
/// argument() is `name` and detail() "<value>: <the rule>". NaN never passes.
/// @{
/// A band half width: a number of voxels from 1 to 1000.
void checkBand(double voxels, const std::string& name);
/// SignOptions::windingAccuracy: a positive finite number (1e300 evaluates every triangle).
void checkWindingAccuracy(double accuracy, const std::string& name);
/// Both bands (the interior one only for signed fields) and the winding accuracy.
void checkLevelSetOptions(const LevelSetOptions& options);
/// @}

template <typename Visit>
void forEachOption(SignOptions& o, Visit&& visit)
{
    visit(OptionInfo{"SignOptions::method", "sign",
                     "Inside/outside: auto (parity for closed, consistently oriented meshes, the winding number "
                     "otherwise), parity or winding (as asked)"},
          o.method);
    visit(OptionInfo{"SignOptions::windingAccuracy", "winding_accuracy",
                     "Winding numbers: tree nodes farther than this many radii use their far-field expansion (a "
                     "positive finite number; larger is slower and more exact; 1e300 evaluates every triangle)"},
          CheckedNumber{o.windingAccuracy, checkWindingAccuracy});
    visit(OptionInfo{"SignOptions::partOfClosedMesh", "part_of_closed_mesh",
                     "The mesh is the part of a closed mesh that the region's z columns meet, top to bottom (grown "
                     "by the band and 2 voxels): parity signs without the closedness check the part would fail"},
          o.partOfClosedMesh);
}

template <typename Visit>
void forEachOption(LevelSetOptions& o, Visit&& visit)
{
    visit(OptionInfo{"LevelSetOptions::exteriorBand", "exterior_band",
                     "Band width outside the surface, in voxels, 1 to 1000"},
          CheckedNumber{o.exteriorBand, checkBand});
    visit(OptionInfo{"LevelSetOptions::interiorBand", "interior_band",
                     "Band width inside the surface, in voxels, 1 to 1000"},
          CheckedNumber{o.interiorBand, checkBand});
    visit(OptionInfo{"LevelSetOptions::unsignedDistance", "unsigned",
                     "Unsigned distances: no inside or outside needed (open meshes, soups)", "--udf"},
          o.unsignedDistance);
    visit(OptionInfo{"LevelSetOptions::closestTriangle", "closest_triangle",
                     "Also the index of each band voxel's closest triangle (an Int32Grid 'closest_triangle')"},
          o.closestTriangle);
    forEachOption(o.sign, visit);
}

} // namespace svo
