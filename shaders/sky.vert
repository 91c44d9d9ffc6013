#version 330 core
// Sky as a strip of kRows bands at the far plane, from uBottom (NDC y; the ground covers every
// row below it) to the top of the image. The gradient is evaluated per
// vertex and interpolated, so the fragment shader is a plain copy (full-screen passes are the
// expensive part on a software rasterizer). Drawn with GL_TRIANGLE_STRIP, 2 * (kRows + 1) vertices.

const int kRows = 24;

uniform vec3 uForward;
uniform vec3 uRight;
uniform vec3 uUp;
uniform vec2 uTanHalfFov;  // (x, y)
uniform vec3 uHorizon;     // linear
uniform vec3 uZenith;      // linear
uniform float uBottom;     // NDC y of the strip's lower edge

out vec3 vColor;  // sRGB-encoded

// Same sqrt-only sRGB fit as scene.frag.
vec3 encodeSrgb(vec3 c) {
  c = clamp(c, 0.0, 1.0);
  vec3 s1 = sqrt(c), s2 = sqrt(s1), s3 = sqrt(s2);
  return clamp(0.585122381 * s1 + 0.783140355 * s2 - 0.368262736 * s3, 0.0, 1.0);
}

void main() {
  int row = gl_VertexID / 2;
  vec2 p = vec2((gl_VertexID % 2 == 0) ? -1.0 : 1.0, mix(uBottom, 1.0, float(row) / float(kRows)));
  vec3 ray = normalize(uForward + p.x * uTanHalfFov.x * uRight + p.y * uTanHalfFov.y * uUp);
  vec3 c = mix(uHorizon, uZenith, sqrt(clamp(ray.y, 0.0, 1.0)));
  c = mix(c, uHorizon * 0.9, clamp(-ray.y * 4.0, 0.0, 1.0));  // below the horizon: hazy
  vColor = encodeSrgb(c);
  gl_Position = vec4(p, 1.0, 1.0);  // depth 1: only pixels nothing covered pass LEQUAL
}
