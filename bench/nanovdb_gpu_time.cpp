// A level set's NanoVDB grid laid out on the host (svo::vdb::buildNanoGrid,
// with and without its checksum) against the GPU builder
// (svo::gl::buildNanoGridGpu) from the same leaves: from host arrays with a
// host copy back (what a file write needs), and from device-resident leaves
// with the grid left on the device (the build alone), and the signed flood
// fill a parity level set takes (vdb::signedFloodFill on the host layout;
// NanoGridHeader::signedFloodFill in the GPU build). Then a surface's
// topology and fog grids as svo::Voxelizer::voxelizeNanoVdb makes them on a
// GL backend (masks uploaded, built with their checksums, read back)
// against the CPU layout (octreeToNanoGrids) of the same octree. Last, an
// unsigned field (band 3) as Voxelizer::levelSetNanoVdb makes it: before
// (the band read back, levelSetNanoGrids with its checksum) and now on a GL
// backend (gl::unsignedFieldLeaves, the GPU builder with the checksum, the
// grid read back): the field passes included, so the difference is the gain.
//   svo-bench-nanovdb-gpu MESH|icosphere [--res 128 256] [--runs 5] [--backend cpu|gpu]
// Prints one Markdown row per resolution: medians in ms.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "svo/core/default_scene.h"
#include "svo/core/error.h"
#include "svo/core/mesh_io.h"
#include "svo/gl/buffer.h"
#include "svo/gl/device.h"
#include "svo/gl/field_pipeline.h"
#include "svo/gl/nano_grid_builder.h"
#include "svo/gl/voxelize_pipeline.h"
#include "svo/vdb_io/nanovdb_grids.h"
#include "svo/vdb_io/nanovdb_layout.h"

namespace {

using Clock = std::chrono::steady_clock;

template <typename F>
double medianMs(int runs, F&& f)
{
    std::vector<double> ms;
    f(); // warm-up: programs compiled, scratch buffers grown
    for (int r = 0; r < runs; ++r) {
        const auto t0 = Clock::now();
        f();
        ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
}

/// A float grid's leaves as the CPU builder takes them.
svo::vdb::SparseVoxels<float> leavesOf(const nanovdb::NanoGrid<float>& grid)
{
    svo::vdb::SparseVoxels<float> s;
    s.background = grid.tree().background();
    const auto& tree = grid.tree();
    const auto* leaf = tree.getFirstNode<0>();
    for (uint32_t i = 0; i < tree.nodeCount(0); ++i, ++leaf) {
        const auto o = leaf->origin();
        s.origins.push_back({o[0], o[1], o[2]});
        svo::Brick b;
        for (uint32_t w = 0; w < 8; ++w) b.words[w] = leaf->valueMask().getWord<uint64_t>(w);
        s.masks.push_back(b);
        for (uint32_t v = 0; v < 512; ++v) s.values.push_back(leaf->getValue(v));
    }
    return s;
}

/// The GPU path of voxelizeNanoVdb for the topology (ValueMask) and fog of
/// an octree: the leaves gathered and uploaded, both grids built with their
/// checksums and read back. Returns the bytes of both.
uint64_t surfaceOnGpu(const svo::gl::Context& context, const svo::Octree& o)
{
    using namespace svo;
    const OctreeLeaves bricks = octreeLeaves(o);
    gl::NanoLeaves leaves;
    leaves.count = uint32_t(bricks.origins.size());
    leaves.origins = bricks.origins.data();
    leaves.masks = bricks.masks.data();
    gl::NanoGridHeader header;
    header.name = "surface";
    header.gridClass = uint32_t(nanovdb::GridClass::Topology);
    header.voxelSize = o.grid.voxelSize;
    header.checksum = true; // on the GPU, as the front door asks
    uint64_t bytes = 0;
    auto build = [&](gl::NanoKind kind) {
        const gl::NanoGridBuffer g = gl::buildNanoGridGpu(context, kind, leaves, header);
        nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(g.bytes);
        g.grid.readBulk(0, g.bytes, buffer.data());
        bytes += g.bytes;
    };
    build(gl::NanoKind::Mask);
    leaves.activeWord = 0x3F800000u; // 1.0f
    header.name = "density";
    header.gridClass = uint32_t(nanovdb::GridClass::FogVolume);
    build(gl::NanoKind::Float);
    return bytes;
}

} // namespace

int run(int argc, char** argv)
{
    using namespace svo;
    std::string mesh = "icosphere";
    std::vector<int64_t> res;
    int runs = 5;
    Backend backend = Backend::Cpu;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (a == "--res") {
            while (i + 1 < argc && argv[i + 1][0] != '-') res.push_back(std::atoll(argv[++i]));
        } else if (a == "--runs" && i + 1 < argc) {
            runs = std::atoi(argv[++i]);
        } else if (a == "--backend" && i + 1 < argc) {
            backend = std::string(argv[++i]) == "gpu" ? Backend::Compute : Backend::Cpu;
        } else if (a == "-h" || a == "--help") {
            fmt::print("usage: svo-bench-nanovdb-gpu MESH|icosphere [--res 128 256] [--runs 5] [--backend cpu|gpu]\n");
            return 0;
        } else if (a[0] == '-') {
            throw svo::InvalidInput(fmt::format("unknown option {} (see --help)", a));
        } else {
            mesh = a;
        }
    }
    if (res.empty()) res = {128, 256};
    const TriangleMesh m = mesh == "icosphere" ? icosphere({0, 0, 0}, 1.0, 6) : loadMesh(mesh);
    gl::Device device;
    const gl::Context::Scope scope(device.context()); // the grids' buffers are freed in it
    fmt::print("renderer: {}\n\n", device.context().info().renderer);
    fmt::print("| mesh | N | leaves | MB | CPU layout ms | CPU layout + checksum ms | CPU flood fill ms | GPU from host + "
               "copy back ms | GPU on device ms | GPU on device + checksum ms | GPU on device + flood fill ms |\n"
               "|---|---|---|---|---|---|---|---|---|---|---|\n");
    for (const int64_t n : res) {
        const GridSpec grid = makeGrid(m, {n, 0.0});
        VoxelizeSettings s;
        s.backend = backend;
        VoxelizeStats stats;
        LevelSetOptions ls;
        const DistanceBricks f = gl::levelSetBricks(device, m, grid, ls, s, Checkpoint{}, stats);
        const auto grids = vdb::levelSetNanoGrids(f, ls.exteriorBand, ls.interiorBand, grid, false);
        const auto* sdf = grids.front().grid<float>();
        const vdb::SparseVoxels<float> in = leavesOf(*sdf);
        vdb::NanoGridInfo info;
        info.name = sdf->gridName();
        info.gridClass = sdf->gridClass();
        info.voxelSize = sdf->voxelSize()[0];
        gl::NanoGridHeader header;
        header.name = info.name;
        header.gridClass = uint32_t(info.gridClass);
        header.voxelSize = info.voxelSize;
        header.background = in.background;
        const double cpuBare = medianMs(runs, [&] {
            info.checksum = false;
            vdb::buildNanoGrid<float>(in, info);
        });
        const double cpuSum = medianMs(runs, [&] {
            info.checksum = true;
            vdb::buildNanoGrid<float>(in, info);
        });
        info.checksum = false;
        auto layout = vdb::buildNanoGrid<float>(in, info);
        const double cpuFlood = medianMs(runs, [&] { vdb::signedFloodFill(*layout.grid<float>()); });
        gl::NanoLeaves host;
        host.count = uint32_t(in.origins.size());
        host.origins = in.origins.data();
        host.masks = in.masks.data();
        std::vector<uint32_t> words(in.values.size());
        std::memcpy(words.data(), in.values.data(), 4 * words.size());
        host.values = words.data();
        gl::Context& context = device.context();
        const double gpuHost = medianMs(runs, [&] { gl::buildNanoGridGpu(context, gl::NanoKind::Float, host, header, true); });
        double gpuDevice = 0;
        double gpuDeviceSum = 0;
        double gpuDeviceFlood = 0;
        uint64_t bytes = 0;
        {
            const gl::Buffer origins("bench origins", 12 * in.origins.size(), in.origins.data());
            const gl::Buffer masks("bench masks", 64 * in.masks.size(), in.masks.data());
            const gl::Buffer values("bench values", 4 * words.size(), words.data());
            gl::NanoLeaves dev;
            dev.count = host.count;
            dev.originBuffer = &origins;
            dev.maskBuffer = &masks;
            dev.valueBuffer = &values;
            gpuDevice = medianMs(runs, [&] {
                bytes = gl::buildNanoGridGpu(context, gl::NanoKind::Float, dev, header).bytes; // reads back the headers' few words: synchronous
            });
            gl::NanoGridHeader summed = header;
            summed.checksum = true; // reads back the node CRCs: synchronous
            gpuDeviceSum = medianMs(runs, [&] { gl::buildNanoGridGpu(context, gl::NanoKind::Float, dev, summed); });
            gl::NanoGridHeader flooded = header;
            flooded.signedFloodFill = true; // the statistics read after the fill waits for it: synchronous
            gpuDeviceFlood = medianMs(runs, [&] { gl::buildNanoGridGpu(context, gl::NanoKind::Float, dev, flooded); });
        }
        fmt::print("| {} | {} | {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} |\n", mesh, n,
                   in.origins.size(), double(bytes) / 1e6, cpuBare, cpuSum, cpuFlood, gpuHost, gpuDevice, gpuDeviceSum,
                   gpuDeviceFlood);
    }
    fmt::print("\n| mesh | N | leaves | MB (mask + fog) | CPU layout + checksum ms | GPU from host, checksum on the GPU, copy back ms |\n"
               "|---|---|---|---|---|---|\n");
    for (const int64_t n : res) {
        const GridSpec grid = makeGrid(m, {n, 0.0});
        VoxelizeSettings s;
        s.backend = backend == Backend::Cpu ? Backend::Cpu : Backend::Compute;
        VoxelizeStats stats;
        const Octree octree = gl::voxelizeMesh(device, m, grid, s, Checkpoint{}, stats);
        GridOptions fog;
        fog.fog = true;
        fog.attributes = false;
        const double cpu = medianMs(runs, [&] { vdb::octreeToNanoGrids(octree, fog); });
        uint64_t bytes = 0;
        const double gpu = medianMs(runs, [&] { bytes = surfaceOnGpu(device.context(), octree); });
        fmt::print("| {} | {} | {} | {:.1f} | {:.1f} | {:.1f} |\n", mesh, n, occupiedBricks(octree).size(),
                   double(bytes) / 1e6, cpu, gpu);
    }
    if (backend == Backend::Cpu) return 0; // the device path needs a GL backend
    fmt::print("\n| mesh | N | leaves | MB | UDF before: field + readback + CPU layout ms | UDF now: field + GPU build and "
               "checksum + readback ms |\n|---|---|---|---|---|---|\n");
    for (const int64_t n : res) {
        const GridSpec grid = makeGrid(m, {n, 0.0});
        VoxelizeSettings s;
        s.backend = Backend::Compute;
        LevelSetOptions ls;
        ls.unsignedDistance = true;
        uint64_t leaves = 0, bytes = 0;
        const double before = medianMs(runs, [&] {
            VoxelizeStats stats;
            const DistanceBricks f = gl::levelSetBricks(device, m, grid, ls, s, Checkpoint{}, stats);
            vdb::levelSetNanoGrids(f, ls.exteriorBand, ls.interiorBand, grid);
        });
        const double now = medianMs(runs, [&] {
            VoxelizeStats stats;
            const gl::DeviceField f = gl::unsignedFieldLeaves(device, m, grid, ls, s, Checkpoint{}, stats);
            gl::NanoLeaves in;
            in.count = f.leaves.count;
            in.originBuffer = f.leaves.origins;
            in.maskBuffer = f.leaves.masks;
            in.valueBuffer = f.leaves.values;
            gl::NanoGridHeader header;
            header.name = "distance";
            header.voxelSize = grid.voxelSize;
            header.translation = grid.translation();
            header.background = double(float(ls.exteriorBand * grid.voxelSize));
            header.checksum = true;
            const gl::NanoGridBuffer g = gl::buildNanoGridGpu(device.context(), gl::NanoKind::Float, in, header);
            nanovdb::HostBuffer buffer = nanovdb::HostBuffer::create(g.bytes);
            g.grid.readBulk(0, g.bytes, buffer.data());
            leaves = in.count;
            bytes = g.bytes;
        });
        fmt::print("| {} | {} | {} | {:.1f} | {:.1f} | {:.1f} |\n", mesh, n, leaves, double(bytes) / 1e6, before, now);
    }
    return 0;
}

int main(int argc, char** argv)
{
    try {
        return run(argc, argv);
    } catch (const std::exception& e) { // one line, not std::terminate
        fmt::print(stderr, "svo-bench-nanovdb-gpu: {}\n", e.what());
        return 1;
    }
}
