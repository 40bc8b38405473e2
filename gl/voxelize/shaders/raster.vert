#version 450 core
// Vertices arrive in local index coordinates (grid.h); the geometry shader projects.
layout(location = 0) in vec3 aPosition;
out vec3 vPosition;
void main()
{
    vPosition = aPosition;
    gl_Position = vec4(0.0);
}
