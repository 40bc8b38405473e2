#version 450 core
// Flat shading from the triangle's own normal (screen derivatives), lit from the eye.
in vec3 vPosition;
uniform vec3 uColor;
uniform vec3 uEye;        // perspective: the eye in cell space
uniform vec3 uViewDir;    // orthographic: the view direction
uniform float uOrthographic;
out vec4 fragColor;
void main()
{
    vec3 n = normalize(cross(dFdx(vPosition), dFdy(vPosition)));
    vec3 toEye = uOrthographic > 0.5 ? -uViewDir : normalize(uEye - vPosition);
    float light = 0.35 + 0.65 * abs(dot(n, toEye));
    fragColor = vec4(uColor * light, 1.0);
}
