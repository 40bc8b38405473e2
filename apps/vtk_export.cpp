#include "vtk_export.h"

#include <algorithm>
#include <array>
#include <fmt/format.h>
#include <functional>
#include <unordered_set>

#include <vtkActor.h>
#include <vtkAutoInit.h>
#include <vtkBitArray.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkFloatArray.h>
#include <vtkHyperTreeGrid.h>
#include <vtkHyperTreeGridNonOrientedCursor.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnsignedIntArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkWindowToImageFilter.h>
#include <vtkXMLHyperTreeGridWriter.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkXMLUnstructuredGridWriter.h>

#include "svo/core/atomic_file.h"
#include "svo/core/error.h"
#include "svo/core/voxel_key.h"
#include "xvfb.h"

// The object factories that give vtkRenderWindow and its interactor their
// OpenGL classes, registered when the module loads (what VTK's CMake
// vtk_module_autoinit would arrange, done here so that the module builds the
// same against VTK's package or against its headers alone).
VTK_MODULE_INIT(vtkRenderingOpenGL2);
VTK_MODULE_INIT(vtkInteractionStyle);

namespace svo::app {
namespace {

/// World position of a point in local voxel coordinates (voxel i spans i +- 1/2).
std::array<double, 3> world(const GridSpec& g, double x, double y, double z)
{
    const double p[3] = {x, y, z};
    std::array<double, 3> w;
    for (int a = 0; a < 3; ++a) w[a] = g.voxelSize * (double(g.anchor[a] + g.shift[a]) + p[a]);
    return w;
}

/// Voxels set in the sub-cube [o, o + size) of a brick.
uint32_t countIn(const Brick& b, uint32_t ox, uint32_t oy, uint32_t oz, uint32_t size)
{
    uint32_t n = 0;
    for (uint32_t x = ox; x < ox + size; ++x)
        for (uint32_t y = oy; y < oy + size; ++y)
            for (uint32_t z = oz; z < oz + size; ++z) {
                const uint32_t bit = x << 6 | y << 3 | z;
                n += uint32_t(b.words[bit >> 6] >> (bit & 63) & 1);
            }
    return n;
}

/// The octree's attribute channels as VTK cell arrays: `normal`, `triangle_id`
/// and `color`, each only when the octree has it. Cells that are not single
/// voxels get 0 (normal, colour) or -1 (triangle id).
class AttributeArrays {
public:
    explicit AttributeArrays(const Octree& o) : a_(o.attributes)
    {
        normal_->SetName("normal");
        normal_->SetNumberOfComponents(3);
        color_->SetName("color");
        color_->SetNumberOfComponents(3);
        triangle_->SetName("triangle_id");
    }
    void set(vtkIdType cell, uint64_t voxel)
    {
        if (!a_.normals.empty()) {
            const Vec3f& n = a_.normals[voxel];
            normal_->InsertTuple3(cell, n.x, n.y, n.z);
        }
        if (!a_.colors.empty()) {
            const Vec3f& c = a_.colors[voxel];
            color_->InsertTuple3(cell, c.x, c.y, c.z);
        }
        if (!a_.triangles.empty()) triangle_->InsertValue(cell, a_.triangles[voxel]);
    }
    void setEmpty(vtkIdType cell)
    {
        if (!a_.normals.empty()) normal_->InsertTuple3(cell, 0, 0, 0);
        if (!a_.colors.empty()) color_->InsertTuple3(cell, 0, 0, 0);
        if (!a_.triangles.empty()) triangle_->InsertValue(cell, -1);
    }
    void addTo(vtkCellData* data) const
    {
        if (!a_.normals.empty()) data->AddArray(normal_);
        if (!a_.triangles.empty()) data->AddArray(triangle_);
        if (!a_.colors.empty()) data->AddArray(color_);
    }

private:
    const VoxelAttributes& a_;
    vtkNew<vtkFloatArray> normal_, color_;
    vtkNew<vtkIntArray> triangle_;
};

/// Rank of `bit` among the set bits of a brick: the voxel's place in voxel order.
uint64_t rankInBrick(const Brick& b, uint32_t bit)
{
    uint64_t n = 0;
    for (uint32_t w = 0; w < bit / 64; ++w) n += uint64_t(__builtin_popcountll(b.words[w]));
    return n + uint64_t(__builtin_popcountll(b.words[bit / 64] & ((uint64_t(1) << (bit % 64)) - 1)));
}

/// Writes `data` with a VTK XML writer in binary mode (see writeHyperTreeGrid for why not appended).
template <typename Writer>
void writeXml(const std::string& path, vtkDataObject* data, const char* what)
{
    vtkNew<Writer> writer;
    writer->SetInputData(data);
    writer->SetDataModeToBinary();
    writeAtomically(path, [&](const std::string& tmp) {
        writer->SetFileName(tmp.c_str());
        if (writer->Write() != 1) throw IoError(fmt::format("{}: VTK could not write the {}", path, what));
    });
}

/// Appends the 12 edges of the box [lo, hi] (world) to points/lines.
void addBoxEdges(vtkPoints* points, vtkCellArray* lines, const std::array<double, 3>& lo, const std::array<double, 3>& hi)
{
    const vtkIdType base = points->GetNumberOfPoints();
    for (int i = 0; i < 8; ++i) points->InsertNextPoint(i & 1 ? hi[0] : lo[0], i & 2 ? hi[1] : lo[1], i & 4 ? hi[2] : lo[2]);
    static const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                     {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (const auto& e : edges) {
        const vtkIdType ids[2] = {base + e[0], base + e[1]};
        lines->InsertNextCell(2, ids);
    }
}

vtkSmartPointer<vtkPolyData> outlines(const Octree& o, const LevelRange& levels)
{
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> lines;
    vtkNew<vtkUnsignedCharArray> level;
    level->SetName("level");
    const uint32_t last = std::min(levels.last, o.brickLevel);
    std::function<void(uint32_t, uint32_t, uint32_t, uint32_t, uint32_t)> visit = [&](uint32_t node, uint32_t l,
                                                                                        uint32_t x, uint32_t y, uint32_t z) {
        const OctreeNode& n = o.nodes[node];
        if (!n.childMask) return;
        if (l >= levels.first && l <= last) {
            const double s = double(8u << (o.brickLevel - l));
            addBoxEdges(points, lines, world(o.grid, x * s - 0.5, y * s - 0.5, z * s - 0.5),
                        world(o.grid, (x + 1) * s - 0.5, (y + 1) * s - 0.5, (z + 1) * s - 0.5));
            for (int e = 0; e < 12; ++e) level->InsertNextValue(static_cast<unsigned char>(l));
        }
        if (l == o.brickLevel || l >= last) return;
        for (uint32_t c = 0; c < 8; ++c)
            if (n.childMask >> c & 1) visit(n.child + c, l + 1, 2 * x + (c & 1), 2 * y + (c >> 1 & 1), 2 * z + (c >> 2));
    };
    visit(0, 0, 0, 0, 0);
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(points);
    poly->SetLines(lines);
    poly->GetCellData()->AddArray(level);
    return poly;
}

/// The faces of occupied voxels that border an empty voxel: the voxel surface.
vtkSmartPointer<vtkPolyData> voxelSurface(const Octree& o)
{
    const std::vector<uint64_t> keys = octreeKeys(o);
    const std::unordered_set<uint64_t> occupied(keys.begin(), keys.end());
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    vtkNew<vtkCellArray> quads;
    for (uint64_t k : keys) {
        const auto p = unpackVoxelKey(k);
        for (int axis = 0; axis < 3; ++axis)
            for (int side : {-1, 1}) {
                auto q = p;
                if (side < 0 && q[axis] == 0) {
                } else {
                    q[axis] += side;
                    if (occupied.count(packVoxelKey(q[0], q[1], q[2]))) continue;
                }
                // The face at p[axis] + side/2, spanning the other two axes.
                const int u = (axis + 1) % 3, v = (axis + 2) % 3;
                const vtkIdType base = points->GetNumberOfPoints();
                for (int corner = 0; corner < 4; ++corner) {
                    double c[3];
                    c[axis] = p[axis] + 0.5 * side;
                    c[u] = p[u] + ((corner == 1 || corner == 2) ? 0.5 : -0.5);
                    c[v] = p[v] + (corner >= 2 ? 0.5 : -0.5);
                    const auto w = world(o.grid, c[0], c[1], c[2]);
                    points->InsertNextPoint(w.data());
                }
                const vtkIdType ids[4] = {base, base + 1, base + 2, base + 3};
                quads->InsertNextCell(4, ids);
            }
    }
    auto poly = vtkSmartPointer<vtkPolyData>::New();
    poly->SetPoints(points);
    poly->SetPolys(quads);
    return poly;
}

} // namespace

void writeHyperTreeGrid(const std::string& path, const Octree& o, const LevelRange& levels)
{
    const uint32_t deepest = std::min(levels.last, o.brickLevel + 3);
    vtkNew<vtkHyperTreeGrid> htg;
    htg->SetBranchFactor(2);
    htg->SetDimensions(2, 2, 2); // points: one root cell
    const double rootVoxels = double(8u << o.brickLevel);
    const auto lo = world(o.grid, -0.5, -0.5, -0.5), hi = world(o.grid, rootVoxels - 0.5, rootVoxels - 0.5, rootVoxels - 0.5);
    vtkNew<vtkDoubleArray> xs, ys, zs;
    for (auto [arr, a] : {std::pair{xs.Get(), 0}, std::pair{ys.Get(), 1}, std::pair{zs.Get(), 2}}) {
        arr->InsertNextValue(lo[size_t(a)]);
        arr->InsertNextValue(hi[size_t(a)]);
    }
    htg->SetXCoordinates(xs);
    htg->SetYCoordinates(ys);
    htg->SetZCoordinates(zs);

    vtkNew<vtkUnsignedCharArray> level, occupancy;
    vtkNew<vtkUnsignedIntArray> count;
    // Empty cells are masked (1), so a viewer draws the voxels without a
    // threshold filter; otherwise ParaView shows the root cube, solid.
    vtkNew<vtkBitArray> mask;
    level->SetName("level");
    occupancy->SetName("occupancy");
    count->SetName("voxel_count");
    AttributeArrays attributes(o);
    const auto offsets = brickVoxelOffsets(o);
    vtkNew<vtkHyperTreeGridNonOrientedCursor> cursor;
    htg->InitializeNonOrientedCursor(cursor, 0, true);
    cursor->SetGlobalIndexStart(0);
    auto record = [&](uint32_t l, uint32_t n) {
        const vtkIdType id = cursor->GetGlobalNodeIndex();
        level->InsertValue(id, static_cast<unsigned char>(l));
        occupancy->InsertValue(id, n ? 1 : 0);
        count->InsertValue(id, n);
        mask->InsertValue(id, n ? 0 : 1);
        attributes.setEmpty(id);
    };
    // Inside brick `bi`: sub-cubes of `size` voxels at brick offset (x, y, z).
    std::function<uint32_t(uint32_t, uint32_t, uint32_t, uint32_t, uint32_t, uint32_t)> visitBrick =
        [&](uint32_t bi, uint32_t l, uint32_t x, uint32_t y, uint32_t z, uint32_t size) {
            const Brick& b = o.bricks[bi];
            const uint32_t n = countIn(b, x, y, z, size);
            record(l, n);
            if (n && size == 1)
                attributes.set(cursor->GetGlobalNodeIndex(), offsets[bi] + rankInBrick(b, x << 6 | y << 3 | z));
            if (n && size > 1 && l < deepest) {
                cursor->SubdivideLeaf();
                const uint32_t h = size / 2;
                for (unsigned char c = 0; c < 8; ++c) {
                    cursor->ToChild(c);
                    visitBrick(bi, l + 1, x + (c & 1) * h, y + (c >> 1 & 1) * h, z + (c >> 2) * h, h);
                    cursor->ToParent();
                }
            }
            return n;
        };
    std::function<uint32_t(uint32_t, uint32_t)> visit = [&](uint32_t node, uint32_t l) -> uint32_t {
        const OctreeNode& n = o.nodes[node];
        if (l == o.brickLevel) return n.childMask ? visitBrick(n.child, l, 0, 0, 0, 8) : (record(l, 0), 0u);
        uint32_t total = 0;
        if (n.childMask && l < deepest) {
            record(l, 0);
            cursor->SubdivideLeaf();
            for (unsigned char c = 0; c < 8; ++c) {
                cursor->ToChild(c);
                total += visit(n.child + c, l + 1);
                cursor->ToParent();
            }
            record(l, total);
        } else if (n.childMask) {
            // Counted but not refined: the voxels below come from the bricks.
            std::function<uint32_t(uint32_t, uint32_t)> sum = [&](uint32_t m, uint32_t k) -> uint32_t {
                const OctreeNode& q = o.nodes[m];
                if (!q.childMask) return 0;
                if (k == o.brickLevel) return o.bricks[q.child].count();
                uint32_t s = 0;
                for (uint32_t c = 0; c < 8; ++c) s += sum(q.child + c, k + 1);
                return s;
            };
            total = sum(node, l);
            record(l, total);
        } else {
            record(l, 0);
        }
        return total;
    };
    visit(0, 0);
    htg->SetMask(mask);
    htg->GetCellData()->AddArray(level);
    htg->GetCellData()->AddArray(occupancy);
    htg->GetCellData()->AddArray(count);
    attributes.addTo(htg->GetCellData());

    writeXml<vtkXMLHyperTreeGridWriter>(path, htg, "hyper tree grid");
}

void writeVoxelCells(const std::string& path, const Octree& o)
{
    // Cells in voxel order (bricks by index, bits ascending), the attributes' order.
    std::vector<uint64_t> keys;
    keys.reserve(o.voxelCount());
    auto refs = occupiedBricks(o);
    std::sort(refs.begin(), refs.end(), [](const BrickRef& a, const BrickRef& b) { return a.index < b.index; });
    for (const auto& r : refs)
        for (uint32_t bit = 0; bit < 512; ++bit)
            if (o.bricks[r.index].words[bit >> 6] >> (bit & 63) & 1)
                keys.push_back(packVoxelKey(r.origin[0], r.origin[1], r.origin[2]) | bit);
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->Allocate(vtkIdType(keys.size() * 8));
    vtkNew<vtkUnstructuredGrid> grid;
    grid->Allocate(vtkIdType(keys.size()));
    vtkNew<vtkIntArray> index;
    index->SetName("index");
    index->SetNumberOfComponents(3);
    AttributeArrays attributes(o);
    for (uint64_t k : keys) {
        attributes.set(grid->GetNumberOfCells(), uint64_t(grid->GetNumberOfCells()));
        const auto p = unpackVoxelKey(k);
        const vtkIdType base = points->GetNumberOfPoints();
        // VTK_VOXEL corner order: x fastest, then y, then z.
        for (int i = 0; i < 8; ++i) {
            const auto w = world(o.grid, p[0] + (i & 1 ? 0.5 : -0.5), p[1] + (i & 2 ? 0.5 : -0.5), p[2] + (i & 4 ? 0.5 : -0.5));
            points->InsertNextPoint(w.data());
        }
        vtkIdType ids[8];
        for (int i = 0; i < 8; ++i) ids[i] = base + i;
        grid->InsertNextCell(VTK_VOXEL, 8, ids);
        const auto g = o.grid.toGlobal(p);
        const int gi[3] = {int(g[0]), int(g[1]), int(g[2])};
        index->InsertNextTypedTuple(gi);
    }
    grid->SetPoints(points);
    grid->GetCellData()->AddArray(index);
    attributes.addTo(grid->GetCellData());
    writeXml<vtkXMLUnstructuredGridWriter>(path, grid, "voxel cells");
}

void writeNodeOutlines(const std::string& path, const Octree& o, const LevelRange& levels)
{
    writeXml<vtkXMLPolyDataWriter>(path, outlines(o, levels), "node outlines");
}

void renderPicture(const std::string& path, const Octree& o, const PictureOptions& opt)
{
    checkWritable(path);
    const XDisplay display; // before any VTK window exists
    vtkNew<vtkRenderer> renderer;
    renderer->SetBackground(1.0, 1.0, 1.0);

    vtkNew<vtkPolyDataMapper> voxelMapper;
    voxelMapper->SetInputData(voxelSurface(o));
    vtkNew<vtkActor> voxels;
    voxels->SetMapper(voxelMapper);
    voxels->GetProperty()->SetColor(0.30, 0.72, 0.30);
    voxels->GetProperty()->SetAmbient(0.35);
    voxels->GetProperty()->SetDiffuse(0.65);
    renderer->AddActor(voxels);

    vtkNew<vtkPolyDataMapper> lineMapper;
    lineMapper->SetInputData(outlines(o, opt.outlineLevels));
    lineMapper->ScalarVisibilityOff();
    vtkNew<vtkActor> lines;
    lines->SetMapper(lineMapper);
    lines->GetProperty()->SetColor(0.85, 0.12, 0.12);
    lines->GetProperty()->SetLineWidth(1.5);
    lines->GetProperty()->LightingOff();
    renderer->AddActor(lines);

    if (opt.mesh) {
        vtkNew<vtkPoints> points;
        points->SetDataTypeToDouble();
        for (const auto& p : opt.mesh->positions) points->InsertNextPoint(p.x, p.y, p.z);
        vtkNew<vtkCellArray> tris;
        for (const auto& t : opt.mesh->triangles) {
            const vtkIdType ids[3] = {t[0], t[1], t[2]};
            tris->InsertNextCell(3, ids);
        }
        vtkNew<vtkPolyData> poly;
        poly->SetPoints(points);
        poly->SetPolys(tris);
        vtkNew<vtkPolyDataMapper> meshMapper;
        meshMapper->SetInputData(poly);
        vtkNew<vtkActor> mesh;
        mesh->SetMapper(meshMapper);
        mesh->GetProperty()->SetColor(0.6, 0.6, 0.65);
        mesh->GetProperty()->SetOpacity(0.25);
        renderer->AddActor(mesh);
    }

    vtkNew<vtkRenderWindow> window;
    window->SetOffScreenRendering(1);
    window->AddRenderer(renderer);
    window->SetSize(opt.width, opt.height);
    // Frame the voxels (outlines of upper levels may reach far past them),
    // seen from the front (+z), a little from the right and above.
    double bounds[6];
    voxelMapper->Update();
    voxelMapper->GetBounds(bounds);
    renderer->ResetCamera(bounds);
    vtkCamera* cam = renderer->GetActiveCamera();
    cam->Azimuth(25);
    cam->Elevation(18);
    cam->OrthogonalizeViewUp();
    renderer->ResetCamera(bounds);
    cam->Dolly(1.1);
    renderer->ResetCameraClippingRange();
    window->Render();

    vtkNew<vtkWindowToImageFilter> grab;
    grab->SetInput(window);
    grab->ReadFrontBufferOff();
    grab->Update();
    vtkNew<vtkPNGWriter> png;
    png->SetInputConnection(grab->GetOutputPort());
    writeAtomically(path, [&](const std::string& tmp) {
        png->SetFileName(tmp.c_str());
        png->Write();
        if (png->GetErrorCode() != 0) throw IoError(fmt::format("{}: VTK could not write the PNG", path));
    });
}

} // namespace svo::app

extern "C" __attribute__((visibility("default"))) const svo::app::VtkExport* SVO_VTK_MODULE_ENTRY()
{
    static const svo::app::VtkExport functions{&svo::app::writeHyperTreeGrid, &svo::app::writeVoxelCells,
                                               &svo::app::writeNodeOutlines, &svo::app::renderPicture};
    return &functions;
}
