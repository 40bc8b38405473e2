// Grids every OpenVDB reader opens (svo/vdb_io/reader_grids.h).
#include "svo/vdb_io/reader_grids.h"

#include <filesystem>
#include <openvdb/io/File.h>

namespace svo::vdb {

std::string triangleSidecarPath(const std::string& path)
{
    std::filesystem::path p(path);
    p.replace_extension(".triangle.vdb");
    return p.string();
}

namespace {
/// The key of markTriangleSidecar, read by isTriangleSidecarOf.
constexpr const char* kSidecarOf = "svo:sidecar_of";
} // namespace

void markTriangleSidecar(const openvdb::GridPtrVec& sidecarGrids, const std::string& output)
{
    const std::string name = std::filesystem::path(output).filename().string();
    for (const auto& g : sidecarGrids) g->insertMeta(kSidecarOf, openvdb::StringMetadata(name));
}

bool isTriangleSidecarOf(const std::string& output)
{
    const std::string path = triangleSidecarPath(output);
    std::error_code ec;
    if (!std::filesystem::is_regular_file(std::filesystem::symlink_status(path, ec))) return false;
    try {
        openvdb::initialize();
        openvdb::io::File file(path);
        file.open(/*delayLoad=*/false);
        const openvdb::GridPtrVecPtr grids = file.readAllGridMetadata();
        file.close();
        const std::string name = std::filesystem::path(output).filename().string();
        if (!grids || grids->empty()) return false;
        for (const auto& g : *grids) {
            const auto mark = g->getMetadata<openvdb::StringMetadata>(kSidecarOf);
            if (!g->isType<openvdb::Int32Grid>() || !mark || mark->value() != name) return false;
        }
        return true;
    } catch (const std::exception&) {
        return false; // not a .vdb file, or one OpenVDB cannot read: not svo's sidecar
    }
}

bool pyopenvdbReads(const openvdb::GridBase& grid)
{
    return grid.isType<openvdb::BoolGrid>() || grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::Vec3SGrid>();
}

std::pair<openvdb::GridPtrVec, openvdb::GridPtrVec> splitTriangleGrids(const openvdb::GridPtrVec& grids)
{
    std::pair<openvdb::GridPtrVec, openvdb::GridPtrVec> out;
    for (const auto& g : grids) (g->isType<openvdb::Int32Grid>() ? out.second : out.first).push_back(g);
    return out;
}

openvdb::GridBase::Ptr withTopology(openvdb::MaskGrid::Ptr mask, GridOptions::Topology topology)
{
    if (topology == GridOptions::Topology::Mask) return mask;
    // TopologyCopy keeps every node and tile where it is: active tiles stay
    // tiles (a solid's inside), with true as their value.
    auto tree = std::make_shared<openvdb::BoolTree>(mask->tree(), /*inactive=*/false, /*active=*/true,
                                                    openvdb::TopologyCopy());
    auto out = openvdb::BoolGrid::create(tree);
    out->setTransform(mask->transform().copy());
    for (auto it = mask->beginMeta(); it != mask->endMeta(); ++it) out->insertMeta(it->first, *it->second);
    out->setName(mask->getName());
    out->setGridClass(mask->getGridClass());
    return out;
}

} // namespace svo::vdb
