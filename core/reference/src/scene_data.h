#pragma once
// SceneData: what a Scene prepares, the Embree device and BVH and the mesh in
// the local frame (double), which is where every ray is made. The renderers
// reach it through sceneData(); the public header only forward-declares it.
#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "svo/reference/scene.h"

namespace svo::reference {

// A surface point reached by a ray, in the local frame.
struct Surface {
    Vec3d point;   // on the triangle, double
    Vec3d normal;  // unit, facing the ray's origin
    Vec3d albedo;
    Vec3d emission;
};

struct SceneData {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    Vec3d centre;                 // world = local + centre
    Bounds bounds;                // world
    double epsilon = 0;           // world = local units
    std::vector<Vec3d> positions; // local, double
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<Vec3d> colors;    // albedo per vertex; empty: `albedo` everywhere
    Vec3d albedo;
    std::vector<Vec3d> emission;  // per triangle; empty: none
    bool emits = false;

    ~SceneData();

    Vec3d toLocal(const Vec3d& world) const { return world - centre; }

    // The closest hit along origin + t dir, t in (0, inf); false on a miss.
    // `dir` must be unit length.
    bool intersect(const Vec3d& origin, const Vec3d& dir, Surface& hit) const;
    // Whether anything lies along origin + t dir, t in (0, tFar).
    bool occluded(const Vec3d& origin, const Vec3d& dir, double tFar) const;
    // Where secondary rays from a surface start.
    Vec3d offset(const Surface& s) const { return s.point + epsilon * s.normal; }
};

// The data of a Scene, for the renderers (a friend of Scene).
const SceneData& sceneData(const Scene& scene);

} // namespace svo::reference
