// NanoVDB's own GPU mesh converter, nanovdb::tools::cuda::MeshToGrid, timed on
// the same OBJ file and voxel size as svo (bench/gpu_host_nanovdb.sh).
// CUDA and NanoVDB's headers only (../shared/peers/nanovdb); not part of svo's build.
//
//   nvcc -O3 -std=c++17 -arch=sm_90 --extended-lambda --expt-relaxed-constexpr \
//        -I peers/nanovdb bench/nanovdb_mesh_to_grid.cu -o m2g
//   m2g MESH.obj --resolution N [--band W] [--udf] [--runs 5] [--out x.nvdb] [--compare svo.nvdb]
//
// The grid: svo's --resolution N rule (voxel size = longest side of the
// vertices' bounding box / N, index 0 at the world origin), so both tools
// share one lattice. Timing: one warm-up, then --runs conversions of the mesh
// already on the GPU (CUDA events around getHandle()/getHandleAndUDF(), its
// allocations included), median reported; "end to end" adds reading the OBJ,
// the upload, the download and the .nvdb write, once. With --compare, the
// active voxels of svo's grid 0 (its .nvdb, uncompressed) are compared with
// MeshToGrid's: voxels in both, only in svo, only in MeshToGrid; and for
// --udf the largest difference of distances on common voxels (world units).
#include <nanovdb/HostBuffer.h>
#include <nanovdb/NanoVDB.h>
#include <nanovdb/cuda/DeviceBuffer.h>
#include <nanovdb/io/IO.h>
#include <nanovdb/tools/cuda/MeshToGrid.cuh>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <type_traits>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

namespace {

using BuildT = nanovdb::ValueOnIndex;
using Clock = std::chrono::steady_clock;

void check(cudaError_t e, const char* what)
{
    if (e == cudaSuccess) return;
    std::fprintf(stderr, "m2g: %s: %s\n", what, cudaGetErrorString(e));
    std::exit(1);
}

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

struct Mesh {
    std::vector<nanovdb::Vec3f> points;
    std::vector<nanovdb::Vec3i> triangles;
    double lo[3] = {1e300, 1e300, 1e300}, hi[3] = {-1e300, -1e300, -1e300};
};

/// OBJ vertices and faces (fans for polygons; "i/t/n" and negative indices).
Mesh readObj(const std::string& path)
{
    std::ifstream in(path);
    if (!in) {
        std::fprintf(stderr, "m2g: %s: cannot open\n", path.c_str());
        std::exit(1);
    }
    Mesh m;
    std::string line;
    while (std::getline(in, line)) {
        if (line.size() < 2) continue;
        if (line[0] == 'v' && line[1] == ' ') {
            std::istringstream s(line.substr(2));
            double x, y, z;
            s >> x >> y >> z;
            const double p[3] = {x, y, z};
            for (int a = 0; a < 3; ++a) {
                m.lo[a] = std::min(m.lo[a], p[a]);
                m.hi[a] = std::max(m.hi[a], p[a]);
            }
            m.points.emplace_back(float(x), float(y), float(z));
        } else if (line[0] == 'f' && line[1] == ' ') {
            std::istringstream s(line.substr(2));
            std::string tok;
            std::vector<int> f;
            while (s >> tok) {
                int i = std::atoi(tok.c_str());
                f.push_back(i < 0 ? int(m.points.size()) + i : i - 1);
            }
            for (size_t k = 2; k < f.size(); ++k) m.triangles.emplace_back(f[0], f[k - 1], f[k]);
        }
    }
    return m;
}

double median(std::vector<double> v)
{
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Sorted keys of a grid's active voxels (host copy).
template <typename GridT>
std::vector<uint64_t> activeKeys(const GridT& g)
{
    std::vector<uint64_t> keys;
    const auto* leaves = g.tree().getFirstLeaf();
    for (uint32_t i = 0; i < g.tree().nodeCount(0); ++i) {
        const auto o = leaves[i].origin();
        for (uint32_t v = 0; v < 512; ++v) {
            if (!leaves[i].isActive(v)) continue;
            const auto c = o + std::remove_reference_t<decltype(leaves[i])>::OffsetToLocalCoord(v);
            keys.push_back(uint64_t(uint32_t(c[0] + (1 << 20))) | uint64_t(uint32_t(c[1] + (1 << 20))) << 21 |
                           uint64_t(uint32_t(c[2] + (1 << 20))) << 42);
        }
    }
    std::sort(keys.begin(), keys.end());
    return keys;
}

nanovdb::Coord keyCoord(uint64_t k)
{
    const uint64_t m = (1u << 21) - 1;
    return nanovdb::Coord(int(k & m) - (1 << 20), int((k >> 21) & m) - (1 << 20), int((k >> 42) & m) - (1 << 20));
}

} // namespace

int main(int argc, char** argv)
{
    std::string mesh, out, compare;
    int resolution = 256, runs = 5;
    float band = 3.0f;
    bool udf = false;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto next = [&]() -> std::string {
            if (i + 1 >= argc) {
                std::fprintf(stderr, "m2g: %s needs a value\n", a.c_str());
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--resolution" || a == "-r") resolution = std::atoi(next().c_str());
        else if (a == "--band") band = float(std::atof(next().c_str()));
        else if (a == "--udf") udf = true;
        else if (a == "--runs") runs = std::atoi(next().c_str());
        else if (a == "--out") out = next();
        else if (a == "--compare") compare = next();
        else mesh = a;
    }
    if (mesh.empty() || resolution < 1 || runs < 1) {
        std::fprintf(stderr, "usage: m2g MESH.obj --resolution N [--band W] [--udf] [--runs 5] [--out x.nvdb] [--compare svo.nvdb]\n");
        return 2;
    }
    check(cudaFree(nullptr), "CUDA start-up"); // the context before any timing
    const auto t0 = Clock::now();
    const Mesh m = readObj(mesh);
    const double readMs = msSince(t0);
    double longest = 0;
    for (int a = 0; a < 3; ++a) longest = std::max(longest, m.hi[a] - m.lo[a]);
    const double voxelSize = longest / resolution; // svo's makeGrid rule
    const nanovdb::Map map(voxelSize);

    const auto t1 = Clock::now();
    nanovdb::Vec3f* dPoints = nullptr;
    nanovdb::Vec3i* dTriangles = nullptr;
    check(cudaMalloc(&dPoints, m.points.size() * sizeof(nanovdb::Vec3f)), "cudaMalloc points");
    check(cudaMalloc(&dTriangles, m.triangles.size() * sizeof(nanovdb::Vec3i)), "cudaMalloc triangles");
    check(cudaMemcpy(dPoints, m.points.data(), m.points.size() * sizeof(nanovdb::Vec3f), cudaMemcpyHostToDevice), "upload");
    check(cudaMemcpy(dTriangles, m.triangles.data(), m.triangles.size() * sizeof(nanovdb::Vec3i), cudaMemcpyHostToDevice),
          "upload");
    const double uploadMs = msSince(t1);

    cudaEvent_t start, stop;
    check(cudaEventCreate(&start), "cudaEventCreate");
    check(cudaEventCreate(&stop), "cudaEventCreate");
    std::vector<double> gpuMs;
    nanovdb::GridHandle<nanovdb::cuda::DeviceBuffer> handle;
    nanovdb::cuda::DeviceBuffer sidecar;
    for (int r = 0; r <= runs; ++r) { // run 0 is the warm-up
        nanovdb::tools::cuda::MeshToGrid<BuildT> conv(dPoints, uint32_t(m.points.size()), dTriangles,
                                                      uint32_t(m.triangles.size()), map);
        conv.setNarrowBandWidth(band);
        check(cudaEventRecord(start, 0), "cudaEventRecord");
        if (udf) {
            auto result = conv.getHandleAndUDF();
            handle = std::move(result.first);
            sidecar = std::move(result.second);
        } else {
            handle = conv.getHandle();
        }
        check(cudaEventRecord(stop, 0), "cudaEventRecord");
        check(cudaEventSynchronize(stop), "cudaEventSynchronize");
        float ms = 0;
        check(cudaEventElapsedTime(&ms, start, stop), "cudaEventElapsedTime");
        if (r > 0) gpuMs.push_back(ms);
    }

    const auto t2 = Clock::now();
    handle.deviceDownload();
    std::vector<float> distances;
    if (udf) {
        distances.resize(sidecar.size() / sizeof(float));
        check(cudaMemcpy(distances.data(), sidecar.deviceData(), sidecar.size(), cudaMemcpyDeviceToHost), "download sidecar");
    }
    const double downloadMs = msSince(t2);
    double writeMs = 0;
    if (!out.empty()) {
        const auto t3 = Clock::now();
        nanovdb::io::writeGrid(out, handle);
        writeMs = msSince(t3);
    }
    const auto* grid = handle.grid<BuildT>();
    if (!grid) {
        std::fprintf(stderr, "m2g: no grid came back\n");
        return 1;
    }
    std::string runsList;
    for (double v : gpuMs) runsList += (runsList.empty() ? "" : ", ") + std::to_string(v);
    std::printf("{\"tool\": \"nanovdb_mesh_to_grid\", \"mesh\": \"%s\", \"triangles\": %zu, \"resolution\": %d, "
                "\"voxel_size\": %.9g, \"band\": %g, \"udf\": %s, \"active_voxels\": %llu, \"leaves\": %u, "
                "\"grid_bytes\": %llu, \"gpu_ms_median\": %.3f, \"gpu_ms_runs\": [%s], \"read_ms\": %.3f, "
                "\"upload_ms\": %.3f, \"download_ms\": %.3f, \"write_ms\": %.3f, \"end_to_end_ms\": %.3f",
                mesh.c_str(), m.triangles.size(), resolution, voxelSize, band, udf ? "true" : "false",
                (unsigned long long)grid->activeVoxelCount(), grid->tree().nodeCount(0),
                (unsigned long long)handle.bufferSize(), median(gpuMs), runsList.c_str(), readMs, uploadMs, downloadMs,
                writeMs, readMs + uploadMs + median(gpuMs) + downloadMs + writeMs);
    if (!compare.empty()) {
        // svo's grid 0: a ValueMask topology or a float distance grid.
        auto svo = nanovdb::io::readGrid<nanovdb::HostBuffer>(compare, 0);
        std::vector<uint64_t> theirs = activeKeys(*grid), ours;
        double maxDiff = -1;
        if (const auto* mask = svo.grid<nanovdb::ValueMask>()) {
            ours = activeKeys(*mask);
        } else if (const auto* dist = svo.grid<float>()) {
            ours = activeKeys(*dist);
            if (udf) {
                auto acc = grid->getAccessor();
                auto sacc = dist->getAccessor();
                maxDiff = 0;
                for (uint64_t k : ours) {
                    const nanovdb::Coord c = keyCoord(k);
                    if (!acc.isActive(c)) continue;
                    maxDiff = std::max(maxDiff, double(std::fabs(distances[acc.getValue(c)] - sacc.getValue(c))));
                }
            }
        } else {
            std::fprintf(stderr, "m2g: %s: grid 0 is neither a mask nor a float grid\n", compare.c_str());
            return 1;
        }
        std::vector<uint64_t> both;
        std::set_intersection(ours.begin(), ours.end(), theirs.begin(), theirs.end(), std::back_inserter(both));
        std::printf(", \"svo_voxels\": %zu, \"both\": %zu, \"only_svo\": %zu, \"only_meshtogrid\": %zu, "
                    "\"udf_max_abs_diff\": %.6g",
                    ours.size(), both.size(), ours.size() - both.size(), theirs.size() - both.size(), maxDiff);
    }
    std::printf("}\n");
    cudaFree(dPoints);
    cudaFree(dTriangles);
    return 0;
}
