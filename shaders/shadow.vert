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
uniform int uBoxCorner;  // 1: the mesh is makeBoxCornerMesh, mirrored onto the faces turned to the sun
uniform vec3 uSunDir;    // unit vector towards the sun

vec3 rotate(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

// Box faces the renderer found inside a neighbouring box (bit 2 * axis + (normal > 0)) are sent
// outside the clip volume; all corners of a face move together, so its triangles are dropped whole.
// Bits 6-11 (faces the camera cannot see) are ignored here: those faces may still cast shadows.
bool hiddenFace(vec3 normal) {
  if (iHiddenFaces < 0.5) return false;
  vec3 a = abs(normal);
  int axis = a.x > 0.5 ? 0 : (a.y > 0.5 ? 1 : 2);
  int bit = 2 * axis + (normal[axis] > 0.0 ? 1 : 0);
  return (((int(iHiddenFaces) & 63) >> bit) & 1) != 0;
}

void main() {
  vec3 pos = aPos, normal = aNormal;
  if (uBoxCorner != 0) {
    // Per axis, the face whose normal points to the sun in the box's frame. The mirror may reverse
    // the winding, so the renderer draws these without face culling.
    vec3 toSun = rotate(vec4(-iQuat.xyz, iQuat.w), uSunDir);
    vec3 s = vec3(toSun.x < 0.0 ? -1.0 : 1.0, toSun.y < 0.0 ? -1.0 : 1.0, toSun.z < 0.0 ? -1.0 : 1.0);
    pos *= s;
    normal *= s;
  }
  vec3 local = pos * iScale + vec3(0.0, aCapSide * iStretch, 0.0);
  gl_Position = hiddenFace(normal) ? vec4(2.0, 2.0, 2.0, 1.0) : uLightViewProj * vec4(iPos + rotate(iQuat, local), 1.0);
}
