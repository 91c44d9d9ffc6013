#version 330 core
// Sun with PCF shadows + hemispheric ambient, an anti-aliased fading grid on the ground, distance
// fog towards the horizon colour, and sRGB encoding at the end (lighting itself is linear).
// SURFACE (set by the renderer) picks the variant at compile time: 0 body, 1 ground (both after
// scene.vert), 2 box with edge lines (after box.vert). llvmpipe runs both sides of every branch
// under a mask, so a runtime switch would make every fragment pay for the grid, the edges and the
// specular at once.

#ifndef SURFACE
#define SURFACE 0
#endif
#ifndef RECEIVES_SHADOW  // 0: ground where no shadow can fall, box faces turned from the sun
#define RECEIVES_SHADOW 1
#endif

in vec3 vShadowCoord;
#if SURFACE != 2
in vec3 vWorldPos;
in vec3 vNormal;
in vec3 vColor;
in float vEmissive;
#endif
#if SURFACE == 1
flat in vec3 vAmbient;  // per face: ground faces are flat
flat in vec3 vSunLit;   // sun * max(n.l, 0)
#endif
#if SURFACE == 2  // from box.vert
in vec4 vEdge;     // metres to the face's four edges
flat in float vEdgeWidth;
flat in vec3 vBase;     // albedo * ambient (per face: box faces are flat)
flat in vec3 vSunLit;   // albedo * sun * max(n.l, 0)
in vec3 vSpec;     // sun * specular, zero on faces turned from the sun
in float vFog;     // fog amount
#endif

uniform sampler2DShadow uShadowMap;
uniform vec3 uSunDir;           // unit vector towards the sun
uniform vec3 uSunColor;         // linear radiance
uniform vec3 uSkyAmbient;       // ambient from above
uniform vec3 uGroundAmbient;    // ambient bounced from below
uniform vec3 uEye;
uniform vec3 uFogColor;         // linear horizon colour
uniform float uFogDistance;     // distance where fog reaches ~63 %
uniform vec3 uGroundColor;      // linear ground albedo
uniform float uGridSpacing;     // minor grid spacing in metres
uniform float uGridFade;        // distance where the grid has faded out

out vec4 fragColor;

// One hardware-filtered comparison = bilinear 2x2 PCF. Each extra tap costs several ms per frame
// on llvmpipe, so the softness comes from filtering, not from many taps. No branches (llvmpipe
// pays for both sides): outside the map the border (1.0) lights, the reference stays below 1 so
// points past the sun's far plane compare like the farthest depth, and without casters the
// renderer fills the map with 1.0.
float shadowFactor() { return texture(uShadowMap, vec3(vShadowCoord.xy, min(vShadowCoord.z, 0.99999))); }

// Anti-aliased grid: minor lines every uGridSpacing, major lines every 10. Derivatives are taken
// once; lines denser than a few pixels fade out instead of turning into moire.
float gridLines(vec2 c) {
  vec2 w = max(fwidth(c), vec2(1e-5));
  vec2 dMinor = abs(fract(c - 0.5) - 0.5) / w;
  vec2 cMajor = c * 0.1;
  vec2 dMajor = abs(fract(cMajor - 0.5) - 0.5) / (w * 0.1);
  float wMax = max(w.x, w.y);
  float minor = (1.0 - min(min(dMinor.x, dMinor.y), 1.0)) * (1.0 - smoothstep(0.15, 0.45, wMax));
  float major = (1.0 - min(min(dMajor.x, dMajor.y) / 1.6, 1.0)) * (1.0 - smoothstep(1.5, 4.5, wMax));
  return max(minor * 0.35, major * 0.6);
}

// Linear -> sRGB with a sqrt-only fit (within 3/255, mostly < 1/255); pow() is slow on llvmpipe.
vec3 encodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
  return clamp(0.585122381 * s1 + 0.783140355 * s2 - 0.368262736 * s3, 0.0, 1.0);
}

#if SURFACE == 2
// Boxes: flat faces under a distant sun, so everything but the shadow and the edge lines was lit
// per vertex. Every rasterised box fragment is shaded with 4x MSAA on llvmpipe (the depth test
// does not skip hidden ones), so this shader is kept short.
void main() {
  // Darken near box edges (in metres) so stacked boxes of similar colour stay readable.
  float e = min(min(vEdge.x, vEdge.y), min(vEdge.z, vEdge.w));
  float px = fwidth(e);
  float edge = 1.0 - smoothstep(vEdgeWidth, vEdgeWidth + px * 1.5, e);
#if RECEIVES_SHADOW
  float shadow = shadowFactor();
  vec3 lit = (1.0 - 0.35 * edge) * (vBase + vSunLit * shadow) + vSpec * shadow;
#else
  vec3 lit = (1.0 - 0.35 * edge) * vBase;  // turned away from the sun: vSunLit and vSpec are zero
#endif
  lit = mix(lit, uFogColor, vFog * 0.5);
  fragColor = vec4(encodeSrgb(lit), 1.0);
}
#elif SURFACE == 1
// Ground: per-pixel grid, shadow and fog on per-vertex lighting; matte.
void main() {
  vec3 toEye = vWorldPos - uEye;
  float dist2 = dot(toEye, toEye);
  float fade = 1.0 - smoothstep(uGridFade * 0.35, uGridFade, sqrt(dist2));
  vec3 albedo = uGroundColor * (1.0 - gridLines(vWorldPos.xz / uGridSpacing) * fade);
#if RECEIVES_SHADOW
  vec3 lit = albedo * (vAmbient + vSunLit * shadowFactor());
#else
  vec3 lit = albedo * (vAmbient + vSunLit);
#endif
  // Gaussian fog: the scene itself stays clear, the far ground melts into the horizon.
  float fog = 1.0 - exp(-dist2 / (uFogDistance * uFogDistance));
  fragColor = vec4(encodeSrgb(mix(lit, uFogColor, fog)), 1.0);
}
#else
// Bodies other than boxes: per-pixel normal, specular and emissive markers.
void main() {
  vec3 n = normalize(vNormal);
  if (!gl_FrontFacing) n = -n;  // open triangle meshes seen from behind
  float dist = length(vWorldPos - uEye);
  float ndl = max(dot(n, uSunDir), 0.0);
  float shadow = ndl > 0.0 ? shadowFactor() : 0.0;
  vec3 ambient = mix(uGroundAmbient, uSkyAmbient, n.y * 0.5 + 0.5);
  vec3 h = normalize(uSunDir + normalize(uEye - vWorldPos));
  float nh = max(dot(n, h), 0.0);
  float nh8 = nh * nh; nh8 *= nh8; nh8 *= nh8;  // (n.h)^48 by squaring, cheaper than pow()
  float spec = nh8 * nh8 * nh8 * nh8 * nh8 * nh8 * 0.12;
  vec3 lit = vColor * (ambient + uSunColor * ndl * shadow) + uSunColor * spec * shadow;
  lit = mix(lit, vColor, vEmissive);
  float fog = 1.0 - exp(-(dist * dist) / (uFogDistance * uFogDistance));
  lit = mix(lit, uFogColor, fog * 0.5);
  fragColor = vec4(encodeSrgb(lit), 1.0);
}
#endif
