#include "svo/vdb_io/vdb_file.h"

#include <chrono>
#include <filesystem>
#include <memory>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/vdb_io/grid_builder.h"

namespace svo::vdb {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// Opens a .vdb for reading, turning OpenVDB's exceptions into svo::Error.
std::unique_ptr<openvdb::io::File> openVdb(const std::string& path)
{
    openvdb::initialize();
    std::error_code ec;
    if (!fs::exists(path, ec)) throw Error(fmt::format("{}: no such file", path));
    if (fs::is_directory(path, ec)) throw Error(fmt::format("{}: is a folder, not a .vdb file", path));
    if (fs::file_size(path, ec) == 0) throw Error(fmt::format("{}: the file is empty", path));
    auto file = std::make_unique<openvdb::io::File>(path); // File cannot be moved
    try {
        file->open(false); // no delayed loading: the file is read whole
    } catch (const std::exception& e) {
        throw Error(fmt::format("{}: not a readable VDB file: {}", path, e.what()));
    }
    return file;
}

void writeGrids(const std::string& path, const openvdb::GridPtrVec& grids)
{
    writeAtomically(path, [&](const std::string& tmp) {
        try {
            openvdb::io::File file(tmp);
            file.write(grids);
            file.close();
        } catch (const std::exception& e) {
            throw Error(fmt::format("{}: cannot write the VDB file: {}", path, e.what()));
        }
    });
}

} // namespace

WriteStats writeVdb(const std::string& path, const Octree& octree, const WriteOptions& options)
{
    checkWritable(path);
    openvdb::initialize();
    WriteStats stats;
    auto t0 = Clock::now();
    openvdb::GridPtrVec grids = octreeToGrids(octree, options);
    stats.leaves = octree.bricks.size(); // one leaf per occupied brick
    for (auto& g : grids)
        for (const auto& [k, v] : options.metadata) g->insertMeta(k, openvdb::StringMetadata(v));
    stats.buildMs = msSince(t0);

    t0 = Clock::now();
    writeGrids(path, grids);
    std::error_code ec;
    stats.bytes = fs::file_size(path, ec);
    stats.writeMs = msSince(t0);
    return stats;
}

void writeVdbMasks(const std::string& path, const std::vector<std::pair<std::string, Octree>>& named,
                   const std::map<std::string, std::string>& metadata)
{
    checkWritable(path);
    openvdb::initialize();
    openvdb::GridPtrVec grids;
    for (const auto& [name, octree] : named) {
        auto g = buildMaskGrid(octree);
        g->setName(name);
        for (const auto& [k, v] : metadata) g->insertMeta(k, openvdb::StringMetadata(v));
        grids.push_back(g);
    }
    writeGrids(path, grids);
}

VdbBricks readVdbBricks(const std::string& path, const std::string& gridName)
{
    auto file = openVdb(path);
    openvdb::GridBase::Ptr grid;
    try {
        auto names = file->beginName();
        if (!(names != file->endName())) throw Error(fmt::format("{}: the file holds no grids", path));
        const std::string name = gridName.empty() ? names.gridName() : gridName;
        if (!file->hasGrid(name)) throw Error(fmt::format("{}: no grid named '{}'", path, name));
        grid = file->readGrid(name);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(fmt::format("{}: cannot read the grid: {}", path, e.what()));
    }
    GridBricks gb = gridToBricks(*grid, path);
    VdbBricks out;
    out.gridName = grid->getName();
    out.gridType = grid->type();
    out.grid = gb.grid;
    out.bricks = std::move(gb.bricks);
    out.tilesExpanded = gb.tilesExpanded;
    return out;
}

} // namespace svo::vdb
