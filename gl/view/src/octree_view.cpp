#include "svo/gl/octree_view.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <fmt/format.h>

#include "svo/gl/gl_api.h"
#include "light_volume.h"
#include "svo/gl/buffer.h"
#include "svo/gl/handle.h"
#include "svo/gl/loop_cut_counter.h"
#include "svo/gl/program.h"
#include "svo/gl/texture_2d.h"
#include "svo/gl/timer_query.h"
#include "svo/gl/vertex_array.h"
#include "svo/core/error.h"
#include "view_layout.h"
#include "view_shaders.h"

namespace svo::gl {

namespace {

using Mat4 = std::array<double, 16>; // column-major, as GLSL

Vec3d cross(const Vec3d& a, const Vec3d& b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double dot(const Vec3d& a, const Vec3d& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(const Vec3d& a) { return std::sqrt(dot(a, a)); }

Mat4 multiply(const Mat4& a, const Mat4& b)
{
    Mat4 r{};
    for (int c = 0; c < 4; ++c)
        for (int row = 0; row < 4; ++row) {
            double s = 0;
            for (int k = 0; k < 4; ++k) s += a[k * 4 + row] * b[c * 4 + k];
            r[c * 4 + row] = s;
        }
    return r;
}

/// Inverse by cofactors (the matrices here are well conditioned: a view and a projection).
Mat4 inverse(const Mat4& m)
{
    Mat4 inv{};
    inv[0] = m[5] * m[10] * m[15] - m[5] * m[11] * m[14] - m[9] * m[6] * m[15] + m[9] * m[7] * m[14] +
             m[13] * m[6] * m[11] - m[13] * m[7] * m[10];
    inv[4] = -m[4] * m[10] * m[15] + m[4] * m[11] * m[14] + m[8] * m[6] * m[15] - m[8] * m[7] * m[14] -
             m[12] * m[6] * m[11] + m[12] * m[7] * m[10];
    inv[8] = m[4] * m[9] * m[15] - m[4] * m[11] * m[13] - m[8] * m[5] * m[15] + m[8] * m[7] * m[13] +
             m[12] * m[5] * m[11] - m[12] * m[7] * m[9];
    inv[12] = -m[4] * m[9] * m[14] + m[4] * m[10] * m[13] + m[8] * m[5] * m[14] - m[8] * m[6] * m[13] -
              m[12] * m[5] * m[10] + m[12] * m[6] * m[9];
    inv[1] = -m[1] * m[10] * m[15] + m[1] * m[11] * m[14] + m[9] * m[2] * m[15] - m[9] * m[3] * m[14] -
             m[13] * m[2] * m[11] + m[13] * m[3] * m[10];
    inv[5] = m[0] * m[10] * m[15] - m[0] * m[11] * m[14] - m[8] * m[2] * m[15] + m[8] * m[3] * m[14] +
             m[12] * m[2] * m[11] - m[12] * m[3] * m[10];
    inv[9] = -m[0] * m[9] * m[15] + m[0] * m[11] * m[13] + m[8] * m[1] * m[15] - m[8] * m[3] * m[13] -
             m[12] * m[1] * m[11] + m[12] * m[3] * m[9];
    inv[13] = m[0] * m[9] * m[14] - m[0] * m[10] * m[13] - m[8] * m[1] * m[14] + m[8] * m[2] * m[13] +
              m[12] * m[1] * m[10] - m[12] * m[2] * m[9];
    inv[2] = m[1] * m[6] * m[15] - m[1] * m[7] * m[14] - m[5] * m[2] * m[15] + m[5] * m[3] * m[14] +
             m[13] * m[2] * m[7] - m[13] * m[3] * m[6];
    inv[6] = -m[0] * m[6] * m[15] + m[0] * m[7] * m[14] + m[4] * m[2] * m[15] - m[4] * m[3] * m[14] -
             m[12] * m[2] * m[7] + m[12] * m[3] * m[6];
    inv[10] = m[0] * m[5] * m[15] - m[0] * m[7] * m[13] - m[4] * m[1] * m[15] + m[4] * m[3] * m[13] +
              m[12] * m[1] * m[7] - m[12] * m[3] * m[5];
    inv[14] = -m[0] * m[5] * m[14] + m[0] * m[6] * m[13] + m[4] * m[1] * m[14] - m[4] * m[2] * m[13] -
              m[12] * m[1] * m[6] + m[12] * m[2] * m[5];
    inv[3] = -m[1] * m[6] * m[11] + m[1] * m[7] * m[10] + m[5] * m[2] * m[11] - m[5] * m[3] * m[10] -
             m[9] * m[2] * m[7] + m[9] * m[3] * m[6];
    inv[7] = m[0] * m[6] * m[11] - m[0] * m[7] * m[10] - m[4] * m[2] * m[11] + m[4] * m[3] * m[10] +
             m[8] * m[2] * m[7] - m[8] * m[3] * m[6];
    inv[11] = -m[0] * m[5] * m[11] + m[0] * m[7] * m[9] + m[4] * m[1] * m[11] - m[4] * m[3] * m[9] -
              m[8] * m[1] * m[7] + m[8] * m[3] * m[5];
    inv[15] = m[0] * m[5] * m[10] - m[0] * m[6] * m[9] - m[4] * m[1] * m[10] + m[4] * m[2] * m[9] +
              m[8] * m[1] * m[6] - m[8] * m[2] * m[5];
    const double det = m[0] * inv[0] + m[1] * inv[4] + m[2] * inv[8] + m[3] * inv[12];
    if (!(std::abs(det) > 0)) throw InvalidInput("octree view: the camera's matrix cannot be inverted");
    for (double& v : inv) v /= det;
    return inv;
}

std::array<float, 16> toFloat(const Mat4& m)
{
    std::array<float, 16> f{};
    for (int i = 0; i < 16; ++i) f[i] = float(m[i]);
    return f;
}

/// World -> cell space (local + 1/2: voxel v covers [v, v + 1]).
Vec3d toCell(const GridSpec& grid, const Vec3d& world)
{
    const Vec3d l = grid.toLocal(world);
    return {l.x + 0.5, l.y + 0.5, l.z + 0.5};
}

struct CellCamera {
    Mat4 viewProjection, inverseViewProjection;
    Vec3d eye, forward;
};

/// The camera's matrices in cell space, with near and far planes around the grid.
CellCamera cellCamera(const GridSpec& grid, const ViewCamera& camera, int width, int height)
{
    const Vec3d eye = toCell(grid, camera.eye), target = toCell(grid, camera.target);
    const Vec3d toTarget = target - eye;
    if (!(length(toTarget) > 0)) throw InvalidInput("octree view: the camera's eye and target coincide");
    const Vec3d f = (1.0 / length(toTarget)) * toTarget;
    Vec3d r = cross(f, camera.up);
    if (!(length(r) > 1e-9 * length(camera.up))) throw InvalidInput("octree view: the camera's up is along its view direction");
    r = (1.0 / length(r)) * r;
    const Vec3d u = cross(r, f);
    Mat4 view{r.x, u.x, -f.x, 0, r.y, u.y, -f.y, 0, r.z, u.z, -f.z, 0, -dot(r, eye), -dot(u, eye), dot(f, eye), 1};

    // Near and far enclose the grid's bounding sphere.
    const Vec3d dims{double(grid.dims[0]), double(grid.dims[1]), double(grid.dims[2])};
    const Vec3d centre = 0.5 * dims;
    const double radius = 0.5 * length(dims) * 1.01 + 1.0;
    const double along = dot(centre - eye, f);
    const double aspect = double(width) / double(height);
    Mat4 proj{};
    if (camera.orthographic) {
        checkOrthographicHeight(camera.height, "octree view: orthographic height");
        const double h = camera.height / grid.voxelSize, w = h * aspect;
        const double n = along - radius, fa = along + radius;
        proj = {2 / w, 0, 0, 0, 0, 2 / h, 0, 0, 0, 0, -2 / (fa - n), 0, 0, 0, -(fa + n) / (fa - n), 1};
    } else {
        checkFieldOfView(camera.fovYDegrees, "octree view: field of view");
        const double n = std::max(along - radius, radius * 1e-4), fa = std::max(along + radius, 2 * n);
        const double t = 1.0 / std::tan(camera.fovYDegrees * M_PI / 360.0);
        proj = {t / aspect, 0, 0, 0, 0, t, 0, 0, 0, 0, (fa + n) / (n - fa), -1, 0, 0, 2 * fa * n / (n - fa), 0};
    }
    CellCamera c;
    c.viewProjection = multiply(proj, view);
    c.inverseViewProjection = inverse(c.viewProjection);
    c.eye = eye;
    c.forward = f;
    return c;
}

void deleteRenderbuffer(GLuint n) { glDeleteRenderbuffers(1, &n); }

/// Colour and depth renderbuffers on a framebuffer: the offscreen target.
struct Target {
    Target(int width, int height)
    {
        GLuint n[2] = {};
        glCreateRenderbuffers(2, n);
        color = Handle<deleteRenderbuffer>(n[0]);
        depth = Handle<deleteRenderbuffer>(n[1]);
        glNamedRenderbufferStorage(n[0], GL_RGBA8, width, height);
        glNamedRenderbufferStorage(n[1], GL_DEPTH_COMPONENT24, width, height);
        GLuint f = 0;
        glCreateFramebuffers(1, &f);
        fbo = Handle<detail::deleteFramebuffer>(f);
        glNamedFramebufferRenderbuffer(f, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, n[0]);
        glNamedFramebufferRenderbuffer(f, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, n[1]);
        checkGl(fmt::format("allocating a {} x {} picture", width, height).c_str());
        const GLenum status = glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw DeviceError(fmt::format("octree view: the {} x {} framebuffer is incomplete (0x{:04x})", width, height, status));
    }
    Handle<deleteRenderbuffer> color, depth;
    Handle<detail::deleteFramebuffer> fbo;
};

/// The mesh's surface per pixel (ViewLayers::surface = Mesh): the index + 1
/// of the triangle it sees, a texture the voxel pass reads, and a depth
/// buffer to keep the nearest triangle.
struct SurfaceTarget {
    SurfaceTarget(int width, int height) : triangle("mesh surface triangles (view)", GL_R32UI, width, height)
    {
        GLuint d = 0;
        glCreateRenderbuffers(1, &d);
        depth = Handle<deleteRenderbuffer>(d);
        glNamedRenderbufferStorage(d, GL_DEPTH_COMPONENT32F, width, height);
        GLuint f = 0;
        glCreateFramebuffers(1, &f);
        fbo = Handle<detail::deleteFramebuffer>(f);
        glNamedFramebufferTexture(f, GL_COLOR_ATTACHMENT0, triangle.get(), 0);
        glNamedFramebufferRenderbuffer(f, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, d);
        glNamedFramebufferDrawBuffer(f, GL_COLOR_ATTACHMENT0);
        checkGl(fmt::format("allocating the mesh's {} x {} surface buffers", width, height).c_str());
        const GLenum status = glCheckNamedFramebufferStatus(f, GL_FRAMEBUFFER);
        if (status != GL_FRAMEBUFFER_COMPLETE)
            throw DeviceError(fmt::format("octree view: the mesh's {} x {} surface framebuffer is incomplete (0x{:04x})",
                                          width, height, status));
    }
    Texture2D triangle; ///< each pixel's triangle + 1, 0 where none (view_surface.frag)
    Handle<deleteRenderbuffer> depth;
    Handle<detail::deleteFramebuffer> fbo;
};

} // namespace

std::array<Vec3d, 2> gridWorldBox(const GridSpec& grid)
{
    std::array<Vec3d, 2> box;
    const auto t = grid.translation();
    for (int i = 0; i < 3; ++i) {
        const double lo = double(grid.anchor[size_t(i)]) - 0.5;
        box[0][i] = grid.voxelSize * lo + t[size_t(i)];
        box[1][i] = grid.voxelSize * (lo + double(grid.dims[size_t(i)])) + t[size_t(i)];
    }
    return box;
}

ViewCamera frameBox(const std::array<Vec3d, 2>& box, const Vec3d& direction, bool orthographic, double aspect)
{
    if (!(length(direction) > 0)) throw InvalidInput("octree view: a view direction must not be zero");
    const Vec3d dir = (1.0 / length(direction)) * direction;
    const Vec3d centre = 0.5 * (box[0] + box[1]);
    const double radius = std::max(0.5 * length(box[1] - box[0]), 1e-30);
    ViewCamera c;
    c.orthographic = orthographic;
    c.target = centre;
    // Up is +y unless the view looks along y; then -z (x to the right from above).
    c.up = std::abs(dir.y) > 0.99 ? Vec3d{0, 0, dir.y > 0 ? 1.0 : -1.0} : Vec3d{0, 1, 0};
    const double fit = 1.05 * radius;
    if (orthographic) {
        c.height = 2 * fit / std::min(aspect, 1.0);
        c.eye = centre - 3 * radius * dir;
    } else {
        const double half = c.fovYDegrees * M_PI / 360.0;
        const double halfX = std::atan(std::tan(half) * aspect);
        c.eye = centre - (fit / std::sin(std::min(half, halfX))) * dir;
    }
    return c;
}

ViewCamera namedView(const std::array<Vec3d, 2>& box, const std::string& name, double aspect)
{
    if (name == "front") return frameBox(box, {-0.35, -0.3, -1.0}, false, aspect);
    const std::pair<const char*, Vec3d> axes[] = {{"+x", {-1, 0, 0}}, {"-x", {1, 0, 0}}, {"+y", {0, -1, 0}},
                                                  {"-y", {0, 1, 0}},  {"+z", {0, 0, -1}}, {"-z", {0, 0, 1}}};
    for (const auto& [axis, dir] : axes)
        if (name == axis) return frameBox(box, dir, true, aspect);
    throw InvalidInput(std::vector<Error::Part>{Error::option("svo::gl::namedView", "view"),
                                                fmt::format(" '{}': expected front, +x, -x, +y, -y, +z or -z", name)});
}

ViewCamera roomView(const std::array<Vec3d, 2>& box, double aspect, double fovYDegrees)
{
    if (!(fovYDegrees > 0 && fovYDegrees < 180) || !(aspect > 0))
        throw InvalidInput(fmt::format("octree view: a room's view needs a field of view in (0, 180) degrees and a "
                                       "positive aspect, not {} and {}",
                                       fovYDegrees, aspect));
    ViewCamera c;
    c.orthographic = false;
    c.fovYDegrees = fovYDegrees;
    c.up = {0, 1, 0};
    const Vec3d centre = 0.5 * (box[0] + box[1]);
    // The open side's half height, or its half width seen through a narrower picture.
    const double half = std::max(0.5 * (box[1].y - box[0].y), 0.5 * (box[1].x - box[0].x) / aspect);
    const double back = half / std::tan(fovYDegrees * M_PI / 360.0);
    c.eye = {centre.x, centre.y, box[1].z + back};
    c.target = centre;
    return c;
}

Lights defaultLights(const std::array<Vec3d, 2>& box, bool inside)
{
    Lights l;
    const Vec3d centre = 0.5 * (box[0] + box[1]);
    if (inside) {
        const Vec3d at{centre.x, box[1].y - 0.1 * (box[1].y - box[0].y), centre.z};
        const double d2 = dot(at - centre, at - centre);
        const double i = M_PI * (d2 > 0 ? d2 : 1.0);
        l.point.push_back({at, {i, i, i}});
    } else {
        l.directional.push_back({{0.4, -1.0, -0.6}, {M_PI, M_PI, M_PI}});
    }
    return l;
}

// The single-option rules (ambient_occlusion.h); checkAmbientOcclusion runs them on a struct's fields.
void checkAoConeCount(int64_t cones, const std::string& name)
{
    if (cones < 0 || cones > 16) throw InvalidInput(name, fmt::format("{}: AO takes 0 (none) to 16 cones", cones));
}

void checkConeAperture(double degrees, const std::string& name)
{
    if (!(degrees > 0 && degrees < 180)) // NaN fails too
        throw InvalidInput(name, fmt::format("{}: a cone's aperture is between 0 and 180 degrees", degrees));
}

void checkConeOffset(double offset, const std::string& name)
{
    if (!(offset >= 0 && offset < 1e6))
        throw InvalidInput(name, fmt::format("{}: cones start 0 or more out of the surface, less than 1e6", offset));
}

void checkAoConeDistance(double voxels, const std::string& name)
{
    if (!(voxels > 0 && voxels <= 1e7))
        throw InvalidInput(name, fmt::format("{}: AO cones stop a positive distance away, at most 1e7 voxels", voxels));
}

void checkConeStep(double share, const std::string& name)
{
    if (!(share > 0 && share <= 1))
        throw InvalidInput(name, fmt::format("{}: a cone's step is a share of its width in (0, 1]", share));
}

void checkAmbientOcclusion(const AmbientOcclusion& ao)
{
    // The single-option rules, naming the field (a front end names its flag or keyword).
    checkAoConeCount(ao.cones, "AmbientOcclusion::cones");
    if (ao.only && ao.cones == 0)
        throw InvalidInput("AmbientOcclusion::cones", "0: drawing AO alone needs 1 or more cones");
    checkConeAperture(ao.apertureDegrees, "AmbientOcclusion::apertureDegrees");
    checkConeOffset(ao.offset, "AmbientOcclusion::offset");
    checkAoConeDistance(ao.distance, "AmbientOcclusion::distance");
    checkConeStep(ao.step, "AmbientOcclusion::step");
    if (ao.source == AmbientOcclusion::Source::Volume)
        checkVolumeResolution(ao.volumeResolution, "AmbientOcclusion::volumeResolution");
}

namespace {

/// What a view holds: its octree on the GPU, and the caches drawing fills.
/// It is OctreeView::Impl, whose name only OctreeView's members may use;
/// the file's helpers take it by this one.
struct ViewState {
    GridSpec grid;
    uint32_t brickLevel = 0;
    std::vector<uint32_t> levelStart;
    Buffer nodes, bricks, origins;
    Buffer opacity; ///< 2 floats per node, ambient occlusion's mip-map: the Average and the Max filter's opacity
    /// Attribute channels, voxel order, when the octree has them; voxelStart
    /// gives each brick's first voxel.
    std::optional<Buffer> voxelStart, normals, colors, triangles;
    std::optional<Buffer> meshVertices, meshIndices;
    std::optional<VertexArray> meshArray;
    uint64_t meshIndexCount = 0;
    VertexArray empty; ///< attribute-less draws (full-screen pass, outlines)
    /// The lighting volume, made when a lit frame (or AO from the volume)
    /// first needs it and kept while the lights stay (drawing is const; the
    /// cache is not). AO reads any volume of its resolution, lit or not.
    mutable std::optional<LightVolumeTextures> light;
    /// The voxel pass's pixels (view_voxels.comp), kept while the picture's size stays.
    mutable std::optional<Texture2D> pixels;
    /// The mesh's triangle per pixel (Surface::Mesh), kept likewise.
    mutable std::optional<SurfaceTarget> surface;
    /// Interleaved cones: each pixel's gathered light and its cones' start
    /// (view_resolve.comp), kept likewise.
    mutable std::optional<Texture2D> gathered, points;
    /// The voxel pass's pixels whose loops the driver cut short, last frame.
    LoopCutCounter loopCut;
    mutable uint32_t cutPixels = 0;

    const Texture2D& pixelImage(int width, int height) const
    {
        if (!pixels || pixels->width() != width || pixels->height() != height) {
            pixels.reset();
            pixels.emplace("view's pixels", GL_RGBA32F, width, height);
        }
        return *pixels;
    }

    /// Binds the interleaved cones' images, made at this size if need be.
    void bindInterleaveImages(int width, int height) const
    {
        if (!gathered || gathered->width() != width || gathered->height() != height) {
            gathered.reset();
            points.reset();
            gathered.emplace("view's gathered light", GL_RGBA32UI, width, height);
            points.emplace("view's cone starts", GL_RGBA32F, width, height);
        }
        gathered->bindImage(SVO_IMAGE_VIEW_GATHER, GL_READ_WRITE, GL_RGBA32UI);
        points->bindImage(SVO_IMAGE_VIEW_POINTS, GL_READ_WRITE, GL_RGBA32F);
    }

    const SurfaceTarget& surfaceTarget(int width, int height) const
    {
        if (!surface || surface->triangle.width() != width || surface->triangle.height() != height) {
            surface.reset();
            surface.emplace(width, height);
        }
        return *surface;
    }

    ViewBuffers buffers() const
    {
        return {grid, brickLevel, nodes, bricks, voxelStart ? &*voxelStart : nullptr, normals ? &*normals : nullptr,
                colors ? &*colors : nullptr};
    }
    /// The volume `l` needs: the cached one, re-injected after the lights
    /// changed, or a new one.
    const LightVolumeTextures& lightVolume(const Context& context, const Illumination& l) const
    {
        if (light && light->lit && sameInjection(light->built, l)) {
        } else if (light && light->lit && sameVolume(light->built, l)) {
            injectLight(context, buffers(), l, *light);
        } else {
            light.reset(); // the old textures go before the new ones are allocated
            light.emplace(buildLightVolume(context, buffers(), l));
        }
        if (l.clearance) buildClearance(context, *light); // once a volume: geometry alone
        return *light;
    }
    /// The opacity volume of `resolution` texels at most, for AO.
    const LightVolumeTextures& opacityVolume(const Context& context, uint32_t resolution) const
    {
        if (texelVoxels(grid, resolution) > 8) // a texel holds at most 8³ voxels
            throw Unsupported(std::vector<Error::Part>{
                fmt::format("octree view: ambient occlusion: a grid {} voxels wide needs a volume of more than {} "
                            "texels a side (",
                            *std::max_element(grid.dims.begin(), grid.dims.end()), resolution),
                Error::option("AmbientOcclusion::volumeResolution"), "), or the octree's opacity (",
                Error::option("AmbientOcclusion::Source::Octree"), ")"});
        checkVolumeResolution(grid, resolution, "ambient occlusion: volume resolution");
        if (light && light->texelVoxels == texelVoxels(grid, resolution) && !light->opticalDepth) return *light;
        light.reset();
        light.emplace(buildOpacityVolume(context, buffers(), resolution));
        return *light;
    }
};

} // namespace

struct OctreeView::Impl : ViewState {};

namespace {

/// Uploads the octree (and mesh) into a new `State`: OctreeView::Impl, which
/// only OctreeView's members may name, so they name it here.
template <class State>
std::unique_ptr<State> upload(const Context& context, const Octree& octree, const TriangleMesh* mesh)
{
    if (octree.levelStart.size() != size_t(octree.brickLevel) + 2 || octree.levelStart.back() != octree.nodes.size() ||
        octree.nodes.empty())
        throw InvalidInput("octree view: the octree's level ranges do not match its nodes");
    checkGl("the GL work before uploading an octree to view");
    auto impl = std::make_unique<State>();
    impl->grid = octree.grid;
    impl->brickLevel = octree.brickLevel;
    impl->levelStart = octree.levelStart;
    impl->nodes = Buffer("octree nodes (view)", octree.nodes.size() * sizeof(OctreeNode), octree.nodes.data(), 0);
    impl->bricks = Buffer("octree bricks (view)", std::max<size_t>(octree.bricks.size(), 1) * sizeof(Brick),
                          octree.bricks.empty() ? nullptr : octree.bricks.data(), 0);
    impl->origins = Buffer("node origins (view)", octree.nodes.size() * 16);
    // Opacity per node, from the bricks up, two filters side by side
    // (AmbientOcclusion::Filter): the voxels a node holds over the voxels of
    // one face of its box, at most 1 (svo's octrees hold surfaces, and a
    // surface crossing a box of w³ voxels fills about w² of them: the volume
    // share, 1/w, would let every wall leak at coarse levels); and that or
    // the most opaque child's (at the brick level, 4³ block's) opacity.
    std::vector<uint64_t> count(octree.nodes.size(), 0);
    std::vector<float> opacity(2 * octree.nodes.size(), 0.0f);
    for (uint32_t level = octree.brickLevel + 1; level-- > 0;) {
        const double width = double(8u << (octree.brickLevel - level));
        for (uint32_t i = octree.levelStart[level]; i < octree.levelStart[level + 1]; ++i) {
            const OctreeNode& n = octree.nodes[i];
            if (!n.childMask) continue;
            float most = 0;
            if (level == octree.brickLevel) {
                const Brick& b = octree.bricks[n.child];
                count[i] = b.count();
                for (uint32_t block = 0; block < 8; ++block) { // 4³ blocks: x, y, z halves
                    const uint32_t x0 = 4 * (block & 1), y0 = 2 * (block & 2), z0 = (block & 4);
                    uint32_t k = 0;
                    for (uint32_t x = x0; x < x0 + 4; ++x)
                        k += uint32_t(__builtin_popcountll(b.words[x] & (0x0F0F0F0FULL << (8 * y0 + z0))));
                    most = std::max(most, std::min(1.0f, float(k) / 16.0f));
                }
            } else {
                for (uint32_t c = 0; c < 8; ++c)
                    if (n.childMask >> c & 1) {
                        count[i] += count[n.child + c];
                        most = std::max(most, opacity[2 * (n.child + c) + 1]);
                    }
            }
            opacity[2 * i] = float(std::min(1.0, double(count[i]) / (width * width)));
            opacity[2 * i + 1] = std::max(opacity[2 * i], most);
        }
    }
    impl->opacity = Buffer("node occupancy (view)", opacity.size() * 4, opacity.data(), 0);
    impl->origins.clearUint(0); // the root's origin; the pass writes every occupied node's

    const Program& origins = context.program(viewShaders(), {"view_origins.comp"});
    impl->nodes.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_NODES);
    impl->origins.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_ORIGINS);
    constexpr uint32_t kGroup = 256, kMaxGroups = 65535;
    for (uint32_t level = 0; level < octree.brickLevel; ++level) {
        const uint32_t first = octree.levelStart[level], count = octree.levelStart[level + 1] - first;
        origins.set("uChildSize", uint32_t(8u << (octree.brickLevel - level - 1)));
        for (uint32_t done = 0; done < count; done += kGroup * kMaxGroups) {
            const uint32_t n = std::min(count - done, kGroup * kMaxGroups);
            origins.set("uFirst", first + done);
            origins.set("uCount", n);
            origins.dispatch((n + kGroup - 1) / kGroup);
            glMemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT);
        }
    }

    if (!octree.attributes.empty()) {
        const std::vector<uint64_t> offsets = brickVoxelOffsets(octree);
        if (offsets.back() >= (uint64_t(1) << 32))
            throw Unsupported("octree view: attribute colours need fewer than 2^32 voxels");
        const std::vector<uint32_t> start(offsets.begin(), offsets.end());
        impl->voxelStart.emplace("brick voxel starts (view)", start.size() * 4, start.data(), 0);
        const VoxelAttributes& a = octree.attributes;
        if (!a.normals.empty()) impl->normals.emplace("voxel normals (view)", a.normals.size() * 12, a.normals.data(), 0);
        if (!a.colors.empty()) impl->colors.emplace("voxel colours (view)", a.colors.size() * 12, a.colors.data(), 0);
        if (!a.triangles.empty())
            impl->triangles.emplace("voxel triangles (view)", a.triangles.size() * 4, a.triangles.data(), 0);
    }

    if (mesh && !mesh->triangles.empty()) {
        std::vector<Vec3f> cells = localPositionsFloat(*mesh, octree.grid);
        for (Vec3f& p : cells) p = {p.x + 0.5f, p.y + 0.5f, p.z + 0.5f};
        impl->meshVertices.emplace("mesh vertices (view)", cells.size() * sizeof(Vec3f), cells.data(), 0);
        impl->meshIndices.emplace("mesh triangles (view)", mesh->triangles.size() * 12, mesh->triangles.data(), 0);
        impl->meshArray.emplace();
        impl->meshArray->setPositions(*impl->meshVertices, 0);
        impl->meshArray->setIndices(*impl->meshIndices);
        impl->meshIndexCount = 3 * uint64_t(mesh->triangles.size());
    }
    checkGl("uploading an octree to view");
    return impl;
}

} // namespace

OctreeView::OctreeView(const Context& context, const Octree& octree, const TriangleMesh* mesh) : context_(context)
{
    Context::Scope scope(context_);
    impl_ = upload<Impl>(context_, octree, mesh);
}

OctreeView::~OctreeView()
{
    Context::Scope scope(context_);
    impl_.reset();
}

void OctreeView::setOctree(const Octree& octree, const TriangleMesh* mesh)
{
    Context::Scope scope(context_);
    auto next = upload<Impl>(context_, octree, mesh);
    impl_ = std::move(next);
}

const GridSpec& OctreeView::grid() const { return impl_->grid; }
uint32_t OctreeView::brickLevel() const { return impl_->brickLevel; }

namespace {

void checkSize(int width, int height)
{
    GLint maxSize = 0;
    glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &maxSize);
    if (width < 1 || height < 1 || width > maxSize || height > maxSize)
        throw InvalidInput(fmt::format("octree view: a {} x {} picture is outside 1 .. {} pixels per side", width, height, maxSize));
}

/// The frame's fixed GL state, the framebuffer cleared, and the octree's buffers bound.
void beginFrame(const ViewState& v, int width, int height)
{
    glViewport(0, 0, width, height);
    const auto& bg = ViewColors::background;
    glClearColor(bg[0], bg[1], bg[2], 1.0f);
    glClearDepth(1.0);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    glDisable(GL_CULL_FACE);
    glDisable(GL_SCISSOR_TEST);
    glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    v.nodes.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_NODES);
    v.bricks.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_BRICKS);
    v.origins.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_ORIGINS);
}

/// The mesh into its own framebuffer: the triangle each pixel sees, where
/// the voxel pass meets it with the pixel's ray and shades (Surface::Mesh).
void drawMeshSurface(const Context& context, const ViewState& v, const std::array<float, 16>& viewProjection,
                     int width, int height)
{
    if (!v.meshArray) throw InvalidInput("octree view: shading the mesh's surface needs the mesh, and the view has none");
    GLint drawn = 0;
    glGetIntegerv(GL_DRAW_FRAMEBUFFER_BINDING, &drawn);
    const SurfaceTarget& target = v.surfaceTarget(width, height);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, target.fbo.get());
    const GLuint none[4] = {0, 0, 0, 0};
    glClearNamedFramebufferuiv(target.fbo.get(), GL_COLOR, 0, none);
    glClear(GL_DEPTH_BUFFER_BIT);
    const Program& p = context.program(viewShaders(), {"view_mesh.vert", "view_surface.frag"});
    p.setMatrix("uViewProjection", viewProjection.data());
    p.use();
    v.meshArray->bind();
    glDrawElements(GL_TRIANGLES, GLsizei(v.meshIndexCount), GL_UNSIGNED_INT, nullptr);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, GLuint(drawn));
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    checkGl("drawing the mesh's surface");
}

/// Binds the attribute channel the voxels are coloured by, if any; returns
/// the shader's colour mode (SVO_VIEW_COLOR_*).
int bindVoxelColor(const ViewState& v, VoxelColor color)
{
    const std::optional<Buffer>* channel = nullptr;
    int mode = SVO_VIEW_COLOR_FLAT;
    switch (color) {
    case VoxelColor::Flat: break;
    case VoxelColor::Normal: channel = &v.normals, mode = SVO_VIEW_COLOR_NORMAL; break;
    case VoxelColor::Color: channel = &v.colors, mode = SVO_VIEW_COLOR_RGB; break;
    case VoxelColor::Triangle: channel = &v.triangles, mode = SVO_VIEW_COLOR_TRIANGLE; break;
    }
    if (channel) {
        if (!*channel) throw InvalidInput("octree view: the octree has no such attribute channel to colour voxels by");
        (*channel)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_ATTRIBUTE);
        v.voxelStart->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_VOXEL_START);
    }
    return mode;
}

/// The volume the voxel pass gathers from: the lighting volume when lit,
/// else the opacity volume for AO's cones (made on first use).
void bindVoxelLight(const Context& context, const ViewState& v, const Program& p, const Illumination& light,
                    const AmbientOcclusion& ao)
{
    const bool aoVolume = ao.source == AmbientOcclusion::Source::Volume;
    if (light.mode != Illumination::Mode::Off) {
        bindLightVolume(p, v.lightVolume(context, light), v.buffers(), light);
        p.set("uExposure", float(light.exposure));
        p.set("uGamma", float(light.gamma));
    } else if (aoVolume) {
        // Cones through the opacity volume: the gather's uniforms; with no
        // cones the volume is neither built nor sampled.
        if (ao.cones > 0)
            bindOpacityVolume(p, v.opacityVolume(context, ao.volumeResolution), v.grid, ao.cones,
                              ao.apertureDegrees, ao.offset, ao.distance, ao.step);
        else
            p.set("uCones", 0);
        if (v.normals) {
            v.normals->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_NORMALS);
            v.voxelStart->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_VOXEL_START);
        }
    }
}

/// The voxel pass's uniforms past the volume's: the mesh surface it meets,
/// the lighting and AO modes, the camera, the grid and the colour.
void setVoxelUniforms(const ViewState& v, const Program& p, const ViewLayers& layers, bool shadeMesh, int colorMode,
                      const std::array<float, 16>& viewProjection, const std::array<float, 16>& inverseViewProjection,
                      int width, int height)
{
    const AmbientOcclusion& ao = layers.ao;
    const Illumination& light = layers.light;
    const bool aoVolume = ao.source == AmbientOcclusion::Source::Volume;
    p.set("uSurface", shadeMesh ? 1u : 0u);
    if (shadeMesh) {
        v.surface->triangle.bindTexture(SVO_UNIT_VIEW_SURFACE_TRIANGLE);
        v.meshVertices->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_MESH_POSITIONS);
        v.meshIndices->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_MESH_TRIANGLES);
    }
    p.set("uAoVolume", aoVolume ? 1u : 0u);
    p.set("uAoNormals", v.normals ? 1u : 0u);
    p.set("uLightMode", light.mode == Illumination::Mode::Off      ? 0
                        : light.mode == Illumination::Mode::Direct ? 1
                                                                   : 2);
    p.set("uColorMode", colorMode);
    p.set("uAoCones", ao.cones);
    p.set("uAoTanHalf", float(std::tan(ao.apertureDegrees * M_PI / 360.0)));
    p.set("uAoOffset", float(ao.offset));
    p.set("uAoDistance", float(ao.distance));
    p.set("uAoStep", float(ao.step));
    p.set("uAoFilter", ao.filter == AmbientOcclusion::Filter::Max ? 1u : 0u);
    p.set("uAoOnly", ao.only ? 1u : 0u);
    p.setMatrix("uInverseViewProjection", inverseViewProjection.data());
    p.setMatrix("uViewProjection", viewProjection.data());
    p.set("uViewport", float(width), float(height));
    p.set("uBrickLevel", v.brickLevel);
    p.set("uDims", int(v.grid.dims[0]), int(v.grid.dims[1]), int(v.grid.dims[2]));
    const auto& c = shadeMesh ? ViewColors::mesh : ViewColors::voxel;
    p.set("uColor", c[0], c[1], c[2]);
}

/// Whether the cones' light is gathered apart and averaged over 4x4 pixels
/// by a second pass (view_resolve.comp), which also composes.
bool interleavesCones(const Illumination& light, const AmbientOcclusion& ao)
{
    const bool aoVolume = ao.source == AmbientOcclusion::Source::Volume;
    return light.mode == Illumination::Mode::Global
               ? light.interleave
               : light.mode == Illumination::Mode::Off && aoVolume && ao.cones > 0 && ao.interleave;
}

/// The rays in a compute pass (view_voxels.comp) into the pixel image, which it returns.
const Texture2D& castRays(const Context& context, const ViewState& v, const Program& p, bool interleave, int width,
                          int height)
{
    p.set("uInterleave", interleave ? 1u : 0u);
    const Texture2D& pixels = v.pixelImage(width, height);
    pixels.bindImage(SVO_IMAGE_VIEW_PIXELS, interleave ? GL_READ_WRITE : GL_WRITE_ONLY, GL_RGBA32F);
    if (interleave) v.bindInterleaveImages(width, height);
    v.loopCut.arm(p, SVO_BIND_VIEW_LOOP_CUT, context.info().loopLimit);
    p.dispatch((uint32_t(width) + 7) / 8, (uint32_t(height) + 7) / 8);
    checkGl("casting the voxels' rays");
    return pixels;
}

/// Averages the interleaved cones' light over 4x4 pixels and composes (view_resolve.comp).
void resolveInterleavedCones(const Context& context, const Illumination& light, const AmbientOcclusion& ao, int width,
                             int height)
{
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    const Program& r = context.program(viewShaders(), {"view_resolve.comp"});
    r.set("uLightMode", light.mode == Illumination::Mode::Global ? 2 : 0);
    r.set("uAoOnly", ao.only ? 1u : 0u);
    r.set("uExposure", float(light.exposure));
    r.set("uGamma", float(light.gamma));
    r.set("uViewport", float(width), float(height));
    r.set("uPlaneTolerance", 1.0f);
    r.dispatch((uint32_t(width) + 7) / 8, (uint32_t(height) + 7) / 8);
    checkGl("averaging the interleaved cones");
}

/// The pixels and depths into the framebuffer by a full-screen triangle
/// (view_pixels.frag); counts the rays the driver cut short.
void drawPixels(const Context& context, const ViewState& v, const Texture2D& pixels)
{
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT);
    v.cutPixels = v.loopCut.count();
    const Program& copy = context.program(viewShaders(), {"view_fullscreen.vert", "view_pixels.frag"});
    pixels.bindTexture(SVO_UNIT_VIEW_PIXELS);
    copy.use();
    v.empty.bind();
    glDrawArrays(GL_TRIANGLES, 0, 3);
    checkGl("drawing the voxels");
}

/// The voxels: rays cast per pixel in a compute pass, their cones' light
/// resolved when interleaved, then their pixels and depths drawn.
void drawVoxels(const Context& context, const ViewState& v, const ViewLayers& layers, bool shadeMesh,
                const std::array<float, 16>& viewProjection, const std::array<float, 16>& inverseViewProjection,
                int width, int height)
{
    const int mode = bindVoxelColor(v, layers.voxelColor);
    const AmbientOcclusion& ao = layers.ao;
    checkAmbientOcclusion(ao);
    v.opacity.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_OPACITY);
    const Program& p = context.program(viewShaders(), {"view_voxels.comp"});
    const Illumination& light = layers.light;
    bindVoxelLight(context, v, p, light, ao);
    setVoxelUniforms(v, p, layers, shadeMesh, mode, viewProjection, inverseViewProjection, width, height);
    const bool interleave = interleavesCones(light, ao);
    const Texture2D& pixels = castRays(context, v, p, interleave, width, height);
    if (interleave) resolveInterleavedCones(context, light, ao, width, height);
    drawPixels(context, v, pixels);
}

/// The mesh drawn as triangles, shaded by the view direction (ViewLayers::mesh).
void drawMesh(const Context& context, const ViewState& v, const CellCamera& cam,
              const std::array<float, 16>& viewProjection, bool orthographic)
{
    const Program& p = context.program(viewShaders(), {"view_mesh.vert", "view_mesh.frag"});
    p.setMatrix("uViewProjection", viewProjection.data());
    const auto& c = ViewColors::mesh;
    p.set("uColor", c[0], c[1], c[2]);
    p.set("uEye", float(cam.eye.x), float(cam.eye.y), float(cam.eye.z));
    p.set("uViewDir", float(cam.forward.x), float(cam.forward.y), float(cam.forward.z));
    p.set("uOrthographic", orthographic ? 1.0f : 0.0f);
    p.use();
    v.meshArray->bind();
    glDrawElements(GL_TRIANGLES, GLsizei(v.meshIndexCount), GL_UNSIGNED_INT, nullptr);
    checkGl("drawing the mesh");
}

/// Node boxes of levels [from, to] in one colour, one instanced draw per level.
void drawOutlines(const Context& context, const ViewState& v, const std::array<float, 16>& viewProjection,
                  uint32_t from, uint32_t to, const float* c)
{
    const Program& p = context.program(viewShaders(), {"view_outlines.vert", "view_color.frag"});
    p.setMatrix("uViewProjection", viewProjection.data());
    p.set("uDepthBias", 2e-4f);
    p.set("uColor", c[0], c[1], c[2]);
    p.use();
    v.empty.bind();
    for (uint32_t level = from; level <= to; ++level) {
        const uint32_t first = v.levelStart[level], count = v.levelStart[level + 1] - first;
        p.set("uFirstNode", first);
        p.set("uNodeSize", float(8u << (v.brickLevel - level)));
        glDrawArraysInstanced(GL_LINES, 0, 24, GLsizei(count));
    }
    checkGl("drawing the node outlines");
}

/// The brick boxes in their colour, then the outlines of the other levels asked for.
void drawNodeBoxes(const Context& context, const ViewState& v, const ViewLayers& layers,
                   const std::array<float, 16>& viewProjection)
{
    uint32_t last = std::min(layers.lastLevel, v.brickLevel);
    if (layers.bricks) {
        drawOutlines(context, v, viewProjection, v.brickLevel, v.brickLevel, ViewColors::brick);
        if (last == v.brickLevel) { // the brick boxes are drawn already, in their colour
            if (last == 0) return;
            --last;
        }
    }
    if (layers.outlines && layers.firstLevel <= last)
        drawOutlines(context, v, viewProjection, layers.firstLevel, last, ViewColors::outline);
}

/// What OctreeView::draw promises to leave: no vertex array or program bound, depth testing off.
void endFrame()
{
    glBindVertexArray(0);
    glUseProgram(0);
    glDisable(GL_DEPTH_TEST);
}

/// Draws the layers into the framebuffer bound now, over (0, 0, width, height).
void drawLayers(const Context& context, const ViewState& v, const ViewCamera& camera, int width, int height,
                const ViewLayers& layers)
{
    v.cutPixels = 0;
    const CellCamera cam = cellCamera(v.grid, camera, width, height);
    const auto viewProjection = toFloat(cam.viewProjection);
    const auto inverseViewProjection = toFloat(cam.inverseViewProjection);
    beginFrame(v, width, height);
    const bool shadeMesh = layers.voxels && layers.surface == Surface::Mesh;
    if (shadeMesh) drawMeshSurface(context, v, viewProjection, width, height);
    if (layers.voxels) drawVoxels(context, v, layers, shadeMesh, viewProjection, inverseViewProjection, width, height);
    if (layers.mesh && v.meshArray && !shadeMesh) drawMesh(context, v, cam, viewProjection, camera.orthographic);
    drawNodeBoxes(context, v, layers, viewProjection);
    endFrame();
}

/// Refuses a frame whose rays the driver cut short (loop_cut.glsl): its
/// picture would be missing voxels or occlusion without a sign of it.
void checkLoopCut(const Context& context, const ViewState& v)
{
    if (v.cutPixels == 0) return;
    throw DeviceError(fmt::format("octree view: {} ended the rays of {} pixels early (its limit of {} loop iterations an "
                                  "invocation), so the picture would be incomplete; draw on a GPU, or with fewer cones, "
                                  "a wider cone step or a coarser grid",
                                  context.info().renderer, v.cutPixels, context.info().loopLimit));
}

} // namespace

uint32_t OctreeView::cutPixels() const { return impl_->cutPixels; }

void OctreeView::draw(const ViewCamera& camera, int width, int height, const ViewLayers& layers) const
{
    Context::Scope scope(context_);
    checkGl("the GL work before drawing a view");
    checkSize(width, height);
    drawLayers(context_, *impl_, camera, width, height, layers);
}

std::vector<OctreeView::FrameTime> OctreeView::timeFrames(const ViewCamera& camera, int width, int height,
                                                         const ViewLayers& layers, int frames,
                                                         bool injectEachFrame) const
{
    Context::Scope scope(context_);
    checkGl("the GL work before timing a view");
    checkSize(width, height);
    if (frames < 1) throw InvalidInput(fmt::format("octree view: {} frames to time; at least 1", frames));
    Target target(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.get());
    drawLayers(context_, *impl_, camera, width, height, layers); // programs made, caches warm: not timed
    checkLoopCut(context_, *impl_);
    glFinish();
    std::vector<TimerQuery> queries(static_cast<size_t>(frames));
    std::vector<FrameTime> times(queries.size());
    for (size_t i = 0; i < queries.size(); ++i) {
        const auto start = std::chrono::steady_clock::now();
        queries[i].begin();
        if (injectEachFrame && layers.light.mode != Illumination::Mode::Off && impl_->light)
            injectLight(context_, impl_->buffers(), layers.light, *impl_->light);
        drawLayers(context_, *impl_, camera, width, height, layers);
        queries[i].end();
        glFinish();
        times[i].wallMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }
    for (size_t i = 0; i < queries.size(); ++i) times[i].gpuMs = queries[i].milliseconds();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("timing the view's frames");
    return times;
}

LightVolume OctreeView::readLightVolume(const Illumination& light) const
{
    Context::Scope scope(context_);
    checkGl("the GL work before reading a lighting volume");
    return svo::gl::readLightVolume(impl_->lightVolume(context_, light));
}

Image OctreeView::render(const ViewCamera& camera, int width, int height, const ViewLayers& layers) const
{
    Context::Scope scope(context_);
    checkGl("the GL work before rendering a view");
    checkSize(width, height);
    Target target(width, height);
    glBindFramebuffer(GL_FRAMEBUFFER, target.fbo.get());
    drawLayers(context_, *impl_, camera, width, height, layers);
    checkLoopCut(context_, *impl_);

    Image image;
    image.width = width;
    image.height = height;
    image.rgba.resize(size_t(width) * size_t(height) * 4);
    std::vector<uint8_t> rows(image.rgba.size());
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rows.data());
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    checkGl("reading the picture back");
    const size_t stride = size_t(width) * 4;
    for (int y = 0; y < height; ++y) // GL's rows start at the bottom
        std::copy_n(&rows[size_t(height - 1 - y) * stride], stride, &image.rgba[size_t(y) * stride]);
    return image;
}

} // namespace svo::gl
