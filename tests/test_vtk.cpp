// svo vtk: files read back with VTK's own readers, and the picture checked by
// its pixels. The expected counts and sets come from the .svo file, read
// independently.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <memory>
#include <set>
#include <sys/wait.h>
#include <unistd.h>
#include <utility>

#include <vtkBitArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkHyperTreeGrid.h>
#include <vtkHyperTreeGridGeometry.h>
#include <vtkHyperTreeGridNonOrientedCursor.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPolyData.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkXMLHyperTreeGridReader.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLUnstructuredGridReader.h>

#include "svo/core/octree.h"
#include "svo/core/octree_file.h"
#include "svo/core/voxel_key.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace svo;

namespace {

int runSvo(const std::string& args)
{
    const std::string cmd = std::string(SVO_EXE) + " " + args + " > /dev/null 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

class Vtk : public ::testing::Test {
protected:
    static void SetUpTestSuite()
    {
        tmp_ = std::make_unique<test::TempDir>("vtk");
        ASSERT_EQ(runSvo("voxelize -r 40 -o " + path("box.svo")), 0);
        octree_ = readOctreeFile(path("box.svo"));
    }
    static void TearDownTestSuite() { tmp_.reset(); }
    static std::string path(const std::string& name) { return tmp_->path(name); }
    static std::unique_ptr<test::TempDir> tmp_;
    static Octree octree_;
};
std::unique_ptr<test::TempDir> Vtk::tmp_;
Octree Vtk::octree_;

/// Occupied cells of a brick's 2^k sub-cubes: independent of the exporter.
uint64_t occupiedSubcubes(const Brick& b, uint32_t size)
{
    uint64_t n = 0;
    for (uint32_t ox = 0; ox < 8; ox += size)
        for (uint32_t oy = 0; oy < 8; oy += size)
            for (uint32_t oz = 0; oz < 8; oz += size) {
                bool any = false;
                for (uint32_t bit = 0; bit < 512; ++bit) {
                    const uint32_t x = bit >> 6, y = bit >> 3 & 7, z = bit & 7;
                    if (x >= ox && x < ox + size && y >= oy && y < oy + size && z >= oz && z < oz + size)
                        any |= bool(b.words[bit >> 6] >> (bit & 63) & 1);
                }
                n += any;
            }
    return n;
}

using Cell = std::array<uint32_t, 4>; // level, x, y, z (in cells of that level)

/// Cells of the .htg's levels that hold at least one voxel, from the voxel
/// set alone: a voxel lies in cell p >> shift at the level whose cells are
/// 2^shift voxels wide (level brickLevel + 3 - shift).
std::set<Cell> occupiedCells(const Octree& o)
{
    std::set<Cell> cells;
    const uint32_t deepest = o.brickLevel + 3;
    for (uint64_t k : octreeKeys(o)) {
        const auto p = unpackVoxelKey(k);
        for (uint32_t shift = 0; shift <= deepest; ++shift)
            cells.insert({deepest - shift, p[0] >> shift, p[1] >> shift, p[2] >> shift});
    }
    return cells;
}

/// Every cell of the tree as read back: its level and position, and whether it
/// is masked and a leaf.
struct ReadCell {
    Cell cell;
    bool masked, leaf;
};
void collectCells(vtkHyperTreeGridNonOrientedCursor* cursor, const Cell& at, std::vector<ReadCell>& out)
{
    out.push_back({at, cursor->IsMasked(), cursor->IsLeaf()});
    if (cursor->IsLeaf()) return;
    for (unsigned char c = 0; c < cursor->GetNumberOfChildren(); ++c) {
        cursor->ToChild(c);
        collectCells(cursor, {at[0] + 1, 2 * at[1] + (c & 1), 2 * at[2] + (c >> 1 & 1), 2 * at[3] + (c >> 2)}, out);
        cursor->ToParent();
    }
}

} // namespace

TEST_F(Vtk, HyperTreeGridMasksExactlyTheEmptyCells)
{
    ASSERT_EQ(runSvo("vtk " + path("box.svo") + " -o " + path("masked.htg")), 0);
    vtkNew<vtkXMLHyperTreeGridReader> reader;
    reader->SetFileName(path("masked.htg").c_str());
    reader->Update();
    vtkHyperTreeGrid* htg = reader->GetOutput();
    ASSERT_TRUE(htg->HasMask());
    ASSERT_EQ(htg->GetMask()->GetNumberOfTuples(), htg->GetNumberOfVertices());

    vtkNew<vtkHyperTreeGridNonOrientedCursor> cursor;
    htg->InitializeNonOrientedCursor(cursor, 0);
    std::vector<ReadCell> cells;
    collectCells(cursor, {0, 0, 0, 0}, cells);
    ASSERT_EQ(int64_t(cells.size()), int64_t(htg->GetNumberOfVertices()));

    const std::set<Cell> occupied = occupiedCells(octree_);
    const uint32_t voxelLevel = octree_.brickLevel + 3;
    std::set<Cell> visibleLeaves;
    uint64_t masked = 0;
    for (const ReadCell& c : cells) {
        EXPECT_EQ(c.masked, occupied.count(c.cell) == 0)
            << "level " << c.cell[0] << " cell " << c.cell[1] << "," << c.cell[2] << "," << c.cell[3];
        masked += c.masked;
        if (c.leaf && !c.masked) visibleLeaves.insert(c.cell);
    }
    EXPECT_GT(masked, 0u);
    // The visible leaves are the voxels, one cell each.
    std::set<Cell> voxels;
    for (const Cell& c : occupied)
        if (c[0] == voxelLevel) voxels.insert(c);
    EXPECT_EQ(voxels.size(), octree_.voxelCount());
    EXPECT_EQ(visibleLeaves, voxels);
}

TEST_F(Vtk, HyperTreeGridGeometryIsTheVoxelSurface)
{
    // What ParaView draws of a .htg with no filter: vtkHyperTreeGridGeometry's
    // faces. With the mask, these are the faces of voxels that border an empty
    // voxel; without it, the 6 faces of the root cube. Faces are compared as
    // sets of doubled local centres (one half-integer coordinate each): VTK
    // 9.1 emits a face between two cells of one level from both sides.
    ASSERT_EQ(runSvo("vtk " + path("box.svo") + " -o " + path("surface.htg")), 0);
    vtkNew<vtkXMLHyperTreeGridReader> reader;
    reader->SetFileName(path("surface.htg").c_str());
    vtkNew<vtkHyperTreeGridGeometry> geometry;
    geometry->SetInputConnection(reader->GetOutputPort());
    geometry->Update();
    vtkPolyData* poly = vtkPolyData::SafeDownCast(geometry->GetOutput());
    ASSERT_NE(poly, nullptr);

    const GridSpec& g = octree_.grid;
    std::set<std::array<int64_t, 3>> drawn;
    for (vtkIdType c = 0; c < poly->GetNumberOfCells(); ++c) {
        double b[6];
        poly->GetCellBounds(c, b);
        std::array<int64_t, 3> centre;
        int flat = 0, voxelWide = 0; // a voxel's face: flat along one axis, one voxel along two
        for (int a = 0; a < 3; ++a) {
            const double extent = (b[2 * a + 1] - b[2 * a]) / g.voxelSize;
            flat += std::abs(extent) < 1e-3; // points are float
            voxelWide += std::abs(extent - 1) < 1e-3;
            const double local = 0.5 * (b[2 * a] + b[2 * a + 1]) / g.voxelSize - double(g.anchor[a] + g.shift[a]);
            centre[size_t(a)] = std::llround(2 * local);
        }
        EXPECT_TRUE(flat == 1 && voxelWide == 2) << "face " << c << " is not one voxel's face: " << (b[1] - b[0]) / g.voxelSize << " " << (b[3] - b[2]) / g.voxelSize << " " << (b[5] - b[4]) / g.voxelSize;
        drawn.insert(centre);
    }

    const std::vector<uint64_t> keys = octreeKeys(octree_);
    const std::set<uint64_t> voxels(keys.begin(), keys.end());
    std::set<std::array<int64_t, 3>> surface;
    for (uint64_t k : keys) {
        const auto p = unpackVoxelKey(k);
        for (int axis = 0; axis < 3; ++axis)
            for (int side : {-1, 1}) {
                auto q = p;
                const bool edge = side < 0 && q[axis] == 0;
                q[axis] += uint32_t(side);
                if (!edge && voxels.count(packVoxelKey(q[0], q[1], q[2]))) continue;
                std::array<int64_t, 3> centre{2 * int64_t(p[0]), 2 * int64_t(p[1]), 2 * int64_t(p[2])};
                centre[size_t(axis)] += side;
                surface.insert(centre);
            }
    }
    EXPECT_GT(surface.size(), 6u);
    EXPECT_EQ(drawn, surface);
}

TEST_F(Vtk, HyperTreeGridReadsBackWithTheOctreesCounts)
{
    ASSERT_EQ(runSvo("vtk " + path("box.svo") + " -o " + path("box.htg")), 0);
    vtkNew<vtkXMLHyperTreeGridReader> reader;
    reader->SetFileName(path("box.htg").c_str());
    reader->Update();
    vtkHyperTreeGrid* htg = reader->GetOutput();
    ASSERT_NE(htg, nullptr);
    EXPECT_EQ(htg->GetBranchFactor(), 2u);
    // Refined cells: every occupied node, and the occupied 4^3 and 2^3 sub-cubes.
    const auto st = octreeStats(octree_);
    uint64_t refined = 0;
    for (size_t l = 0; l < st.occupiedPerLevel.size(); ++l) refined += st.occupiedPerLevel[l];
    for (const auto& b : octree_.bricks) refined += occupiedSubcubes(b, 4) + occupiedSubcubes(b, 2);
    EXPECT_EQ(uint64_t(htg->GetNumberOfVertices()), 1 + 8 * refined);
    for (const char* name : {"level", "occupancy", "voxel_count"})
        EXPECT_NE(htg->GetCellData()->GetArray(name), nullptr) << name;
    vtkDataArray* level = htg->GetCellData()->GetArray("level");
    vtkDataArray* occ = htg->GetCellData()->GetArray("occupancy");
    vtkDataArray* count = htg->GetCellData()->GetArray("voxel_count");
    ASSERT_TRUE(level && occ && count);
    uint64_t voxels = 0;
    std::vector<uint64_t> perLevel(octree_.brickLevel + 4, 0);
    for (vtkIdType i = 0; i < level->GetNumberOfTuples(); ++i) {
        const auto l = size_t(level->GetTuple1(i));
        ASSERT_LT(l, perLevel.size());
        perLevel[l] += occ->GetTuple1(i) > 0;
        if (l == octree_.brickLevel + 3) voxels += occ->GetTuple1(i) > 0;
    }
    EXPECT_EQ(voxels, octree_.voxelCount());
    for (size_t l = 0; l <= octree_.brickLevel; ++l) EXPECT_EQ(perLevel[l], st.occupiedPerLevel[l]) << "level " << l;
    EXPECT_EQ(uint64_t(count->GetTuple1(0)), octree_.voxelCount()); // the root holds them all
}

TEST_F(Vtk, VoxelCellsAndOutlinesReadBack)
{
    ASSERT_EQ(runSvo("vtk " + path("box.svo") + " -o " + path("box.vtu")), 0);
    vtkNew<vtkXMLUnstructuredGridReader> ug;
    ug->SetFileName(path("box.vtu").c_str());
    ug->Update();
    EXPECT_EQ(uint64_t(ug->GetOutput()->GetNumberOfCells()), octree_.voxelCount());
    EXPECT_EQ(ug->GetOutput()->GetCellType(0), VTK_VOXEL);
    EXPECT_NE(ug->GetOutput()->GetCellData()->GetArray("index"), nullptr);
    // One voxel's cell has the voxel's size.
    double b[6];
    ug->GetOutput()->GetCell(0)->GetBounds(b);
    EXPECT_NEAR(b[1] - b[0], octree_.grid.voxelSize, 1e-9);

    ASSERT_EQ(runSvo("vtk " + path("box.svo") + " -o " + path("box.vtp") + " --levels 1..3"), 0);
    vtkNew<vtkXMLPolyDataReader> pd;
    pd->SetFileName(path("box.vtp").c_str());
    pd->Update();
    const auto st = octreeStats(octree_);
    EXPECT_EQ(uint64_t(pd->GetOutput()->GetNumberOfLines()),
              12 * (st.occupiedPerLevel[1] + st.occupiedPerLevel[2] + st.occupiedPerLevel[3]));
    vtkDataArray* level = pd->GetOutput()->GetCellData()->GetArray("level");
    ASSERT_NE(level, nullptr);
    EXPECT_EQ(level->GetRange()[0], 1.0);
    EXPECT_EQ(level->GetRange()[1], 3.0);
}

TEST_F(Vtk, PictureShowsVoxelsAndOutlines)
{
    if (runSvo("vtk " + path("box.svo") + " --png " + path("box.png") + " --size 640") != 0) {
        // Only acceptable when there is no way to get an X display.
        ASSERT_TRUE(std::getenv("DISPLAY") == nullptr && std::system("command -v Xvfb > /dev/null") != 0)
            << "svo vtk --png failed although an X server is available";
        GTEST_SKIP() << "no DISPLAY and no Xvfb";
    }
    vtkNew<vtkPNGReader> png;
    png->SetFileName(path("box.png").c_str());
    png->Update();
    vtkImageData* img = png->GetOutput();
    int dims[3];
    img->GetDimensions(dims);
    EXPECT_EQ(dims[0], 640);
    EXPECT_EQ(dims[1], 480);
    uint64_t green = 0, red = 0, white = 0, total = uint64_t(dims[0]) * uint64_t(dims[1]);
    for (int y = 0; y < dims[1]; ++y)
        for (int x = 0; x < dims[0]; ++x) {
            const auto* p = static_cast<unsigned char*>(img->GetScalarPointer(x, y, 0));
            const int r = p[0], g = p[1], b = p[2];
            if (r > 240 && g > 240 && b > 240) ++white;
            else if (g > r + 30 && g > b + 30) ++green;
            else if (r > g + 80 && r > b + 80) ++red;
        }
    // The voxels fill a good part of the frame, outlines show, the rest is background.
    EXPECT_GT(double(green) / double(total), 0.15) << green;
    EXPECT_GT(red, 500u);
    EXPECT_GT(double(white) / double(total), 0.05) << white;
}

TEST_F(Vtk, AttributeChannelsBecomeCellArrays)
{
    ASSERT_EQ(runSvo("voxelize -r 24 --attributes normal,triangle -o " + path("attr.svo")), 0);
    const Octree o = readOctreeFile(path("attr.svo"));
    ASSERT_EQ(o.channels(), uint32_t(kNormals | kTriangles));
    ASSERT_EQ(runSvo("vtk " + path("attr.svo") + " -o " + path("attr.vtu")), 0);
    vtkNew<vtkXMLUnstructuredGridReader> ug;
    ug->SetFileName(path("attr.vtu").c_str());
    ug->Update();
    vtkDataArray* normal = ug->GetOutput()->GetCellData()->GetArray("normal");
    vtkDataArray* tri = ug->GetOutput()->GetCellData()->GetArray("triangle_id");
    ASSERT_TRUE(normal && tri);
    EXPECT_EQ(ug->GetOutput()->GetCellData()->GetArray("color"), nullptr); // not asked for
    ASSERT_EQ(uint64_t(normal->GetNumberOfTuples()), o.voxelCount());
    // Unit normals, or 0 where opposite faces cancel (a block standing on the floor).
    size_t zeroVtk = 0, zeroSvo = 0;
    for (vtkIdType i = 0; i < normal->GetNumberOfTuples(); ++i) {
        const double* n = normal->GetTuple3(i);
        const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        zeroVtk += len == 0.0;
        if (len != 0.0) {
            EXPECT_NEAR(len, 1.0, 1e-4) << i;
        }
        EXPECT_GE(tri->GetTuple1(i), 0.0);
    }
    for (const auto& n : o.attributes.normals) zeroSvo += n.x == 0 && n.y == 0 && n.z == 0;
    EXPECT_EQ(zeroVtk, zeroSvo);
    EXPECT_LT(zeroVtk, o.voxelCount() / 20);
    // The multiset of triangle ids equals the octree's.
    std::vector<int> fromVtk, fromSvo(o.attributes.triangles.begin(), o.attributes.triangles.end());
    for (vtkIdType i = 0; i < tri->GetNumberOfTuples(); ++i) fromVtk.push_back(int(tri->GetTuple1(i)));
    std::sort(fromVtk.begin(), fromVtk.end());
    std::sort(fromSvo.begin(), fromSvo.end());
    EXPECT_EQ(fromVtk, fromSvo);

    ASSERT_EQ(runSvo("vtk " + path("attr.svo") + " -o " + path("attr.htg")), 0);
    vtkNew<vtkXMLHyperTreeGridReader> reader;
    reader->SetFileName(path("attr.htg").c_str());
    reader->Update();
    vtkDataArray* htgTri = reader->GetOutput()->GetCellData()->GetArray("triangle_id");
    ASSERT_NE(htgTri, nullptr);
    uint64_t voxelCells = 0;
    for (vtkIdType i = 0; i < htgTri->GetNumberOfTuples(); ++i) voxelCells += htgTri->GetTuple1(i) >= 0;
    EXPECT_EQ(voxelCells, o.voxelCount());
}

/// Output (stdout and stderr) and exit status of a shell command.
static std::pair<int, std::string> runCapture(const std::string& cmd)
{
    FILE* p = popen((cmd + " 2>&1").c_str(), "r");
    std::string out;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
    const int status = pclose(p);
    return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// VTK is a module that only `svo vtk` loads: svo itself needs none of VTK's
// libraries, and a copy of svo away from its module says so in one line
// when asked for VTK output, writing nothing.
TEST_F(Vtk, OnlyTheVtkCommandLoadsVtk)
{
    const auto ldd = runCapture(std::string("ldd ") + SVO_EXE);
    ASSERT_EQ(ldd.first, 0) << ldd.second;
    EXPECT_EQ(ldd.second.find("libvtk"), std::string::npos) << ldd.second;

    const fs::path lone = fs::path(path("lone")) / "bin" / "svo";
    fs::create_directories(lone.parent_path());
    fs::copy_file(SVO_EXE, lone);
    const auto r = runCapture(lone.string() + " vtk " + path("box.svo") + " -o " + path("lone.htg"));
    EXPECT_EQ(r.first, 1) << r.second;
    EXPECT_EQ(std::count(r.second.begin(), r.second.end(), '\n'), 1) << r.second;
    EXPECT_NE(r.second.find("libsvo_vtk.so: cannot load svo's VTK module"), std::string::npos) << r.second;
    EXPECT_FALSE(fs::exists(path("lone.htg")));
    // The same copy still does everything else.
    EXPECT_EQ(runCapture(lone.string() + " info " + path("box.svo")).first, 0);
}
