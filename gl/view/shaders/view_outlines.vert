#version 450 core
// Node outlines: one instance per node of one level, 24 vertices (12 edges of
// its box). Empty nodes are moved outside the clip volume.
#include "gpu_layout.h"
#include "view_layout.h"

layout(std430, binding = SVO_BIND_VIEW_NODES) readonly restrict buffer Nodes { uint nodes[]; };
layout(std430, binding = SVO_BIND_VIEW_ORIGINS) readonly restrict buffer Origins { uvec4 origins[]; };

uniform mat4 uViewProjection; // cell space -> clip
uniform uint uFirstNode;
uniform float uNodeSize;      // edge in cells
uniform float uDepthBias;     // NDC depth moved towards the eye, so faces under a line do not hide it

// Edge e runs from corner kEdges[2e] to kEdges[2e+1]; corner bits are x, y, z.
const int kEdges[24] = int[24](0, 1, 2, 3, 4, 5, 6, 7,  // along x
                               0, 2, 1, 3, 4, 6, 5, 7,  // along y
                               0, 4, 1, 5, 2, 6, 3, 7); // along z

void main()
{
    uint node = uFirstNode + uint(gl_InstanceID);
    if (nodes[kNodeWords * node + 1u] == 0u) {
        gl_Position = vec4(0.0, 0.0, 2.0, 1.0);
        return;
    }
    int corner = kEdges[gl_VertexID];
    vec3 p = vec3(origins[node].xyz) + vec3(corner & 1, (corner >> 1) & 1, corner >> 2) * uNodeSize;
    gl_Position = uViewProjection * vec4(p, 1.0);
    gl_Position.z -= uDepthBias * gl_Position.w;
}
