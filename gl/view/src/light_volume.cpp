#include "light_volume.h"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <vector>

#include "svo/gl/gl_api.h"
#include "svo/gl/loop_cut_counter.h"
#include "svo/core/error.h"
#include "view_layout.h"
#include "view_shaders.h"

namespace svo::gl {

namespace {

bool finite(const Vec3d& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool nonNegative(const Vec3d& v) { return finite(v) && v.x >= 0 && v.y >= 0 && v.z >= 0; }

int nextPowerOfTwo(uint64_t n)
{
    int p = 1;
    while (uint64_t(p) < n) p *= 2;
    return p;
}

/// Textures for level 0 of `resolution` texels at most and every mip level:
/// opacity, and when `lit` radiance (and with `directional` the six-way and
/// lit-side textures).
LightVolumeTextures allocateVolume(const GridSpec& grid, uint32_t resolution, bool lit, bool directional)
{
    LightVolumeTextures v;
    v.lit = lit;
    // Six-way volumes are the ones for thin walls: their opacity composites
    // as optical depth. Ambient occlusion keeps opacities: depths make a
    // wall at the edge of a cone's footprint count as nearly opaque, and the
    // Cornell box's AO darker than the path tracer's (RMSE 0.071 -> 0.121).
    v.opticalDepth = lit && directional;
    v.texelVoxels = texelVoxels(grid, resolution);
    int largest = 1;
    for (int i = 0; i < 3; ++i) {
        v.size[i] = nextPowerOfTwo((grid.dims[size_t(i)] + v.texelVoxels - 1) / v.texelVoxels);
        largest = std::max(largest, v.size[i]);
    }
    int levels = 1;
    while ((1 << (levels - 1)) < largest) ++levels;
    v.opacity = Texture3D("lighting volume's opacity", GL_RGBA16F, levels, v.size[0], v.size[1], v.size[2]);
    if (!lit) return v;
    v.radiance = Texture3D("lighting volume's radiance", GL_RGBA16F, levels, v.size[0], v.size[1], v.size[2]);
    if (directional && levels > 1) {
        static const char* names[6] = {"lighting volume's radiance along +x", "lighting volume's radiance along -x",
                                       "lighting volume's radiance along +y", "lighting volume's radiance along -y",
                                       "lighting volume's radiance along +z", "lighting volume's radiance along -z"};
        v.litSide = Texture3D("lighting volume's lit sides", GL_RGBA16F, 1, v.size[0], v.size[1], v.size[2]);
        for (int d = 0; d < 6; ++d)
            v.along[size_t(d)] = Texture3D(names[d], GL_RGBA16F, levels - 1, std::max(1, v.size[0] / 2),
                                           std::max(1, v.size[1] / 2), std::max(1, v.size[2] / 2));
    }
    return v;
}

/// Level 0 from the octree's voxels (with `light`, its radiance too), then
/// the mip-map on the GPU.
void fillVolume(const Context& context, const ViewBuffers& o, const Illumination* light, LightVolumeTextures& v);

} // namespace

uint32_t texelVoxels(const GridSpec& grid, uint32_t resolution)
{
    // The smallest power of two that keeps the volume's largest side within
    // the resolution asked for.
    const uint64_t largest = *std::max_element(grid.dims.begin(), grid.dims.end());
    uint32_t k = 1;
    while ((largest + k - 1) / k > resolution) k *= 2;
    return k;
}

void checkVolumeResolution(const GridSpec& grid, uint32_t r, const char* what)
{
    if (r < 8 || r > 2048 || (r & (r - 1)) != 0)
        throw InvalidInput(fmt::format("octree view: {} {} is not a power of two from 8 to 2048", what, r));
    if (texelVoxels(grid, r) > 8) {
        const uint64_t largest = *std::max_element(grid.dims.begin(), grid.dims.end());
        throw Unsupported(fmt::format("octree view: {} {} is too small for a grid {} voxels wide: at least {} (a texel "
                                      "holds at most 8³ voxels)",
                                      what, r, largest, nextPowerOfTwo((largest + 7) / 8)));
    }
}

// The single-option rules (illumination.h); checkIllumination runs them on a struct's fields.
void checkGiConeCount(int64_t cones, const std::string& name)
{
    if (cones < 1 || cones > 16) throw InvalidInput(name, fmt::format("{}: the bounce gathers 1 to 16 cones", cones));
}

void checkGiConeDistance(double voxels, const std::string& name)
{
    if (!(voxels >= 0 && voxels <= 1e7))
        throw InvalidInput(name, fmt::format("{}: cones stop 0 (the grid's diagonal) to 1e7 voxels away", voxels));
}

void checkShadowOffset(double voxels, const std::string& name)
{
    if (!(voxels >= 0 && voxels < 1e6))
        throw InvalidInput(name, fmt::format("{}: shadow rays start 0 or more voxels out, less than 1e6", voxels));
}

void checkVolumeResolution(int64_t texels, const std::string& name)
{
    if (texels < 8 || texels > 2048 || (texels & (texels - 1)) != 0)
        throw InvalidInput(name, fmt::format("{}: a volume resolution is a power of two from 8 to 2048", texels));
}

void checkPositive(double value, const std::string& name)
{
    if (!(value > 0 && std::isfinite(value)))
        throw InvalidInput(name, fmt::format("{}: expected a positive finite number", value));
}

void checkIllumination(const Illumination& l)
{
    auto bad = [](const std::string& what) { throw InvalidInput("octree view: lighting: " + what); };
    if (l.lights.directional.empty() && l.lights.point.empty()) bad("no light: give a directional or a point light");
    for (const DirectionalLight& d : l.lights.directional) {
        if (!finite(d.direction) || !(dot(d.direction, d.direction) > 0))
            bad(fmt::format("directional light direction {},{},{} is zero or not finite", d.direction.x, d.direction.y,
                            d.direction.z));
        if (!nonNegative(d.irradiance)) bad("a directional light's irradiance is negative or not finite");
    }
    for (const PointLight& p : l.lights.point) {
        if (!finite(p.position)) bad("a point light's position is not finite");
        if (!nonNegative(p.intensity)) bad("a point light's intensity is negative or not finite");
    }
    if (!(l.lights.environment.x == 0 && l.lights.environment.y == 0 && l.lights.environment.z == 0))
        bad("an environment light is not injected (directional and point lights are)");
    if (!nonNegative(l.albedo) || l.albedo.x > 1 || l.albedo.y > 1 || l.albedo.z > 1)
        bad(fmt::format("albedo {},{},{} is outside [0, 1]", l.albedo.x, l.albedo.y, l.albedo.z));
    // The single-option rules, naming the field (a front end names its flag or keyword).
    checkGiConeCount(l.cones, "Illumination::cones");
    checkConeAperture(l.apertureDegrees, "Illumination::apertureDegrees");
    if (!nonNegative(l.specular) || l.specular.x > 1 || l.specular.y > 1 || l.specular.z > 1)
        bad(fmt::format("specular {},{},{} is outside [0, 1]", l.specular.x, l.specular.y, l.specular.z));
    checkConeAperture(l.specularApertureDegrees, "Illumination::specularApertureDegrees");
    checkConeOffset(l.offset, "Illumination::offset");
    checkGiConeDistance(l.distance, "Illumination::distance");
    checkConeStep(l.step, "Illumination::step");
    checkShadowOffset(l.shadowOffset, "Illumination::shadowOffset");
    checkPositive(l.exposure, "Illumination::exposure");
    checkPositive(l.gamma, "Illumination::gamma");
    checkVolumeResolution(l.volumeResolution, "Illumination::volumeResolution");
}

void checkIllumination(const Illumination& l, const ViewBuffers& octree)
{
    checkIllumination(l);
    if (!octree.normals)
        throw InvalidInput(std::vector<Error::Part>{
            "octree view: lighting: the octree has no normal channel (voxelize the mesh with ",
            Error::option("svo::kNormals", "the normal attribute channel, svo::kNormals"), ")"});
    checkVolumeResolution(octree.grid, l.volumeResolution, "lighting: volume resolution");
}

bool sameInjection(const Illumination& a, const Illumination& b)
{
    auto same = [](const Vec3d& x, const Vec3d& y) { return x.x == y.x && x.y == y.y && x.z == y.z; };
    if (a.lights.directional.size() != b.lights.directional.size() || a.lights.point.size() != b.lights.point.size())
        return false;
    for (size_t i = 0; i < a.lights.directional.size(); ++i)
        if (!same(a.lights.directional[i].direction, b.lights.directional[i].direction) ||
            !same(a.lights.directional[i].irradiance, b.lights.directional[i].irradiance))
            return false;
    for (size_t i = 0; i < a.lights.point.size(); ++i)
        if (!same(a.lights.point[i].position, b.lights.point[i].position) ||
            !same(a.lights.point[i].intensity, b.lights.point[i].intensity))
            return false;
    return same(a.albedo, b.albedo) && a.shadowOffset == b.shadowOffset && a.volumeResolution == b.volumeResolution &&
           a.directional == b.directional;
}

void bindLights(const Program& p, const LightVolumeTextures& v, const ViewBuffers& o, const Illumination& l)
{
    v.lights.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_LIGHTS);
    v.direct.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_DIRECT);
    o.normals->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_NORMALS);
    (o.colors ? o.colors : o.normals)->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_ALBEDO);
    o.voxelStart->bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_VOXEL_START);
    p.set("uLightCount", v.lightCount);
    p.set("uShadowOffset", float(l.shadowOffset));
    p.set("uVoxelSize", float(o.grid.voxelSize));
    p.set("uAlbedo", float(l.albedo.x), float(l.albedo.y), float(l.albedo.z));
    p.set("uHasAlbedo", o.colors ? 1u : 0u);
}

void bindOpacityVolume(const Program& p, const LightVolumeTextures& v, const GridSpec& grid, int cones,
                       double apertureDegrees, double offset, double distance, double step)
{
    p.set("uConeStep", float(step));
    p.set("uOpticalDepth", v.opticalDepth ? 1u : 0u);
    v.opacity.bindTexture(SVO_UNIT_LIGHT_OPACITY);
    p.set("uDirectional", 0u);
    p.set("uConeClearance", 0u);
    const double k = v.texelVoxels;
    p.set("uVolumeScale", float(1.0 / (k * v.size[0])), float(1.0 / (k * v.size[1])), float(1.0 / (k * v.size[2])));
    p.set("uTexelCells", float(k));
    p.set("uConeTanHalf", float(std::tan(apertureDegrees * M_PI / 360.0)));
    const auto& d = grid.dims;
    const double diagonal = std::sqrt(double(d[0]) * d[0] + double(d[1]) * d[1] + double(d[2]) * d[2]);
    p.set("uConeDistance", float(distance > 0 ? distance : diagonal));
    p.set("uConeOffset", float(offset * k)); // texels of level 0, in voxels
    p.set("uCones", cones);
}

void bindLightVolume(const Program& p, const LightVolumeTextures& v, const ViewBuffers& o, const Illumination& l)
{
    bindLights(p, v, o, l);
    bindOpacityVolume(p, v, o.grid, l.cones, l.apertureDegrees, l.offset, l.distance, l.step);
    v.radiance.bindTexture(SVO_UNIT_LIGHT_RADIANCE);
    const bool sixWay = v.built.directional && v.opacity.levels() > 1;
    if (sixWay) {
        for (GLuint d = 0; d < 6; ++d) v.along[d].bindTexture(SVO_UNIT_LIGHT_ALONG + d);
        v.litSide.bindTexture(SVO_UNIT_LIGHT_LIT_SIDE);
    }
    p.set("uDirectional", sixWay ? 1u : 0u);
    if (l.clearance && v.clear.levels() == 0)
        throw InvalidInput("octree view: lighting: clearance asked for before its texture was built"); // buildClearance first
    if (l.clearance) v.clear.bindTexture(SVO_UNIT_LIGHT_CLEAR);
    p.set("uConeClearance", l.clearance ? 1u : 0u);
    p.set("uSpecular", float(l.specular.x), float(l.specular.y), float(l.specular.z));
    p.set("uSpecularTanHalf", float(std::tan(l.specularApertureDegrees * M_PI / 360.0)));
}

LightVolumeTextures buildLightVolume(const Context& context, const ViewBuffers& o, const Illumination& l)
{
    checkIllumination(l, o);
    LightVolumeTextures v = allocateVolume(o.grid, l.volumeResolution, true, l.directional);
    v.direct = Buffer("voxels' direct light", std::max<uint64_t>(o.normals->bytes() / 12, 1) * 16, nullptr, 0);
    injectLight(context, o, l, v);
    return v;
}

LightVolumeTextures buildOpacityVolume(const Context& context, const ViewBuffers& o, uint32_t resolution)
{
    checkVolumeResolution(o.grid, resolution, "ambient occlusion: volume resolution");
    LightVolumeTextures v = allocateVolume(o.grid, resolution, false, false);
    fillVolume(context, o, nullptr, v);
    return v;
}

void injectLight(const Context& context, const ViewBuffers& o, const Illumination& l, LightVolumeTextures& v)
{
    checkIllumination(l, o);
    if (!v.lit || texelVoxels(o.grid, l.volumeResolution) != v.texelVoxels)
        throw InvalidInput("octree view: lighting: re-injecting into another volume"); // callers rebuild instead
    v.built = l;
    // Lights in cell space (local + 1/2), two vec4 each (view_lights.glsl).
    std::vector<float> lights;
    for (const DirectionalLight& d : l.lights.directional) {
        const Vec3d u = (1.0 / std::sqrt(dot(d.direction, d.direction))) * d.direction;
        lights.insert(lights.end(), {float(u.x), float(u.y), float(u.z), 0.0f, float(d.irradiance.x),
                                     float(d.irradiance.y), float(d.irradiance.z), 0.0f});
    }
    for (const PointLight& p : l.lights.point) {
        const Vec3d c = o.grid.toLocal(p.position);
        lights.insert(lights.end(), {float(c.x + 0.5), float(c.y + 0.5), float(c.z + 0.5), 1.0f, float(p.intensity.x),
                                     float(p.intensity.y), float(p.intensity.z), 0.0f});
    }
    v.lightCount = int(lights.size() / 8);
    v.lights = Buffer("lights (view)", lights.size() * 4, lights.data(), 0);
    fillVolume(context, o, &l, v);
}

namespace {

void fillVolume(const Context& context, const ViewBuffers& o, const Illumination* l, LightVolumeTextures& v)
{
    const int levels = v.opacity.levels();
    // Level 0: opacity, and the injected light.
    const Program& inject = context.program(viewShaders(), {"light_inject.comp"});
    o.nodes.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_NODES);
    o.bricks.bindBase(GL_SHADER_STORAGE_BUFFER, SVO_BIND_VIEW_BRICKS);
    if (l) bindLights(inject, v, o, *l);
    inject.set("uBrickLevel", o.brickLevel);
    inject.set("uDims", int(o.grid.dims[0]), int(o.grid.dims[1]), int(o.grid.dims[2]));
    inject.set("uBaseSize", v.size[0], v.size[1], v.size[2]);
    inject.set("uTexelCells", int(v.texelVoxels));
    inject.set("uLit", l ? 1u : 0u);
    inject.set("uOpticalDepth", v.opticalDepth ? 1u : 0u);
    v.opacity.bindImage(0, 0, GL_WRITE_ONLY, GL_RGBA16F);
    if (l) v.radiance.bindImage(1, 0, GL_WRITE_ONLY, GL_RGBA16F);
    const bool sixWay = l && l->directional && levels > 1;
    if (sixWay) v.litSide.bindImage(2, 0, GL_WRITE_ONLY, GL_RGBA16F);
    inject.set("uDirectional", sixWay ? 1u : 0u);
    const LoopCutCounter loopCut;
    loopCut.arm(inject, SVO_BIND_VIEW_LOOP_CUT, context.info().loopLimit);
    inject.use();
    glDispatchCompute(GLuint((v.size[0] + 3) / 4), GLuint((v.size[1] + 3) / 4), GLuint((v.size[2] + 3) / 4));
    glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    checkGl(l ? "injecting light into the lighting volume" : "filling the opacity volume");
    // A texel marches a shadow ray per voxel and light: on a CPU rasterizer
    // a coarse texel of a large grid can spend the loop budget.
    if (const uint32_t cut = loopCut.count())
        throw DeviceError(fmt::format("lighting volume: {} ended the light injection of {} texels early (its limit of {} "
                                      "loop iterations an invocation), so their light would be wrong; light on a GPU, or "
                                      "a coarser grid or a finer lighting volume (fewer voxels a texel)",
                                      context.info().renderer, cut, context.info().loopLimit));

    // The mip-map, level by level; with six-way radiance, each direction's
    // level from the level below (level 1 from level 0's isotropic radiance).
    const Program& mip = context.program(viewShaders(), {"light_mip.comp"});
    const Program* along = sixWay ? &context.program(viewShaders(), {"light_mip_along.comp"}) : nullptr;
    mip.set("uLit", l ? 1u : 0u);
    mip.set("uOpticalDepth", v.opticalDepth ? 1u : 0u);
    if (along) along->set("uOpticalDepth", v.opticalDepth ? 1u : 0u);
    for (int level = 1; level < levels; ++level) {
        const int in[3] = {v.opacity.size(level - 1, 0), v.opacity.size(level - 1, 1), v.opacity.size(level - 1, 2)};
        const int out[3] = {v.opacity.size(level, 0), v.opacity.size(level, 1), v.opacity.size(level, 2)};
        const GLuint groups[3] = {GLuint((out[0] + 3) / 4), GLuint((out[1] + 3) / 4), GLuint((out[2] + 3) / 4)};
        v.opacity.bindImage(0, level - 1, GL_READ_ONLY, GL_RGBA16F);
        v.opacity.bindImage(2, level, GL_WRITE_ONLY, GL_RGBA16F);
        if (l) {
            v.radiance.bindImage(1, level - 1, GL_READ_ONLY, GL_RGBA16F);
            v.radiance.bindImage(3, level, GL_WRITE_ONLY, GL_RGBA16F);
        }
        mip.set("uInSize", in[0], in[1], in[2]);
        mip.set("uOutSize", out[0], out[1], out[2]);
        mip.use();
        glDispatchCompute(groups[0], groups[1], groups[2]);
        if (along) {
            along->set("uInSize", in[0], in[1], in[2]);
            along->set("uOutSize", out[0], out[1], out[2]);
            for (int d = 0; d < 6; ++d) {
                const Texture3D& t = v.along[size_t(d)];
                v.opacity.bindImage(0, level - 1, GL_READ_ONLY, GL_RGBA16F);
                if (level == 1) v.radiance.bindImage(1, 0, GL_READ_ONLY, GL_RGBA16F);
                else t.bindImage(1, level - 2, GL_READ_ONLY, GL_RGBA16F);
                t.bindImage(2, level - 1, GL_WRITE_ONLY, GL_RGBA16F);
                v.litSide.bindImage(3, 0, GL_READ_ONLY, GL_RGBA16F);
                along->set("uFromBase", level == 1 ? 1u : 0u);
                along->set("uAxis", d / 2);
                along->set("uPositive", d % 2 == 0 ? 1 : 0);
                along->use();
                glDispatchCompute(groups[0], groups[1], groups[2]);
            }
        }
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT | GL_SHADER_STORAGE_BARRIER_BIT);
    for (GLuint unit = 0; unit < 8; ++unit) glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
    glUseProgram(0);
    checkGl("mip-mapping the lighting volume");
}

} // namespace

void buildClearance(const Context& context, LightVolumeTextures& v)
{
    if (v.clear.levels() > 0) return;
    const int* n = v.size;
    Texture3D clear("lighting volume's clearance", GL_R8UI, 1, n[0], n[1], n[2]);
    const Texture3D across("lighting volume's clearance (x and y)", GL_R8UI, 1, n[0], n[1], n[2]);
    clear.nearest();
    const Program& p = context.program(viewShaders(), {"light_clear.comp"});
    p.set("uSize", n[0], n[1], n[2]);
    p.set("uCap", 255);
    v.opacity.bindImage(0, 0, GL_READ_ONLY, GL_RGBA16F);
    p.use();
    // x: opacity -> clear; y: clear -> across; z: across -> clear, as levels.
    for (int axis = 0; axis < 3; ++axis) {
        const Texture3D& in = axis == 2 ? across : clear;
        const Texture3D& out = axis == 1 ? across : clear;
        if (axis > 0) in.bindImage(1, 0, GL_READ_ONLY, GL_R8UI);
        out.bindImage(2, 0, GL_WRITE_ONLY, GL_R8UI);
        p.set("uAxis", axis);
        glDispatchCompute(GLuint((n[0] + 3) / 4), GLuint((n[1] + 3) / 4), GLuint((n[2] + 3) / 4));
        glMemoryBarrier(GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
    glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_TEXTURE_UPDATE_BARRIER_BIT);
    for (GLuint unit = 0; unit < 3; ++unit) glBindImageTexture(unit, 0, 0, GL_FALSE, 0, GL_READ_ONLY, GL_RGBA8);
    glUseProgram(0);
    checkGl("building the lighting volume's clearance");
    v.clear = std::move(clear);
}

LightVolume readLightVolume(const LightVolumeTextures& v)
{
    LightVolume out;
    out.texelVoxels = v.texelVoxels;
    for (int level = 0; level < v.opacity.levels(); ++level) {
        LightVolumeLevel l;
        for (int i = 0; i < 3; ++i) l.size[i] = v.opacity.size(level, i);
        const size_t n = size_t(l.size[0]) * size_t(l.size[1]) * size_t(l.size[2]) * 4;
        l.opacity.resize(n);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        v.opacity.read(level, GL_RGBA, GL_FLOAT, n * 4, l.opacity.data());
        if (v.opticalDepth) // back to opacities, as opacity_depth.glsl's opacityFromStored
            for (size_t i = 0; i < n; ++i)
                if (i % 4 != 3) l.opacity[i] = 1.0f - std::exp(-l.opacity[i]);
        if (!v.lit) {
            out.levels.push_back(std::move(l));
            continue;
        }
        l.radiance.resize(n);
        v.radiance.read(level, GL_RGBA, GL_FLOAT, n * 4, l.radiance.data());
        if (level == 0 && v.built.directional && v.opacity.levels() > 1) {
            l.litSide.resize(n);
            v.litSide.read(0, GL_RGBA, GL_FLOAT, n * 4, l.litSide.data());
        }
        if (level > 0 && v.built.directional)
            for (size_t d = 0; d < 6; ++d) {
                l.along[d].resize(n);
                v.along[d].read(level - 1, GL_RGBA, GL_FLOAT, n * 4, l.along[d].data());
            }
        out.levels.push_back(std::move(l));
    }
    if (v.clear.levels() > 0) {
        out.clearLevel.resize(size_t(v.size[0]) * size_t(v.size[1]) * size_t(v.size[2]));
        v.clear.read(0, GL_RED_INTEGER, GL_UNSIGNED_BYTE, out.clearLevel.size(), out.clearLevel.data());
    }
    checkGl("reading the lighting volume back");
    return out;
}

} // namespace svo::gl
