// Minimal float vector/matrix helpers for the renderer. Kept separate from the physics math on
// purpose: the renderer must build without any physics code. Matrices are column-major like GL.
#pragma once

#include <cmath>

namespace haif::render {

struct Vec3 {
  float x = 0.f, y = 0.f, z = 0.f;
};

inline Vec3 operator+(Vec3 a, Vec3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline Vec3 operator-(Vec3 a, Vec3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline Vec3 operator*(Vec3 a, float s) { return {a.x * s, a.y * s, a.z * s}; }
inline float dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline float length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) {
  const float l = length(a);
  return l > 1e-20f ? a * (1.f / l) : Vec3{0.f, 1.f, 0.f};
}

/// Rotates v by the unit quaternion q = (x, y, z, w).
inline Vec3 rotate(const float q[4], Vec3 v) {
  const Vec3 u{q[0], q[1], q[2]};
  const Vec3 t = cross(u, v) * 2.f;
  return v + t * q[3] + cross(u, t);
}

struct Mat4 {
  float m[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
};

inline Mat4 operator*(const Mat4& a, const Mat4& b) {
  Mat4 r;
  for (int c = 0; c < 4; ++c)
    for (int row = 0; row < 4; ++row) {
      float s = 0.f;
      for (int k = 0; k < 4; ++k) s += a.m[k * 4 + row] * b.m[c * 4 + k];
      r.m[c * 4 + row] = s;
    }
  return r;
}

/// Right-handed view matrix looking from eye to target.
inline Mat4 lookAt(Vec3 eye, Vec3 target, Vec3 up) {
  const Vec3 f = normalize(target - eye);
  Vec3 s = cross(f, up);
  if (length(s) < 1e-6f) s = cross(f, std::fabs(f.x) < 0.9f ? Vec3{1, 0, 0} : Vec3{0, 0, 1});
  s = normalize(s);
  const Vec3 u = cross(s, f);
  Mat4 r;
  r.m[0] = s.x, r.m[4] = s.y, r.m[8] = s.z;
  r.m[1] = u.x, r.m[5] = u.y, r.m[9] = u.z;
  r.m[2] = -f.x, r.m[6] = -f.y, r.m[10] = -f.z;
  r.m[12] = -dot(s, eye), r.m[13] = -dot(u, eye), r.m[14] = dot(f, eye);
  return r;
}

inline Mat4 perspective(float fovYRadians, float aspect, float zNear, float zFar) {
  const float t = 1.f / std::tan(fovYRadians * 0.5f);
  Mat4 r;
  r.m[0] = t / aspect;
  r.m[5] = t;
  r.m[10] = (zFar + zNear) / (zNear - zFar);
  r.m[11] = -1.f;
  r.m[14] = 2.f * zFar * zNear / (zNear - zFar);
  r.m[15] = 0.f;
  return r;
}

inline Mat4 ortho(float l, float r, float b, float t, float n, float f) {
  Mat4 o;
  o.m[0] = 2.f / (r - l);
  o.m[5] = 2.f / (t - b);
  o.m[10] = -2.f / (f - n);
  o.m[12] = -(r + l) / (r - l);
  o.m[13] = -(t + b) / (t - b);
  o.m[14] = -(f + n) / (f - n);
  return o;
}

}  // namespace haif::render
