// The rules of the field options' numbers (svo/core/field_options.h).
#include "svo/core/field_options.h"

#include <cmath>
#include <fmt/format.h>

#include "svo/core/error.h"

namespace svo {

void checkBand(double voxels, const std::string& name)
{
    if (!(voxels >= 1.0 && voxels <= 1000.0)) // NaN fails too
        throw InvalidInput(name, fmt::format("{}: a band is a number of voxels from 1 to 1000", voxels));
}

void checkWindingAccuracy(double accuracy, const std::string& name)
{
    if (!(accuracy > 0) || !std::isfinite(accuracy))
        throw InvalidInput(name, fmt::format("{}: the winding accuracy is a positive finite number (default 1.5; larger "
                                             "is slower and more exact, 1e300 evaluates every triangle)",
                                             accuracy));
}

void checkLevelSetOptions(const LevelSetOptions& ls)
{
    checkBand(ls.exteriorBand, "LevelSetOptions::exteriorBand");
    if (!ls.unsignedDistance) checkBand(ls.interiorBand, "LevelSetOptions::interiorBand");
    checkWindingAccuracy(ls.sign.windingAccuracy, "SignOptions::windingAccuracy");
}

} // namespace svo
