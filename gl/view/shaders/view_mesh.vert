#version 450 core
// The mesh, in cell space like the octree.
layout(location = 0) in vec3 position;
uniform mat4 uViewProjection;
out vec3 vPosition;
void main()
{
    vPosition = position;
    gl_Position = uViewProjection * vec4(position, 1.0);
}
