// Interim consumer, until the library API (svo/svo.h, svo::meshToMask) lands:
// voxelizes the mesh through the installed svo::gl and svo::vdb_io and checks
// the result against the grid the CLI wrote, voxel for voxel.
#include <cstdio>
#include <exception>
#include <stdexcept>

#include <openvdb/openvdb.h>

#include <svo/core/grid.h>
#include <svo/core/mesh_io.h>
#include <svo/gl/raster_voxelizer.h>
#include <svo/vdb_io/grid_builder.h>

// Active voxels of a that are not active in b.
static openvdb::Index64 missingFrom(const openvdb::MaskGrid& a, const openvdb::MaskGrid& b)
{
    openvdb::Index64 n = 0;
    const auto acc = b.getConstAccessor();
    for (auto it = a.cbeginValueOn(); it; ++it) {
        if (!it.isVoxelValue()) { // a tile: count its voxels one by one
            openvdb::CoordBBox box;
            it.getBoundingBox(box);
            for (auto c = box.begin(); c; ++c) n += !acc.isValueOn(*c);
        } else {
            n += !acc.isValueOn(it.getCoord());
        }
    }
    return n;
}

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: consumer <mesh> <grid written by svo voxelize -r 64>.vdb\n");
        return 2;
    }
    try {
        openvdb::initialize();
        const svo::TriangleMesh mesh = svo::loadMesh(argv[1]);

        openvdb::io::File file(argv[2]);
        file.open();
        const auto cli = openvdb::gridPtrCast<openvdb::MaskGrid>(file.readGrid("surface"));
        file.close();
        if (!cli) throw std::runtime_error("grid 'surface' is not a MaskGrid");

        svo::GridRequest request;
        request.resolution = 64;
        const svo::GridSpec grid = svo::makeGrid(mesh, request);
        svo::gl::Context context;
        const auto octree = svo::gl::voxelizeToOctree(context, mesh, grid);
        const auto mine = svo::vdb::buildMaskGrid(octree.octree);

        const auto missing = missingFrom(*cli, *mine), extra = missingFrom(*mine, *cli);
        std::printf("triangles %zu | cli %llu voxels | package %llu voxels | missing %llu | extra %llu\n",
                    mesh.triangles.size(), (unsigned long long)cli->activeVoxelCount(),
                    (unsigned long long)mine->activeVoxelCount(), (unsigned long long)missing,
                    (unsigned long long)extra);
        const bool same = missing == 0 && extra == 0 && cli->activeVoxelCount() == mine->activeVoxelCount();
        std::printf("%s\n", same ? "identical" : "DIFFERENT");
        return same ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
