// The command line's flag for a library identifier (option_flags.h).
#include "option_flags.h"

#include "svo/core/city_scene.h"
#include "svo/core/field_options.h"
#include "svo/gl/device_options.h"
#include "svo/gl/view_request.h"
#include "svo/gl/voxelize_settings.h"
#include "svo/vdb_io/grid_options.h"

namespace svo::app {

std::string flagFor(std::string_view identifier)
{
    std::string flag;
    const auto find = [&](const OptionInfo& info, auto&&) {
        if (info.identifier == identifier) flag = flagOf(info);
    };
    VoxelizeSettings voxelize;
    DeviceOptions device;
    LevelSetOptions levelSet;
    GridOptions grids;
    gl::ViewRequest view; // its layers, AO and lighting too
    GridRequest request;
    CityOptions city;
    forEachOption(request, find);
    forEachOption(city, find);
    forEachOption(voxelize, find);
    forEachOption(device, find);
    forEachOption(levelSet, find);
    forEachOption(grids, find);
    forEachOption(view, find);
    if (!flag.empty()) return flag;
    for (const OptionFlag& o : kOptionFlags)
        if (o.identifier == identifier) return std::string(o.flag);
    return {};
}

} // namespace svo::app
