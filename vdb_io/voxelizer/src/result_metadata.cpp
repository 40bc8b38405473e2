// The svo:* metadata of a result (svo/result_metadata.h).
#include "svo/result_metadata.h"

#include <fmt/format.h>

namespace svo {

const char* version() { return SVO_VERSION; }

std::map<std::string, std::string> resultMetadata(const TriangleMesh& mesh, const GridSpec& grid,
                                                  const GridRequest& request, bool guardBand)
{
    std::map<std::string, std::string> out = {
        {"svo:source", mesh.source},
        {"svo:triangles", std::to_string(mesh.triangles.size())},
        {"svo:grid", request.voxelSize > 0    ? fmt::format("voxel size {}", grid.voxelSize)
                     : request.resolution > 0 ? fmt::format("resolution {}", request.resolution)
                                              : std::string("transform")},
        {"svo:voxel_size", fmt::format("{}", grid.voxelSize)},
        {"svo:version", SVO_VERSION}};
    if (guardBand) out["svo:epsilon"] = fmt::format("{:.3g}", grid.epsilon());
    return out;
}

} // namespace svo
