#include "svo/vdb_io/nanovdb_output.h"
#include "svo/vdb_io/nanovdb_file.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <nanovdb/util/IO.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <vector>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"

namespace svo::vdb {

nanovdb::GridHandle<nanovdb::HostBuffer> toNanoVdb(const openvdb::GridBase::Ptr& grid)
{
    if (!grid) throw InvalidInput("no grid to convert to NanoVDB");
    try {
        // A full checksum (every node, not only the header and root) lets
        // svo's reader (nanovdb_input.h) find a changed value.
        return nanovdb::openToNanoVDB(grid, nanovdb::StatsMode::Default, nanovdb::ChecksumMode::Full);
    } catch (const std::exception& e) {
        throw Unsupported(fmt::format("grid '{}' ({}) cannot become a NanoVDB grid: {}", grid->getName(), grid->type(),
                                      e.what()));
    }
}

uint64_t writeNanoVdb(const std::string& path, const openvdb::GridPtrVec& grids, NanoCodec codec)
{
    checkWritable(path);
    std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>> handles;
    for (const auto& g : grids) handles.push_back(toNanoVdb(g));
    return writeNanoVdb(path, handles, codec);
}

bool nanoCodecAvailable(NanoCodec codec)
{
    switch (codec) {
    case NanoCodec::None: return true;
#ifdef NANOVDB_USE_ZIP
    case NanoCodec::Zip: return true;
#endif
#ifdef NANOVDB_USE_BLOSC
    case NanoCodec::Blosc: return true;
#endif
    default: return false;
    }
}

uint64_t writeNanoVdb(const std::string& path, const std::vector<nanovdb::GridHandle<nanovdb::HostBuffer>>& handles,
                      NanoCodec codec)
{
    if (!nanoCodecAvailable(codec))
        throw Unsupported(fmt::format("{}: this build of svo has no {} codec for NanoVDB", path,
                                      codec == NanoCodec::Zip ? "Zip" : "Blosc"));
    const nanovdb::io::Codec nanoCodec = codec == NanoCodec::Zip     ? nanovdb::io::Codec::ZIP
                                         : codec == NanoCodec::Blosc ? nanovdb::io::Codec::BLOSC
                                                                     : nanovdb::io::Codec::NONE;
    checkWritable(path);
    writeAtomically(path, [&](const std::string& tmp) {
        // NanoVDB's writeGrids(fileName) leaves its last bytes to the stream's
        // destructor, unchecked: svo opens, flushes and closes the stream and
        // checks each step, so a full disk is an error naming its cause.
        std::ofstream os(tmp, std::ios::out | std::ios::binary | std::ios::trunc);
        if (!os) throw IoError(fmt::format("{}: cannot create the file: {}", path, std::strerror(errno)));
        errno = 0;
        try {
            nanovdb::io::writeGrids<nanovdb::HostBuffer, std::vector>(os, handles, nanoCodec);
        } catch (const std::exception& e) {
            if (os) throw IoError(fmt::format("{}: cannot write the NanoVDB file: {}", path, e.what()));
        }
        int err = errno;
        if (os) {
            os.flush();
            err = errno;
        }
        if (os) {
            os.close();
            err = errno;
        }
        if (!os) throw IoError(fmt::format("{}: {}", path, err ? std::strerror(err) : "the write failed"));
    });
    return outputBytes(path); // the staged temporary while an OutputBatch holds it
}

} // namespace svo::vdb
