#version 330 core
// Depth is all the shadow pass needs; the colour output is masked off.
void main() {}
