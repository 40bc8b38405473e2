#include "svo/vdb_io/nanovdb_output.h"

#include <filesystem>
#include <fmt/format.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <vector>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"

namespace svo::vdb {

nanovdb::GridHandle<nanovdb::HostBuffer> toNanoVdb(const openvdb::GridBase::Ptr& grid)
{
    if (!grid) throw Error("no grid to convert to NanoVDB");
    try {
        return nanovdb::openToNanoVDB(grid);
    } catch (const std::exception& e) {
        throw Error(fmt::format("grid '{}' ({}) cannot become a NanoVDB grid: {}", grid->getName(), grid->type(),
                                e.what()));
    }
}

uint64_t writeNanoVdb(const std::string& path, const openvdb::GridPtrVec& grids)
{
    checkWritable(path);
    std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> handles;
    for (const auto& g : grids) handles.push_back(toNanoVdb(g));
    writeAtomically(path, [&](const std::string& tmp) {
        try {
            nanovdb::io::writeGrids<nanovdb::HostBuffer, std::vector>(tmp, handles);
        } catch (const std::exception& e) {
            throw Error(fmt::format("{}: cannot write the NanoVDB file: {}", path, e.what()));
        }
    });
    return outputBytes(path); // the staged temporary while an OutputBatch holds it
}

} // namespace svo::vdb
