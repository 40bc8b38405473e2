#include "svo/reference/camera.h"

#include <cmath>
#include <fmt/format.h>

#include "svo/core/error.h"
#include "vec_math.h"

namespace svo::reference {

void checkCamera(const Camera& camera, int width, int height)
{
    constexpr int maxSide = 32768;
    if (width < 1 || height < 1 || width > maxSide || height > maxSide)
        throw InvalidInput(fmt::format("reference camera: a {} x {} image is outside 1 .. {} pixels per side", width, height,
                                       maxSide));
    if (!finite(camera.eye) || !finite(camera.target) || !finite(camera.up))
        throw InvalidInput("reference camera: eye, target and up must be finite");
    const Vec3d toTarget = camera.target - camera.eye;
    if (!(length(toTarget) > 0)) throw InvalidInput("reference camera: the eye and the target coincide");
    // The same test as the GL view's, so that both refuse the same cameras.
    const Vec3d r = cross(normalize(toTarget), camera.up);
    if (!(length(r) > 1e-9 * length(camera.up)))
        throw InvalidInput("reference camera: up is zero or along the view direction");
    if (camera.orthographic) checkOrthographicHeight(camera.height, "reference camera: orthographic height");
    else checkFieldOfView(camera.fovYDegrees, "reference camera: field of view");
}

Ray cameraRay(const Camera& camera, int width, int height, int x, int y)
{
    checkCamera(camera, width, height);
    if (x < 0 || y < 0 || x >= width || y >= height)
        throw InvalidInput(fmt::format("reference camera: pixel ({}, {}) is outside the {} x {} image", x, y, width, height));
    const Vec3d f = normalize(camera.target - camera.eye);
    const Vec3d r = normalize(cross(f, camera.up));
    const Vec3d u = cross(r, f);
    const double aspect = double(width) / double(height);
    const double ndcX = 2.0 * (x + 0.5) / width - 1.0;
    const double ndcY = 1.0 - 2.0 * (y + 0.5) / height;
    if (camera.orthographic) {
        const double h = camera.height, w = h * aspect;
        return {camera.eye + (0.5 * w * ndcX) * r + (0.5 * h * ndcY) * u, f};
    }
    const double t = std::tan(camera.fovYDegrees * M_PI / 360.0);
    return {camera.eye, normalize(f + (ndcX * t * aspect) * r + (ndcY * t) * u)};
}

} // namespace svo::reference
