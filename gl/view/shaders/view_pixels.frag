#version 450 core
// The voxel pass's pixels (view_voxels.comp) into the framebuffer, with their
// depth, so that the mesh and the node outlines are drawn in front of or
// behind them. Pixels whose ray hit nothing keep the background.
#include "gpu_layout.h"
#include "view_layout.h"

layout(binding = SVO_UNIT_VIEW_PIXELS) uniform sampler2D uPixels;

out vec4 fragColor;

void main()
{
    vec4 p = texelFetch(uPixels, ivec2(gl_FragCoord.xy), 0);
    if (p.a < 0.0) discard;
    fragColor = vec4(p.rgb, 1.0);
    gl_FragDepth = p.a;
}
