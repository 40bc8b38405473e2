// A pipeline's view of svo: only the installed package and its public API.
//   consumer <mesh> <grid.vdb written by `svo voxelize <mesh> -r 64 -o grid.vdb`>
// Voxelizes the mesh with svo::meshToMask in the CLI grid's own transform and
// exits 0 only when both voxel sets are identical; then checks that a rotated,
// non-uniformly scaled transform works as well.
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include <svo/svo.h> // the whole public API, <openvdb/openvdb.h> included

// Active voxels of a that are not active in b (tiles counted voxel by voxel).
static openvdb::Index64 missingFrom(const openvdb::MaskGrid& a, const openvdb::MaskGrid& b)
{
    openvdb::Index64 n = 0;
    const auto acc = b.getConstAccessor();
    for (auto it = a.cbeginValueOn(); it; ++it) {
        if (it.isVoxelValue()) {
            n += !acc.isValueOn(it.getCoord());
            continue;
        }
        openvdb::CoordBBox box;
        it.getBoundingBox(box);
        for (auto c = box.begin(); c; ++c) n += !acc.isValueOn(*c);
    }
    return n;
}

static unsigned long long ull(openvdb::Index64 n) { return static_cast<unsigned long long>(n); }

int main(int argc, char** argv)
{
    if (argc != 3) {
        std::fprintf(stderr, "usage: consumer <mesh> <grid.vdb from svo voxelize>\n");
        return 2;
    }
    try {
        openvdb::initialize();

        const svo::TriangleMesh mesh = svo::loadMesh(argv[1]);
        std::vector<openvdb::Vec3d> points;
        points.reserve(mesh.positions.size());
        for (const auto& p : mesh.positions) points.emplace_back(p.x, p.y, p.z);
        std::vector<openvdb::Vec3I> triangles;
        triangles.reserve(mesh.triangles.size());
        for (const auto& t : mesh.triangles) triangles.emplace_back(t[0], t[1], t[2]);

        openvdb::io::File file(argv[2]);
        file.open();
        const auto cli = openvdb::gridPtrCast<openvdb::MaskGrid>(file.readGrid("surface"));
        file.close();
        if (!cli) throw std::runtime_error(std::string(argv[2]) + ": grid 'surface' is not a MaskGrid");

        // The CLI's grid, through the library in the same transform.
        const openvdb::MaskGrid::Ptr mask = svo::meshToMask(points, triangles, cli->transform());
        const openvdb::Index64 missing = missingFrom(*cli, *mask), extra = missingFrom(*mask, *cli);
        const bool same = missing == 0 && extra == 0 && cli->activeVoxelCount() == mask->activeVoxelCount();
        std::printf("triangles %zu | cli %llu voxels | meshToMask %llu voxels | missing %llu | extra %llu: %s\n",
                    triangles.size(), ull(cli->activeVoxelCount()), ull(mask->activeVoxelCount()), ull(missing),
                    ull(extra), same ? "identical" : "DIFFERENT");

        // Any affine transform: rotated and scaled unevenly in index space.
        const auto xform = openvdb::math::Transform::createLinearTransform(0.01);
        xform->preRotate(0.5, openvdb::math::X_AXIS);
        xform->preRotate(0.3, openvdb::math::Z_AXIS);
        xform->preScale(openvdb::Vec3d(1.0, 1.5, 0.75));
        const openvdb::MaskGrid::Ptr turned = svo::meshToMask(points, triangles, *xform);
        const bool kept = turned && turned->transform() == *xform;
        const openvdb::Index64 turnedVoxels = turned ? turned->activeVoxelCount() : 0;
        const bool affine = kept && turnedVoxels > 0;
        std::printf("rotated, scaled transform: %llu voxels, transform %s\n", ull(turnedVoxels),
                    kept ? "kept" : "CHANGED");

        return same && affine ? 0 : 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer: %s\n", e.what());
        return 1;
    }
}
