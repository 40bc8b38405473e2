// Writing a grid's leaf buffers on every core. OpenVDB's writer compresses
// the leaves of a grid one after another on one thread (Grid::writeBuffers);
// at 2048³ that is the longest stage of a level set. The bytes a leaf writes
// depend only on the leaf and on two stream settings (the grid's data
// compression and background), so the leaves can be written into buffers in
// parallel and the buffers appended in leaf order: the file is the same, byte
// for byte, as OpenVDB's own.
#pragma once

#include <openvdb/Grid.h>

namespace svo::vdb {

/// A grid that shares `grid`'s tree, transform and metadata and writes its
/// leaf buffers in parallel, for openvdb::io::File::write; grids of types
/// outside openvdb::GridTypes, or with multi-pass I/O, come back as they are.
openvdb::GridBase::Ptr withParallelBuffers(const openvdb::GridBase::Ptr& grid);

} // namespace svo::vdb
