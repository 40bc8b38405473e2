#version 450 core
// Six-way radiance (Illumination::directional; design §7d; Crassin et al.
// 2011): one level of the radiance a ray travelling along one axis
// direction sees in a texel, from the level below. Along the axis the
// children are composited front to back in the ray's order, premultiplied:
// C = C_front + (1 - a_front) C_back, with a the child's opacity along the
// axis, so what a wall hides stays hidden; across the axis the columns are
// averaged. Level 1 reads level 0's isotropic radiance, taking from each
// texel only the light leaving towards the ray (its lit side), higher
// levels the same direction's level below. An axis already one texel wide has one child
// along it.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, rgba16f) readonly restrict uniform image3D uOpacityIn;
layout(binding = 1, rgba16f) readonly restrict uniform image3D uRadianceIn;
layout(binding = 2, rgba16f) writeonly restrict uniform image3D uRadianceOut;
layout(binding = 3, rgba16f) readonly restrict uniform image3D uLitSideIn; // level 0's lit side times its light

uniform ivec3 uInSize;
uniform ivec3 uOutSize;
uniform int uAxis;     // 0, 1, 2: x, y, z
uniform int uPositive; // 1: the ray travels towards +axis (meets the low child first)
uniform uint uFromBase; // 1: the level below is level 0

#include "lit_side.glsl"
#include "opacity_depth.glsl"

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, uOutSize))) return;
    ivec3 n = ivec3(uInSize.x > 1 ? 2 : 1, uInSize.y > 1 ? 2 : 1, uInSize.z > 1 ? 2 : 1);
    ivec3 base = ivec3(uInSize.x > 1 ? 2 * p.x : p.x, uInSize.y > 1 ? 2 * p.y : p.y, uInSize.z > 1 ? 2 * p.z : p.z);
    int u = (uAxis + 1) % 3, v = (uAxis + 2) % 3; // the axes across
    vec3 sum = vec3(0.0);
    float opaque = 0.0;
    for (int i = 0; i < n[u]; ++i)
        for (int j = 0; j < n[v]; ++j) {
            vec3 c = vec3(0.0);
            float through = 1.0;
            for (int k = 0; k < n[uAxis]; ++k) {
                ivec3 child = ivec3(0);
                child[u] = i;
                child[v] = j;
                child[uAxis] = uPositive != 0 ? k : n[uAxis] - 1 - k;
                float a = opacityFromStored(imageLoad(uOpacityIn, base + child).rgb)[uAxis];
                vec3 r = imageLoad(uRadianceIn, base + child).rgb;
                if (uFromBase != 0u) { // the light leaving back towards the ray: along -axis for +axis
                    vec3 back = vec3(0.0);
                    back[uAxis] = uPositive != 0 ? -1.0 : 1.0;
                    r *= towardsLitSide(litSideOf(imageLoad(uLitSideIn, base + child).xyz, r), back);
                }
                c += through * r;
                through *= 1.0 - a;
            }
            sum += c;
            opaque += 1.0 - through;
        }
    float columns = float(n[u] * n[v]);
    imageStore(uRadianceOut, p, vec4(sum / columns, opaque / columns));
}
