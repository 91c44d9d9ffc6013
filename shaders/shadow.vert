#version 330 core
// Depth-only pass from the sun; same instance layout as scene.vert.

layout(location = 0) in vec3 aPos;
layout(location = 1) in vec3 aNormal;
layout(location = 2) in float aCapSide;
layout(location = 3) in vec3 iPos;
layout(location = 4) in vec4 iQuat;
layout(location = 5) in vec3 iScale;
layout(location = 6) in float iStretch;
layout(location = 8) in float iHiddenFaces;

uniform mat4 uLightViewProj;

vec3 rotate(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

// Box faces the renderer found inside a neighbouring box (bit 2 * axis + (normal > 0)) are sent
// outside the clip volume; all corners of a face move together, so its triangles are dropped whole.
bool hiddenFace() {
  if (iHiddenFaces < 0.5) return false;
  vec3 a = abs(aNormal);
  int axis = a.x > 0.5 ? 0 : (a.y > 0.5 ? 1 : 2);
  int bit = 2 * axis + (aNormal[axis] > 0.0 ? 1 : 0);
  return ((int(iHiddenFaces) >> bit) & 1) != 0;
}

void main() {
  vec3 local = aPos * iScale + vec3(0.0, aCapSide * iStretch, 0.0);
  gl_Position = hiddenFace() ? vec4(2.0, 2.0, 2.0, 1.0) : uLightViewProj * vec4(iPos + rotate(iQuat, local), 1.0);
}
