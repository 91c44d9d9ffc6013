#version 330 core
// The gradient was computed per vertex in sky.vert.
in vec3 vColor;
out vec4 fragColor;
void main() { fragColor = vec4(vColor, 1.0); }
