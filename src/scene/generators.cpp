#include "scene/generators.h"

#include <cmath>

namespace haif {

uint64_t SplitMix64::next() {
  uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double SplitMix64::uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }

namespace {

Vec3 toFloat(const Vec3d& v) { return v.cast<float>(); }

BodyDesc& emit(const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out, const Vec3d& position) {
  out.push_back(proto);
  BodyDesc& b = out.back();
  b.where = where;  // Numbering appends " #k"
  b.position = toFloat(position);
  return b;
}

// Numbers each body of one generator call 0..n-1 in its `where`.
struct Numbering {
  std::vector<BodyDesc>& out;
  size_t first;
  std::string where;
  Numbering(std::vector<BodyDesc>& o, const std::string& w) : out(o), first(o.size()), where(w) {}
  ~Numbering() {
    for (size_t i = first; i < out.size(); ++i) out[i].where = where + " #" + std::to_string(i - first);
  }
};

ShapeDesc boxShape(const Vec3d& half) {
  ShapeDesc s;
  s.type = ShapeType::Box;
  s.halfExtents = toFloat(half);
  return s;
}

Quat yawQuat(double deg) {
  const double a = deg * (3.14159265358979323846 / 180.0);
  return Quat(Eigen::AngleAxisd(a, Vec3d::UnitY()).cast<float>());
}

}  // namespace

void generateGround(const GroundParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  BodyDesc& b = emit(proto, where, out, p.position);
  b.motion = MotionType::Static;
  b.name = "ground";
  b.shape = boxShape(p.halfExtents);
}

void generateStack(const StackParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const double pitch = 2.0 * p.halfExtents.y() + p.gap;
  for (int h = 0; h < p.count; ++h) {
    BodyDesc& b = emit(proto, where, out, p.base + Vec3d(0.0, p.halfExtents.y() + h * pitch, 0.0));
    b.shape = boxShape(p.halfExtents);
  }
}

int stacksGridSide(int count, int perStack) {
  const int stacks = (count + perStack - 1) / perStack;
  int k = 1;
  while (k * k < stacks) ++k;
  return k;
}

void generateStacks(const StacksParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const int k = stacksGridSide(p.count, p.perStack);
  const double pitch = 2.0 * p.halfExtents.y() + p.gap;
  for (int i = 0; i < p.count; ++i) {
    const int s = i / p.perStack, h = i % p.perStack;
    const Vec3d pos = p.origin + Vec3d(p.spacing * (s % k), p.halfExtents.y() + h * pitch, p.spacing * (s / k));
    emit(proto, where, out, pos).shape = boxShape(p.halfExtents);
  }
}

void generatePyramid2d(const Pyramid2dParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const double s = 2.0 * p.half;
  for (int i = 0; i < p.base; ++i)
    for (int j = i; j < p.base; ++j) {
      const Vec3d pos(0.5 * (i + 1) + (j - i) - 0.5 * p.base, i + 0.5, 0.0);
      emit(proto, where, out, p.origin + s * pos).shape = boxShape(Vec3d::Constant(p.half));
    }
}

void generatePyramid3d(const Pyramid3dParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const double h = p.half;
  const double layerGap = p.layerGap < 0.0 ? 0.5 * h : p.layerGap;
  for (int i = 0; i < p.base; ++i) {
    const double shift = (i % 2 == 1) ? h : 0.0;
    const int lo = i / 2, hi = p.base - 1 - (i + 1) / 2;
    for (int j = lo; j <= hi; ++j)
      for (int k = lo; k <= hi; ++k) {
        const Vec3d pos(-p.base * h + 2.0 * h * j + shift, h + i * (2.0 * h + layerGap), -p.base * h + 2.0 * h * k + shift);
        emit(proto, where, out, p.origin + pos).shape = boxShape(Vec3d::Constant(h));
      }
  }
}

void generateManyPyramids(const ManyPyramidsParams& p, const BodyPrototype& proto, const std::string& where,
                          std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const double s = 2.0 * p.half;
  const double pitch = (p.base + 1) * s;
  const double gx = 0.5 * p.cols * pitch, gz = 0.5 * p.rows * pitch;
  for (int r = 0; r < p.rows; ++r) {
    const double z = p.rows > 1 ? -gz + s + r * 2.0 * (gz - s) / (p.rows - 1) : 0.0;
    for (int c = 0; c < p.cols; ++c) {
      const double cx = -gx + c * pitch + s;
      for (int i = 0; i < p.base; ++i)
        for (int j = i; j < p.base; ++j) {
          const Vec3d pos(cx + s * (0.5 * (i + 1) + (j - i) - 0.5), s * (i + 0.5), z);
          emit(proto, where, out, p.origin + pos).shape = boxShape(Vec3d::Constant(p.half));
        }
    }
  }
}

void generateWall(const WallParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const Vec3d& h = p.brickHalfExtents;
  const double len = 2.0 * h.x(), step = len + p.gap;
  const double width = p.cols * len + (p.cols - 1) * p.gap;
  const Quat q = yawQuat(p.yawDeg);
  const Eigen::Matrix3d rot = q.cast<double>().toRotationMatrix();
  auto place = [&](double x, double y, const Vec3d& half) {
    BodyDesc& b = emit(proto, where, out, p.position + rot * Vec3d(x, y, 0.0));
    b.shape = boxShape(half);
    b.orientation = q;
  };
  for (int r = 0; r < p.rows; ++r) {
    const double y = h.y() + r * (2.0 * h.y() + p.gap);
    if (!p.runningBond || r % 2 == 0) {
      for (int c = 0; c < p.cols; ++c) place(-0.5 * width + h.x() + c * step, y, h);
    } else {
      // Half bricks at both ends keep the wall's ends flush.
      const double halfLen = 0.5 * (len - p.gap);
      const Vec3d halfBrick(0.5 * halfLen, h.y(), h.z());
      place(-0.5 * width + 0.5 * halfLen, y, halfBrick);
      for (int c = 0; c + 1 < p.cols; ++c) place(-0.5 * width + 0.5 * step + h.x() + c * step, y, h);
      place(0.5 * width - 0.5 * halfLen, y, halfBrick);
    }
  }
}

void generateGrid(const GridParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  for (int iy = 0; iy < p.ny; ++iy)
    for (int iz = 0; iz < p.nz; ++iz)
      for (int ix = 0; ix < p.nx; ++ix)
        emit(proto, where, out, p.origin + p.spacing.cwiseProduct(Vec3d(ix, iy, iz)));
}

namespace {

struct PileLattice {
  double cell;
  int nx, ny, nz;
};

PileLattice pileLattice(const RandomPileParams& p) {
  PileLattice l;
  l.cell = 2.2 * p.maxSize;
  const Vec3d ext = p.hi - p.lo;
  l.nx = static_cast<int>(std::floor(ext.x() / l.cell));
  l.ny = static_cast<int>(std::floor(ext.y() / l.cell));
  l.nz = static_cast<int>(std::floor(ext.z() / l.cell));
  return l;
}

// Uniform random rotation by rejection from the 4-ball: only +, * and sqrt, so bit-identical everywhere.
Quat randomRotation(SplitMix64& rng) {
  for (;;) {
    const Eigen::Vector4d v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const double n2 = v.squaredNorm();
    if (n2 > 1e-4 && n2 <= 1.0) {
      const Eigen::Vector4d u = v / std::sqrt(n2);
      return Quat(static_cast<float>(u[3]), static_cast<float>(u[0]), static_cast<float>(u[1]), static_cast<float>(u[2]));
    }
  }
}

// A random convex shape whose bounding sphere has radius <= r.
ShapeDesc randomShape(ShapeType kind, double r, SplitMix64& rng) {
  ShapeDesc s;
  s.type = kind;
  switch (kind) {
    case ShapeType::Sphere:
      s.radius = static_cast<float>(r);
      break;
    case ShapeType::Capsule: {
      const double radius = r * rng.uniform(0.35, 0.55);
      s.radius = static_cast<float>(radius);
      s.halfHeight = static_cast<float>(r - radius);
      break;
    }
    case ShapeType::ConvexHull: {
      // Six axis points (so the hull is never flat) plus six random directions.
      for (int axis = 0; axis < 3; ++axis)
        for (double sign : {-1.0, 1.0}) {
          Vec3d v = Vec3d::Zero();
          v[axis] = sign * r * rng.uniform(0.6, 1.0);
          s.points.push_back(toFloat(v));
        }
      for (int i = 0; i < 6;) {
        const Vec3d d(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
        const double n2 = d.squaredNorm();
        if (n2 < 1e-4 || n2 > 1.0) continue;
        s.points.push_back(toFloat(d / std::sqrt(n2) * (r * rng.uniform(0.6, 1.0))));
        ++i;
      }
      break;
    }
    default: {  // box
      s.type = ShapeType::Box;
      const double k = r / std::sqrt(3.0);
      s.halfExtents = toFloat(Vec3d(k * rng.uniform(0.6, 1.0), k * rng.uniform(0.6, 1.0), k * rng.uniform(0.6, 1.0)));
      break;
    }
  }
  return s;
}

}  // namespace

int randomPileCapacity(const RandomPileParams& p) {
  const PileLattice l = pileLattice(p);
  if (l.nx <= 0 || l.ny <= 0 || l.nz <= 0) return 0;
  const double cap = static_cast<double>(l.nx) * l.ny * l.nz;
  return cap > 1e9 ? 1000000000 : static_cast<int>(cap);
}

void generateRandomPile(const RandomPileParams& p, const BodyPrototype& proto, const std::string& where,
                        std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const PileLattice l = pileLattice(p);
  SplitMix64 rng(p.seed);
  for (int i = 0; i < p.count; ++i) {
    // Bottom layer first: the pile starts compact and settles quickly.
    const int ix = i % l.nx, iz = (i / l.nx) % l.nz, iy = i / (l.nx * l.nz);
    const ShapeType kind = p.kinds[static_cast<size_t>(rng.next() % p.kinds.size())];
    const double r = rng.uniform(p.minSize, p.maxSize);
    const double jitter = 0.5 * l.cell - r;
    const Vec3d centre = p.lo + l.cell * Vec3d(ix + 0.5, iy + 0.5, iz + 0.5);
    const Vec3d pos = centre + Vec3d(rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter), rng.uniform(-jitter, jitter));
    BodyDesc& b = emit(proto, where, out, pos);
    b.shape = randomShape(kind, r, rng);
    b.orientation = randomRotation(rng);
  }
}

void generateDominoes(const DominoParams& p, const BodyPrototype& proto, const std::string& where, std::vector<BodyDesc>& out) {
  Numbering n(out, where);
  const Vec3d& h = p.halfExtents;
  const double deg = 3.14159265358979323846 / 180.0;
  for (int k = 0; k < p.count; ++k) {
    Vec3d foot, dir;  // bottom centre and unit direction of the run (in the x-z plane)
    if (p.arc) {
      const double sign = p.reverse ? -1.0 : 1.0;
      const double a = p.startDeg * deg + sign * k * p.spacing / p.radius;
      foot = p.center + p.radius * Vec3d(std::cos(a), 0.0, std::sin(a));
      dir = sign * Vec3d(-std::sin(a), 0.0, std::cos(a));
    } else {
      dir = Vec3d(p.direction.x(), 0.0, p.direction.z()).normalized();
      foot = p.start + k * p.spacing * dir;
    }
    // Yaw that turns local +x onto dir: rotation about +y by a maps x to (cos a, 0, -sin a).
    const double yaw = std::atan2(-dir.z(), dir.x());
    Eigen::Quaterniond q(Eigen::AngleAxisd(yaw, Vec3d::UnitY()));
    Vec3d centre = foot + Vec3d(0.0, h.y(), 0.0);
    if (k == 0 && p.firstTiltDeg != 0.0) {
      // Tip forward about the front bottom edge, so the domino still touches the ground there.
      // Rotating about y x dir turns +y towards dir.
      const Eigen::AngleAxisd tilt(p.firstTiltDeg * deg, Vec3d::UnitY().cross(dir).normalized());
      const Vec3d edge = foot + h.x() * dir;
      centre = edge + tilt * (centre - edge);
      q = Eigen::Quaterniond(tilt) * q;
    }
    BodyDesc& b = emit(proto, where, out, centre);
    b.shape = boxShape(h);
    b.orientation = q.cast<float>().normalized();
  }
}

}  // namespace haif
