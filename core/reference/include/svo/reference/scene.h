#pragma once
/// @file scene.h
/// @brief The triangles a reference is traced against, prepared once: a
/// TriangleMesh with its material, in an Embree 3 BVH.
///
/// @details Surfaces are two-sided Lambertian reflectors: at a hit, the
/// normal is the triangle's geometric normal turned to face the incoming
/// ray, and any emission leaves both sides. Albedo is the mesh's per-vertex
/// colour, interpolated over the triangle, when the mesh has colours and
/// Material::vertexColors is set; otherwise Material::albedo.
///
/// Numerics: Embree takes floats. The mesh goes to a local frame centred on
/// its bounding box (in double) before it is rounded to float, so that a mesh
/// far from the origin keeps float's relative precision; every ray is made in
/// that frame from double data. Hit points are rebuilt in double from the
/// triangle's corners and Embree's barycentrics, and a secondary ray starts
/// at the hit point moved by the ray epsilon along the facing normal (never
/// along the ray, which fails at grazing angles). The default epsilon,
/// 1e-5 of the bounding box's diagonal, is ~170 float ulps of the largest
/// local coordinate: above Embree's and the rounding's error, and well below
/// any feature the voxel octree resolves. The BVH is built with
/// RTC_SCENE_FLAG_ROBUST, so rays do not slip through shared edges (a closed
/// box stays closed).
#include <cstddef>
#include <memory>
#include <vector>

#include "svo/core/mesh.h"

namespace svo::reference {

struct SceneData; // what a Scene prepares: the renderers' (src/scene_data.h), opaque here

/// @brief Reflectance and emission of every triangle.
struct Material {
    /// Albedo per channel, in [0, 1], where vertex colours are not used.
    Vec3d albedo{0.5, 0.5, 0.5};
    /// Use mesh.colors (each channel in [0, 1]) as albedo when the mesh has them.
    bool vertexColors = true;
    /// Emitted radiance of each triangle per channel (finite, >= 0), the same
    /// on both sides and in every direction; empty for none, else one per triangle.
    std::vector<Vec3d> emission;
};

/// @brief A mesh and its material in an Embree BVH, ready for any number of renders
/// (which may run at the same time: a Scene is read-only after construction).
/// Movable, not copyable.
class Scene {
public:
    /// @brief Copies what it needs of @a mesh and @a material and builds the BVH.
    /// @param rayEpsilon  offset of secondary ray origins, world units; 0 picks
    ///                    1e-5 of the bounding box's diagonal (see the file comment)
    /// @throw svo::InvalidInput  the mesh fails svo::validateMesh, a vertex colour or the
    ///                    albedo is outside [0, 1] or not finite, the emission list
    ///                    is neither empty nor one per triangle, an emission is
    ///                    negative or not finite, rayEpsilon is negative or not
    ///                    finite, or there are more than 2^31 triangles
    /// @throw svo::DeviceError when Embree fails (its message is kept)
    /// @throw svo::OutOfMemory when Embree cannot allocate
    explicit Scene(const TriangleMesh& mesh, const Material& material = {}, double rayEpsilon = 0);
    ~Scene();
    Scene(Scene&&) noexcept;
    Scene& operator=(Scene&&) noexcept;
    Scene(const Scene&) = delete;
    Scene& operator=(const Scene&) = delete;

    Bounds bounds() const;       ///< of the mesh's vertices, world units
    double rayEpsilon() const;   ///< in use, world units
    size_t triangleCount() const; ///< the mesh's triangles
    bool emits() const;          ///< some triangle has non-zero emission

private:
    std::unique_ptr<SceneData> data_;
    /// The renderers' way in (path_trace.cpp, ambient_occlusion.cpp), not a caller's.
    friend const SceneData& sceneData(const Scene& scene);
};

} // namespace svo::reference
