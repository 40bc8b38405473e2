// A stale triangle-index sidecar, removed (stale_sidecar.h).
#include "stale_sidecar.h"

#include <filesystem>
#include <fmt/format.h>

#include "svo/core/atomic_file.h"
#include "svo/vdb_io/reader_grids.h"

namespace svo::app {

std::string removeStaleSidecar(const std::string& output, const std::vector<std::string>& inputs,
                               const OutputHabits& habits)
{
    if (output.empty() || !vdb::isTriangleSidecarOf(output)) return {};
    const std::string sidecar = vdb::triangleSidecarPath(output);
    for (const auto& in : inputs)
        if (sameFile(sidecar, in)) return {}; // read by this run: never removed
    if (habits.noClobber) {
        printWarnings({fmt::format("{}: left in place (--no-clobber), though it holds the triangle indices of an "
                                   "earlier {}, not of this one",
                                   sidecar, output)});
        return {};
    }
    std::error_code ec;
    if (!std::filesystem::remove(sidecar, ec)) {
        printWarnings({fmt::format("{}: the triangle indices of an earlier {} could not be removed: {}", sidecar,
                                   output, ec ? ec.message() : std::string("it is gone"))});
        return {};
    }
    return sidecar;
}

std::string staleSidecarText(const std::string& removed, const std::string& output)
{
    return fmt::format("{}, the triangle indices of an earlier {}", removed,
                       std::filesystem::path(output).filename().string());
}

std::string staleSidecarNote(const std::string& removed, const std::string& output)
{
    return removed.empty() ? std::string() : "; removed " + staleSidecarText(removed, output);
}

} // namespace svo::app
