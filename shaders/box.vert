#version 330 core
// Boxes as one stream of world-space face corners (BoxFaceStream), lit per vertex: flat faces
// under a distant sun, so exact but for the tiny change of the view direction across a face.
// scene.frag (SURFACE 2) adds the shadow and the edge lines.

layout(location = 0) in vec3 aPos;        // world position
layout(location = 1) in vec3 aNormal;     // world unit normal of the face
layout(location = 2) in vec3 aColor;      // linear albedo
layout(location = 3) in vec4 aEdge;       // metres to the face's four edges
layout(location = 4) in float aEdgeWidth; // edge line width in metres

uniform mat4 uViewProj;
uniform mat4 uLightViewProj;
uniform float uShadowNormalOffset;  // metres to push the shadow lookup along the normal (kills acne)
uniform vec3 uSunDir;
uniform vec3 uSunColor;
uniform vec3 uSkyAmbient;
uniform vec3 uGroundAmbient;
uniform vec3 uEye;
uniform float uFogDistance;

out vec3 vShadowCoord;  // shadow map coordinates and depth in [0, 1] (the sun's view is orthographic)
out vec4 vEdge;
flat out float vEdgeWidth;
flat out vec3 vBase;    // albedo * ambient (flat: constant on a face, nothing to interpolate)
flat out vec3 vSunLit;  // albedo * sun * max(n.l, 0)
out vec3 vSpec;    // sun * specular, zero on faces turned from the sun
out float vFog;    // fog amount

void main() {
  vec3 n = aNormal;
  vShadowCoord = (uLightViewProj * vec4(aPos + n * uShadowNormalOffset, 1.0)).xyz * 0.5 + 0.5;
  vEdge = aEdge;
  vEdgeWidth = aEdgeWidth;
  gl_Position = uViewProj * vec4(aPos, 1.0);
  float ndl = max(dot(n, uSunDir), 0.0);
  vec3 ambient = mix(uGroundAmbient, uSkyAmbient, n.y * 0.5 + 0.5);
  vec3 toEye = uEye - aPos;
  vec3 h = normalize(uSunDir + normalize(toEye));
  float nh = max(dot(n, h), 0.0);
  float nh8 = nh * nh; nh8 *= nh8; nh8 *= nh8;  // (n.h)^48 by squaring, as in scene.frag
  float spec = ndl > 0.0 ? nh8 * nh8 * nh8 * nh8 * nh8 * nh8 * 0.12 : 0.0;
  vBase = aColor * ambient;
  vSunLit = aColor * uSunColor * ndl;
  vSpec = uSunColor * spec;
  float d2 = dot(toEye, toEye);
  vFog = 1.0 - exp(-d2 / (uFogDistance * uFogDistance));
}
