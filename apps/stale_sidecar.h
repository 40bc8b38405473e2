#pragma once
/// @file stale_sidecar.h
/// The triangle-index sidecar an earlier run left beside a .vdb output
/// (svo/vdb_io/reader_grids.h): a run that writes the output without one
/// removes it, since it no longer matches the output.
#include <string>
#include <vector>

#include "cli_options.h"

namespace svo::app {

/// @brief After a run wrote the .vdb @a output and no sidecar beside it:
/// removes vdb::triangleSidecarPath(@a output) when it is the sidecar svo
/// wrote for an earlier @a output (vdb::isTriangleSidecarOf), which no longer
/// matches it. Never an input; never with --no-clobber, where a warning says
/// that it was left. A failure to remove it is a warning: the run did what it
/// was asked.
/// @param inputs the run's inputs (empty paths skipped)
/// @return the path removed, empty when none was
std::string removeStaleSidecar(const std::string& output, const std::vector<std::string>& inputs,
                               const OutputHabits& habits);

/// @brief A removed sidecar in words: "X, the triangle indices of an earlier
/// out.vdb" (the -v report's line).
std::string staleSidecarText(const std::string& removed, const std::string& output);
/// @brief The summary line's end for a removed sidecar: "; removed " and
/// staleSidecarText; empty when @a removed is.
std::string staleSidecarNote(const std::string& removed, const std::string& output);

} // namespace svo::app
