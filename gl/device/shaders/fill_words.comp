#version 450 core
// fillWords (svo/gl/fill_words.h): the first uWords 32-bit words set to
// uValue, an invocation a word.
layout(local_size_x = 256) in;

layout(std430, binding = 0) writeonly buffer Target { uint words[]; };

uniform uint uWords;
uniform uint uValue;

void main()
{
    const uint i = gl_GlobalInvocationID.x + gl_GlobalInvocationID.y * gl_NumWorkGroups.x * gl_WorkGroupSize.x;
    if (i < uWords) words[i] = uValue;
}
