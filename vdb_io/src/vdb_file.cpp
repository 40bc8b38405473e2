#include "svo/vdb_io/vdb_file.h"

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <random>
#include <unistd.h>

#include "svo/core/error.h"
#include "svo/vdb_io/grid_builder.h"

namespace svo::vdb {
namespace fs = std::filesystem;

void checkWritable(const std::string& path)
{
    if (path.empty()) throw Error("the output path is empty");
    const fs::path p(path);
    std::error_code ec;
    if (fs::is_directory(p, ec)) throw Error(fmt::format("{}: is a folder; give a file name", path));
    const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
    if (!fs::is_directory(dir, ec)) throw Error(fmt::format("{}: the folder {} does not exist", path, dir.string()));
    if (::access(dir.c_str(), W_OK) != 0)
        throw Error(fmt::format("{}: the folder {} is not writable", path, dir.string()));
}

WriteStats writeVdb(const std::string& path, const Voxelization& voxels, const WriteOptions& options)
{
    using Clock = std::chrono::steady_clock;
    checkWritable(path);
    openvdb::initialize();
    WriteStats stats;
    auto t0 = Clock::now();
    openvdb::GridPtrVec grids;
    auto mask = buildMaskGrid(voxels);
    mask->setName(options.gridName);
    grids.push_back(mask);
    stats.leaves = mask->tree().leafCount();
    if (options.fog) {
        auto fog = buildFogGrid(voxels);
        fog->setName("density");
        grids.push_back(fog);
    }
    for (auto& g : grids)
        for (const auto& [k, v] : options.metadata) g->insertMeta(k, openvdb::StringMetadata(v));
    stats.buildMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();

    t0 = Clock::now();
    std::random_device rd;
    const std::string tmp = fmt::format("{}.tmp-{:08x}", path, rd());
    try {
        openvdb::io::File file(tmp);
        file.write(grids);
        file.close();
    } catch (const std::exception& e) {
        std::remove(tmp.c_str());
        throw Error(fmt::format("{}: cannot write the VDB file: {}", path, e.what()));
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        std::remove(tmp.c_str());
        throw Error(fmt::format("{}: cannot move the finished file into place: {}", path, ec.message()));
    }
    stats.bytes = fs::file_size(path, ec);
    stats.writeMs = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
    return stats;
}

} // namespace svo::vdb
