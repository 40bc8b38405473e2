// The svo:* metadata of a result (svo/result_metadata.h).
#include "svo/result_metadata.h"

#include <fmt/format.h>

namespace svo {

const char* version() { return SVO_VERSION; }

std::map<std::string, std::string> sourceMetadata(const std::string& source)
{
    return {{"svo:source", source}, {"svo:version", SVO_VERSION}};
}

std::map<std::string, std::string> resultMetadata(const TriangleMesh& mesh, const GridSpec& grid,
                                                  const GridRequest& request, bool guardBand)
{
    std::map<std::string, std::string> out = sourceMetadata(mesh.source);
    out["svo:triangles"] = std::to_string(mesh.triangles.size());
    out["svo:grid"] = request.voxelSize > 0    ? fmt::format("voxel size {}", grid.voxelSize)
                      : request.resolution > 0 ? fmt::format("resolution {}", request.resolution)
                                               : std::string("transform");
    out["svo:voxel_size"] = fmt::format("{}", grid.voxelSize);
    if (guardBand) out["svo:epsilon"] = fmt::format("{:.3g}", grid.epsilon());
    return out;
}

} // namespace svo
