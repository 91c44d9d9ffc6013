#version 330 core
// Instanced bodies but boxes (box.vert), and the ground. Per-vertex: unit shape; per-instance: rigid transform, scale
// and colour. Lighting happens in world space in scene.frag.

layout(location = 0) in vec3 aPos;       // unit-shape position
layout(location = 1) in vec3 aNormal;    // unit-shape normal
layout(location = 2) in float aCapSide;  // +1/-1 on capsule halves, 0 otherwise
layout(location = 3) in vec3 iPos;       // world position
layout(location = 4) in vec4 iQuat;      // orientation quaternion (x, y, z, w)
layout(location = 5) in vec3 iScale;     // half extents / radius
layout(location = 6) in float iStretch;  // capsule half height
layout(location = 7) in vec4 iColor;     // linear rgb, a = emissive amount (markers)
layout(location = 8) in float iHiddenFaces;  // box faces to drop (bit mask as a float), 0 otherwise

uniform mat4 uViewProj;
uniform mat4 uLightViewProj;
uniform float uShadowNormalOffset;  // metres to push the shadow lookup along the normal (kills acne)

out vec3 vWorldPos;
out vec3 vNormal;
out vec3 vColor;
out float vEmissive;
out vec3 vShadowCoord;   // shadow map coordinates and depth in [0, 1] (the sun's view is orthographic)

#ifndef SURFACE
#define SURFACE 0
#endif
#if SURFACE == 1
// The ground's faces are flat too: its lighting but for the shadow and the grid is per vertex.
uniform vec3 uSunDir;
uniform vec3 uSunColor;
uniform vec3 uSkyAmbient;
uniform vec3 uGroundAmbient;
uniform vec3 uEye;
flat out vec3 vAmbient;  // flat: constant on each (flat) face, so nothing to interpolate
flat out vec3 vSunLit;   // sun * max(n.l, 0)
#endif

vec3 rotate(vec4 q, vec3 v) {
  vec3 t = 2.0 * cross(q.xyz, v);
  return v + q.w * t + cross(q.xyz, t);
}

// Faces of a ground box the renderer found inside a neighbouring box (bit 2 * axis + (normal > 0))
// are sent outside the clip volume; all corners of a face move together, so its triangles are
// dropped whole.
bool hiddenFace(vec3 normal) {
  if (iHiddenFaces < 0.5) return false;
  vec3 a = abs(normal);
  int axis = a.x > 0.5 ? 0 : (a.y > 0.5 ? 1 : 2);
  int bit = 2 * axis + (normal[axis] > 0.0 ? 1 : 0);
  return ((int(iHiddenFaces) >> bit) & 1) != 0;
}

void main() {
  vec3 local = aPos * iScale + vec3(0.0, aCapSide * iStretch, 0.0);
  vec3 world = iPos + rotate(iQuat, local);
  // Inverse-scale the normal so non-uniform boxes keep correct face normals.
  vec3 n = normalize(rotate(iQuat, aNormal / max(iScale, vec3(1e-6))));
  vWorldPos = world;
  vNormal = n;
  vColor = iColor.rgb;
  vEmissive = iColor.a;
  vShadowCoord = (uLightViewProj * vec4(world + n * uShadowNormalOffset, 1.0)).xyz * 0.5 + 0.5;
  gl_Position = hiddenFace(aNormal) ? vec4(2.0, 2.0, 2.0, 1.0) : uViewProj * vec4(world, 1.0);
#if SURFACE == 1
  vec3 nf = dot(n, uEye - world) < 0.0 ? -n : n;  // the two-sided plane seen from below
  vAmbient = mix(uGroundAmbient, uSkyAmbient, nf.y * 0.5 + 0.5);
  vSunLit = uSunColor * max(dot(nf, uSunDir), 0.0);
#endif
}
