#version 450 core
// The mesh's surface for shading (ViewLayers::surface = Mesh): each pixel's
// point on the nearest triangle and that triangle's unit normal, in cell
// space, which view_voxels.comp then shades like a voxel's centre.
in vec3 vPosition;
layout(location = 0) out vec4 point;
layout(location = 1) out vec4 normal;
void main()
{
    // The triangle's own normal from screen derivatives: a triangle is
    // planar, so every pixel of it (and its helper pixels) gives the same.
    point = vec4(vPosition, 1.0);
    normal = vec4(normalize(cross(dFdx(vPosition), dFdy(vPosition))), 0.0);
}
