#include "svo/vdb_io/octree_files.h"

#include <chrono>
#include <filesystem>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/core/octree_file.h"
#include "svo/vdb_io/grid_builder.h"
#include "svo/vdb_io/nanovdb_file.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/vdb_io/reader_grids.h"

namespace svo {
namespace fs = std::filesystem;
namespace {

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

std::string extensionOf(const std::string& path) { return fs::path(path).extension().string(); }

} // namespace

OutputFormat outputFormat(const std::string& path)
{
    const std::string ext = extensionOf(path);
    if (ext == ".vdb") return OutputFormat::Vdb;
    if (ext == ".svo") return OutputFormat::Svo;
    if (ext == ".nvdb") return OutputFormat::NanoVdb;
    throw IoError(fmt::format("{}: the output must end in .vdb, .nvdb or .svo", path));
}

void checkOutputPath(const std::string& path)
{
    outputFormat(path);
    checkWritable(path);
}

WriteReport writeOctree(const std::string& path, const Octree& octree, const GridOptions& grids,
                        const std::map<std::string, std::string>& metadata)
{
    WriteReport report;
    report.format = outputFormat(path);
    if (report.format == OutputFormat::Svo) {
        if (grids.fog)
            throw InvalidInput(fmt::format("{}: a .svo file holds the octree only; a fog grid needs .vdb or .nvdb output",
                                           path));
        const auto t0 = Clock::now();
        writeOctreeFile(path, octree);
        report.stages.push_back({"svo write", -1, msSince(t0)});
        report.bytes = outputBytes(path); // the staged temporary while an OutputBatch holds it
        return report;
    }
    if (report.format == OutputFormat::Vdb) {
        vdb::WriteOptions wo;
        static_cast<GridOptions&>(wo) = grids;
        wo.metadata = metadata;
        if (grids.attributes && (octree.channels() & kTriangles)) wo.triangleSidecar = vdb::triangleSidecarPath(path);
        const vdb::WriteStats ws = vdb::writeVdb(path, octree, wo);
        report.sidecar = wo.triangleSidecar;
        report.sidecarBytes = ws.sidecarBytes;
        report.stages.push_back({"vdb build (cpu)", -1, ws.buildMs});
        report.stages.push_back({"vdb write", -1, ws.writeMs});
        report.bytes = ws.bytes;
        report.leaves = ws.leaves;
        return report;
    }
    // NanoVDB grids laid out from the bricks, no OpenVDB tree (nanovdb_grids.h).
    // NanoVDB grids hold no string metadata: @a metadata has nowhere to go.
    checkWritable(path);
    auto t0 = Clock::now();
    const std::vector<vdb::NanoHandle> nano = vdb::octreeToNanoGrids(octree, grids);
    report.stages.push_back({"nvdb build (cpu)", -1, msSince(t0)});
    t0 = Clock::now();
    report.bytes = vdb::writeNanoVdb(path, nano, grids.codec);
    report.stages.push_back({"nvdb write", -1, msSince(t0)});
    report.leaves = octree.bricks.size();
    return report;
}

} // namespace svo
