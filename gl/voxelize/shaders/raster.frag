#version 450 core
// One fragment is one voxel column (column_walk.glsl).
#include "glsl_types.glsl"
#include "overlap.glsl"
#include "column_walk.glsl"

flat in vec3 gA;
flat in vec3 gB;
flat in vec3 gC;
flat in int gAxis;
flat in vec4 gBox;

uniform vec2 uTileOrigin;

void main()
{
    svo_walk_column(gA, gB, gC, gAxis, floor(gl_FragCoord.xy) + uTileOrigin, gBox, uint(gl_PrimitiveID));
}
