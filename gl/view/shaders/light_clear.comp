#version 450 core
// Illumination::clearance's texture (design §7d): per texel of the lighting
// volume's level 0, the coarsest level a cone may sample anywhere in that
// texel and read no voxel. A level-L sample at q reads the 2³ level-L texels
// around q, which reach less than 1.5 · 2^L texels of level 0 from q along
// each axis (narrower where an axis has fewer levels). If the nearest texel
// holding a voxel lies D texels from q's texel (max-norm, between centres),
// its box lies D - 1 or more from q, so levels with 1.5 · 2^L <= D - 1 are
// clear. D is a separable max-norm distance transform, one pass an axis:
// along x the distance to the row's nearest occupied texel, then along y
// and z min over k of max(|k|, the previous pass at k), searched outwards
// until |k| reaches the best so far. Distances stop at uCap (the texture's
// byte); a level read from the cap is still clear, only not the coarsest.
layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, rgba16f) readonly restrict uniform image3D uOpacity; // level 0 (uAxis 0)
layout(binding = 1, r8ui) readonly restrict uniform uimage3D uIn;        // the previous axis' pass
layout(binding = 2, r8ui) writeonly restrict uniform uimage3D uOut;

uniform ivec3 uSize; // level 0, texels
uniform int uAxis;   // 0: x, from the opacity; 1: y; 2: z, written as levels
uniform int uCap;    // at most 255

bool occupied(ivec3 p) { return dot(imageLoad(uOpacity, p), vec4(1.0)) > 0.0; }

/// The previous pass at p, uCap outside the volume (nothing there).
int previous(ivec3 p)
{
    return any(lessThan(p, ivec3(0))) || any(greaterThanEqual(p, uSize)) ? uCap : int(imageLoad(uIn, p).r);
}

/// The coarsest level L with 1.5 · 2^L <= D - 1, in integers 3 · 2^L <= 2(D - 1); 0 if none.
uint clearLevel(int d)
{
    uint l = 0u;
    while ((3 << (l + 1u)) <= 2 * (d - 1)) ++l;
    return l;
}

void main()
{
    ivec3 p = ivec3(gl_GlobalInvocationID);
    if (any(greaterThanEqual(p, uSize))) return;
    ivec3 e = ivec3(uAxis == 0 ? 1 : 0, uAxis == 1 ? 1 : 0, uAxis == 2 ? 1 : 0);
    int n = uSize[uAxis], at = p[uAxis];
    int best = uCap;
    if (uAxis == 0) {
        for (int k = 0; k < best && (at - k >= 0 || at + k < n); ++k)
            if ((at - k >= 0 && occupied(p - k * e)) || (at + k < n && occupied(p + k * e))) best = k;
    } else {
        best = previous(p);
        for (int k = 1; k < best && (at - k >= 0 || at + k < n); ++k) best = min(best, max(k, min(previous(p - k * e), previous(p + k * e))));
    }
    imageStore(uOut, p, uvec4(uAxis == 2 ? clearLevel(best) : uint(best)));
}
