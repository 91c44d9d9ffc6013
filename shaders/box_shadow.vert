#version 330 core
// Depth-only pass from the sun for the box faces BoxFaceStream put in world space.
layout(location = 0) in vec3 aPos;
uniform mat4 uLightViewProj;
void main() { gl_Position = uLightViewProj * vec4(aPos, 1.0); }
