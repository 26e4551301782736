// Media: the submerged part of a body (volume, centre of buoyancy), buoyancy and drag,
// against closed forms and an independent integration written here (rays along the
// body's axis, each clipped exactly by the medium's box), never against the code
// under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "body.h"
#include "builders.h"
#include "medium.h"
#include "medium_detail.h"

namespace {

using rigid::Mat3;
using rigid::Quat;
using rigid::Shape;
using rigid::ShapeType;
using rigid::SubmergedPart;
using rigid::Vec3;

constexpr double kPi = 3.14159265358979323846;
constexpr double kBig = 1e3;  // m, half-size of "unbounded" medium boxes

// Errors of the approximations, as stated in docs/reports/media.md.
constexpr double kLatheVolumeError = 2.5e-3;    // of the body's volume
constexpr double kLatheCentroidError = 3e-3;    // of the body's largest dimension
constexpr double kSphereMultiAxisError = 1e-3;  // of the ball's volume, cut along 2-3 axes
constexpr double kSphereCentroidError = 1e-2;   // of the radius

using rigid::test::box;
using rigid::test::capsule;
using rigid::test::cylinder;
using rigid::test::sphere;

Mat3 rotX(double a) { return Eigen::AngleAxisd(a, Vec3::UnitX()).toRotationMatrix(); }
Mat3 rotation(double angle, const Vec3& axis) { return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix(); }

// Medium box whose top face is the plane z = top, unbounded otherwise.
Vec3 lowCorner() { return Vec3(-kBig, -kBig, -kBig); }
Vec3 highCorner(double top) { return Vec3(kBig, kBig, top); }

// Independent integration: the body as a bundle of rays along its z axis; each ray's
// overlap with the box is found exactly (slab method), so the integrand is continuous
// and the midpoint rule over the cross-section converges as 1/n^2. Discs are sampled in
// polar coordinates (rho = r sin phi), which makes the end caps' sqrt(r^2 - rho^2) smooth.
struct Reference {
  double volume = 0.0;
  Vec3 centroid = Vec3::Zero();
};
Reference rayIntegral(const Shape& s, const Vec3& X, const Mat3& R, const Vec3& mn, const Vec3& mx, int n = 500) {
  double V = 0.0;
  Vec3 M = Vec3::Zero();
  const Vec3 d = R.col(2);
  auto ray = [&](double u, double v, double half, double w) {
    const Vec3 p0 = X + R * Vec3(u, v, 0.0);
    double t0 = -half, t1 = half;
    for (int k = 0; k < 3; ++k) {
      if (std::abs(d[k]) < 1e-300) {
        if (p0[k] < mn[k] || p0[k] > mx[k]) return;
        continue;
      }
      double ta = (mn[k] - p0[k]) / d[k], tb = (mx[k] - p0[k]) / d[k];
      if (ta > tb) std::swap(ta, tb);
      t0 = std::max(t0, ta);
      t1 = std::min(t1, tb);
    }
    if (t1 <= t0) return;
    V += w * (t1 - t0);
    M += w * (t1 - t0) * (p0 + d * (0.5 * (t0 + t1)));
  };
  if (s.type == ShapeType::Box) {
    const double w = s.size.x() * s.size.y() / (double(n) * n);
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j)
        ray(s.size.x() * ((i + 0.5) / n - 0.5), s.size.y() * ((j + 0.5) / n - 0.5), 0.5 * s.size.z(), w);
  } else {
    const double r = s.radius, dphi = 0.5 * kPi / n, dtheta = 2.0 * kPi / n;
    for (int i = 0; i < n; ++i) {
      const double phi = (i + 0.5) * dphi;
      const double rho = r * std::sin(phi), cap = r * std::cos(phi);
      const double w = r * r * std::sin(phi) * std::cos(phi) * dphi * dtheta;
      double half = 0.0;
      switch (s.type) {
        case ShapeType::Sphere: half = cap; break;
        case ShapeType::Cylinder: half = 0.5 * s.length; break;
        case ShapeType::Capsule: half = 0.5 * s.length + cap; break;
        case ShapeType::Box:
        case ShapeType::Mesh:
        case ShapeType::Compound: break;  // (media take neither)
      }
      for (int j = 0; j < n; ++j) {
        const double theta = (j + 0.5) * dtheta;
        ray(rho * std::cos(theta), rho * std::sin(theta), half, w);
      }
    }
  }
  Reference out;
  out.volume = V;
  out.centroid = V > 0.0 ? Vec3(M / V) : X;
  return out;
}

double largestDimension(const Shape& s) {
  switch (s.type) {
    case ShapeType::Sphere: return 2.0 * s.radius;
    case ShapeType::Box: return s.size.maxCoeff();
    case ShapeType::Cylinder: return std::max(2.0 * s.radius, s.length);
    case ShapeType::Capsule: return s.length + 2.0 * s.radius;
    case ShapeType::Mesh:
    case ShapeType::Compound: break;  // (media take neither)
  }
  return 0.0;
}

// Cap of height h of a ball of radius r: volume and the distance of its centroid from
// the ball's centre.
double capVolume(double r, double h) { return kPi * h * h * (3.0 * r - h) / 3.0; }
double capCentroidDistance(double r, double h) { return 3.0 * (2.0 * r - h) * (2.0 * r - h) / (4.0 * (3.0 * r - h)); }

}  // namespace

// ---- spheres --------------------------------------------------------------------------

TEST(Submerged, SphereCutByOnePlaneIsTheSphericalCap) {
  const double r = 0.3;
  const Vec3 X(1.0, -2.0, 3.0);
  const double full = 4.0 / 3.0 * kPi * r * r * r;
  for (double h : {1e-4, 0.01, 0.15, 0.3, 0.45, 0.59, 0.6 - 1e-4}) {
    // Medium below the plane z = X.z - r + h: the cap at the bottom is inside.
    SubmergedPart p = rigid::submergedPart(sphere(r), X, Mat3::Identity(), lowCorner(), highCorner(X.z() - r + h));
    const double below = h <= r ? capVolume(r, h) : full - capVolume(r, 2 * r - h);
    EXPECT_NEAR(p.volume, capVolume(r, h), 1e-13 * full) << "h = " << h;
    EXPECT_NEAR(p.volume, below, 1e-13 * full) << "h = " << h;
    EXPECT_NEAR(p.centroid.z(), X.z() - capCentroidDistance(r, h), 1e-12 * r) << "h = " << h;
    EXPECT_NEAR((p.centroid.head<2>() - X.head<2>()).norm(), 0.0, 1e-15);
    // Medium beyond the plane x = X.x + r - h (a wall of fluid at +x): the cap at +x.
    p = rigid::submergedPart(sphere(r), X, Mat3::Identity(), Vec3(X.x() + r - h, -kBig, -kBig), Vec3(kBig, kBig, kBig));
    EXPECT_NEAR(p.volume, capVolume(r, h), 1e-13 * full) << "h = " << h;
    EXPECT_NEAR(p.centroid.x(), X.x() + capCentroidDistance(r, h), 1e-12 * r) << "h = " << h;
  }
}

TEST(Submerged, SphereInASlabBetweenTwoParallelPlanes) {
  const double r = 0.5;
  const Vec3 X(0.0, 0.0, 10.0);
  const double a = -0.2, b = 0.35;  // relative to the centre
  const SubmergedPart p =
      rigid::submergedPart(sphere(r), X, Mat3::Identity(), Vec3(-kBig, -kBig, X.z() + a), Vec3(kBig, kBig, X.z() + b));
  // Discs pi (r^2 - z^2) integrated over [a, b].
  const double V = kPi * (r * r * (b - a) - (b * b * b - a * a * a) / 3.0);
  const double M = kPi * (r * r * (b * b - a * a) / 2.0 - (b * b * b * b - a * a * a * a) / 4.0);
  EXPECT_NEAR(p.volume, V, 1e-14);
  EXPECT_NEAR(p.centroid.z(), X.z() + M / V, 1e-13);
}

TEST(Submerged, FullyInsideIsTheWholeBodyAtItsCentreAndOutsideIsNothing) {
  const Mat3 R = rotation(0.7, Vec3(1.0, 2.0, -0.5));
  const Vec3 X(0.3, -0.4, -5.0);
  for (const Shape& s : {sphere(0.2), box(0.3, 0.5, 0.7), cylinder(0.2, 0.6), capsule(0.1, 0.5)}) {
    SubmergedPart p = rigid::submergedPart(s, X, R, Vec3(-1, -1, -6), Vec3(1, 1, 0));
    EXPECT_DOUBLE_EQ(p.volume, rigid::shapeVolume(s)) << rigid::shapeTypeName(s.type);
    EXPECT_EQ(p.centroid, X);
    p = rigid::submergedPart(s, X, R, Vec3(-1, -1, -4.0), Vec3(1, 1, 0));  // 1 m above the body
    EXPECT_EQ(p.volume, 0.0) << rigid::shapeTypeName(s.type);
  }
}

TEST(Submerged, SphereCutAlongSeveralAxesWithinTheStatedError) {
  // A ball at an edge (two faces cut it) and at a corner (three) of a pool: the product
  // of the one-axis fractions, against the ray integration (its own error ~1e-5).
  const double r = 0.25;
  const double full = 4.0 / 3.0 * kPi * r * r * r;
  double worst[2] = {0.0, 0.0}, worstC[2] = {0.0, 0.0};
  for (int corner = 0; corner < 2; ++corner)
    for (int i = -6; i <= 6; ++i)
      for (int j = -6; j <= 6; ++j) {
        const Vec3 X(0.04 * i, corner ? 0.04 * (i + j) / 2.0 : 1.0, 0.04 * j);
        const Vec3 mn(0.0, 0.0, -kBig), mx(kBig, kBig, 0.0);
        const SubmergedPart p = rigid::submergedPart(sphere(r), X, Mat3::Identity(), mn, mx);
        const Reference ref = rayIntegral(sphere(r), X, Mat3::Identity(), mn, mx, 200);
        const double err = std::abs(p.volume - ref.volume) / full;
        worst[corner] = std::max(worst[corner], err);
        EXPECT_LT(err, kSphereMultiAxisError) << "corner " << corner << " at " << X.transpose();
        if (ref.volume > 0.02 * full) {
          const double errC = (p.centroid - ref.centroid).norm() / r;
          worstC[corner] = std::max(worstC[corner], errC);
          EXPECT_LT(errC, kSphereCentroidError) << "corner " << corner << " at " << X.transpose();
        }
      }
  std::printf(
      "ball at an edge: worst volume error %.2e of V, centroid %.2e of r; "
      "at a corner: %.2e, %.2e\n",
      worst[0], worstC[0], worst[1], worstC[1]);
}

TEST(Submerged, SphereStaysContinuousAsASecondFaceStartsToCut) {
  // Half in the water, sliding towards a wall at x = 0: the volume and the centroid move
  // by no more than the geometry's own rate as the wall starts to cut (a jump of 1e-6 of
  // the volume would be three times the tolerance).
  const double r = 0.25, step = 1e-7;
  const Vec3 mn(0.0, -kBig, -kBig), mx(kBig, kBig, 0.0);
  for (double edge : {r, 1.1 * r}) {  // the ball's and (about) the polyhedron's reach
    SubmergedPart prev = rigid::submergedPart(sphere(r), Vec3(edge + 20 * step, 0, 0.05), Mat3::Identity(), mn, mx);
    for (int i = 19; i >= -20; --i) {
      const SubmergedPart p = rigid::submergedPart(sphere(r), Vec3(edge + i * step, 0, 0.05), Mat3::Identity(), mn, mx);
      // A continuous volume moves at most by the largest section times the step.
      EXPECT_NEAR(p.volume, prev.volume, 1.01 * kPi * r * r * step) << edge << " " << i;
      EXPECT_NEAR((p.centroid - prev.centroid).norm(), 0.0, 100 * step) << edge << " " << i;
      prev = p;
    }
  }
}

// ---- boxes ------------------------------------------------------------------------------

TEST(Submerged, CubeTurned45DegreesAboutXCutThroughItsCentre) {
  // The section across x is a square standing on a corner; below its centre lies the
  // triangle with apex a/sqrt2 down, whose centroid is a / (3 sqrt2) below the centre.
  const double a = 0.8;
  const Vec3 X(2.0, 1.0, 0.0);
  const SubmergedPart p = rigid::submergedPart(box(a, a, a), X, rotX(kPi / 4), lowCorner(), highCorner(0.0));
  EXPECT_NEAR(p.volume, 0.5 * a * a * a, 1e-12 * a * a * a);
  EXPECT_NEAR(p.centroid.z(), -a / (3.0 * std::sqrt(2.0)), 1e-12 * a);
  EXPECT_NEAR(p.centroid.x(), X.x(), 1e-12 * a);
  EXPECT_NEAR(p.centroid.y(), X.y(), 1e-12 * a);
}

TEST(Submerged, BoxCutThroughItsCentreIsHalfInAnyOrientation) {
  // A box is symmetric about its centre: any plane through the centre halves it.
  const Shape s = box(0.3, 0.7, 1.1);
  for (int i = 0; i < 20; ++i) {
    const Mat3 R = rotation(0.37 * i + 0.1, Vec3(std::sin(1.3 * i), std::cos(0.7 * i), 0.5));
    const Vec3 X(0.1 * i, -0.2, 4.0);
    const SubmergedPart p = rigid::submergedPart(s, X, R, lowCorner(), highCorner(X.z()));
    EXPECT_NEAR(p.volume, 0.5 * rigid::shapeVolume(s), 1e-12 * rigid::shapeVolume(s)) << i;
  }
}

TEST(Submerged, TiltedBoxMatchesTheRayIntegration) {
  const Shape s = box(0.4, 0.6, 1.0);
  const double V = rigid::shapeVolume(s);
  struct Case {
    Vec3 axis;
    double angle;
    Vec3 X;
    Vec3 mn, mx;
  };
  const Case cases[] = {
      {Vec3(1, 0, 0), 0.3, Vec3(0, 0, 0.2), lowCorner(), highCorner(0.0)},  // one plane
      {Vec3(1, 1, 0), 1.1, Vec3(0, 0, -0.3), lowCorner(), highCorner(0.0)},
      {Vec3(1, 2, 3), 2.0, Vec3(0, 0, 0.45), lowCorner(), highCorner(0.0)},                 // a corner dips
      {Vec3(-1, 2, 0.5), 0.8, Vec3(0.1, 0, -0.1), Vec3(0, -kBig, -kBig), highCorner(0.0)},  // edge
      {Vec3(3, -1, 2), 2.5, Vec3(0.05, -0.1, 0.1), Vec3(0, 0, -kBig), highCorner(0.0)},     // corner
      {Vec3(0, 1, 1), 0.6, Vec3(0, 0, 0), Vec3(-0.2, -0.25, -0.3), Vec3(0.15, 0.3, 0.2)},   // all six
  };
  for (const Case& c : cases) {
    const Mat3 R = rotation(c.angle, c.axis);
    const SubmergedPart p = rigid::submergedPart(s, c.X, R, c.mn, c.mx);
    const Reference ref = rayIntegral(s, c.X, R, c.mn, c.mx, 600);
    // The reference's error: the midpoint rule on a continuous, piecewise-linear
    // integrand, ~1e-6 of the volume at n = 600.
    EXPECT_NEAR(p.volume, ref.volume, 2e-5 * V) << c.axis.transpose() << " " << c.angle;
    EXPECT_NEAR((p.centroid - ref.centroid).norm(), 0.0, 2e-5 * largestDimension(s))
        << c.axis.transpose() << " " << c.angle;
  }
}

TEST(Submerged, BoxFacesFlushWithTheMediumAreCountedOnce) {
  const Shape s = box(1.0, 1.0, 0.5);
  // Resting exactly on the floor of a tank and with its top exactly at the surface.
  SubmergedPart p = rigid::submergedPart(s, Vec3(0, 0, 0.25), Mat3::Identity(), Vec3(-2, -2, 0), Vec3(2, 2, 0.5));
  EXPECT_NEAR(p.volume, 0.5, 1e-9);
  EXPECT_NEAR(p.centroid.z(), 0.25, 1e-9);
  // Its sides flush with the tank's walls too: the body fills the tank exactly.
  p = rigid::submergedPart(s, Vec3(0, 0, 0.25), Mat3::Identity(), Vec3(-0.5, -0.5, 0), Vec3(0.5, 0.5, 0.5));
  EXPECT_NEAR(p.volume, 0.5, 1e-9);
  // Sitting on the surface, touching it from above: nothing is submerged.
  p = rigid::submergedPart(s, Vec3(0, 0, 0.25), Mat3::Identity(), Vec3(-2, -2, -1), Vec3(2, 2, 0));
  EXPECT_NEAR(p.volume, 0.0, 1e-9);
  // Half in, turned about z (the cut stays parallel to two faces).
  p = rigid::submergedPart(s, Vec3(0.3, 0.1, 0.0), rotation(0.4, Vec3::UnitZ()), lowCorner(), highCorner(0.0));
  EXPECT_NEAR(p.volume, 0.25, 1e-12);
  EXPECT_NEAR(p.centroid.z(), -0.125, 1e-12);
}

// ---- cylinders and capsules: polyhedra, within the stated error ------------------------

namespace {
// Area of the circular segment below the chord at height t (relative to the centre,
// -r <= t <= r) and the integral of y over it.
double segmentArea(double r, double t) { return r * r * std::acos(-t / r) + t * std::sqrt(r * r - t * t); }
double segmentMoment(double r, double t) { return -2.0 / 3.0 * std::pow(r * r - t * t, 1.5); }
}  // namespace

TEST(Submerged, HorizontalCylinderAndCapsuleAgainstClosedForms) {
  const double r = 0.2, l = 0.8;
  for (const Shape& s : {cylinder(r, l), capsule(r, l)}) {
    const double V = rigid::shapeVolume(s);
    const bool isCapsule = s.type == ShapeType::Capsule;
    for (double t : {-0.19, -0.12, -0.05, 0.0, 0.07, 0.15, 0.195}) {
      for (double roll : {0.0, 0.13, kPi / 24}) {  // about the axis: a side or an edge down
        // Axis along world x; water surface at z = t relative to the centre.
        const Mat3 R = rotation(kPi / 2, Vec3::UnitY()) * rotation(roll, Vec3::UnitZ());
        const Vec3 X(0.5, 0.0, 1.0);
        const SubmergedPart p = rigid::submergedPart(s, X, R, lowCorner(), highCorner(X.z() + t));
        double Vexp = l * segmentArea(r, t), Mexp = l * segmentMoment(r, t);
        if (isCapsule) {  // the two hemispheres make one ball cut at the same height
          const double h = t + r;
          Vexp += capVolume(r, h);
          Mexp += -capVolume(r, h) * capCentroidDistance(r, h);
        }
        EXPECT_NEAR(p.volume, Vexp, kLatheVolumeError * V) << "t " << t << " roll " << roll;
        EXPECT_NEAR(p.centroid.z() - X.z(), Mexp / Vexp, kLatheCentroidError * largestDimension(s))
            << "t " << t << " roll " << roll;
      }
    }
  }
}

TEST(Submerged, UprightCylinderIsExactAndCapsuleWithinError) {
  // Cut across its axis the equal-area polygon gives the exact volume pi r^2 h.
  const double r = 0.15, l = 0.6;
  for (double h : {0.05, 0.3, 0.55}) {
    const Vec3 X(0, 0, 2.0);
    const SubmergedPart p =
        rigid::submergedPart(cylinder(r, l), X, Mat3::Identity(), lowCorner(), highCorner(X.z() - 0.5 * l + h));
    EXPECT_NEAR(p.volume, kPi * r * r * h, 1e-12);
    EXPECT_NEAR(p.centroid.z(), X.z() - 0.5 * l + 0.5 * h, 1e-12);
    EXPECT_NEAR(p.centroid.head<2>().norm(), 0.0, 1e-12);
  }
  // Upright capsule cut in its lower hemisphere and in its cylinder.
  const Shape c = capsule(r, l);
  const double V = rigid::shapeVolume(c);
  for (double h : {0.05, 0.1, 0.3, 0.6}) {
    const Vec3 X(0, 0, 0);
    const double bottom = -0.5 * l - r;
    const SubmergedPart p = rigid::submergedPart(c, X, Mat3::Identity(), lowCorner(), highCorner(bottom + h));
    double Vexp, Mexp;
    if (h <= r) {
      Vexp = capVolume(r, h);
      Mexp = Vexp * (-0.5 * l - capCentroidDistance(r, h));
    } else {
      const double hem = 2.0 / 3.0 * kPi * r * r * r, hc = h - r;
      Vexp = hem + kPi * r * r * hc;
      Mexp = hem * (-0.5 * l - 3.0 * r / 8.0) + kPi * r * r * hc * (-0.5 * l + 0.5 * hc);
    }
    EXPECT_NEAR(p.volume, Vexp, kLatheVolumeError * V) << h;
    EXPECT_NEAR(p.centroid.z(), Mexp / Vexp, kLatheCentroidError * largestDimension(c)) << h;
  }
}

TEST(Submerged, TiltedCylinderAndCapsuleMatchTheRayIntegration) {
  double worstV = 0.0, worstC = 0.0;
  for (const Shape& s : {cylinder(0.2, 0.8), cylinder(0.3, 0.2), capsule(0.2, 0.8), capsule(0.25, 0.1)}) {
    const double V = rigid::shapeVolume(s), D = largestDimension(s);
    for (int i = 0; i < 8; ++i) {
      const Mat3 R = rotation(0.4 * i + 0.2, Vec3(1.0, 0.3 * i, 0.1));
      const Vec3 X(0.0, 0.05 * i, 0.1 * (i - 4) * D / 4);
      // One plane, then a corner of the pool (three planes).
      for (int corner = 0; corner < 2; ++corner) {
        const Vec3 mn = corner ? Vec3(-0.05, 0.02, -kBig) : lowCorner();
        const SubmergedPart p = rigid::submergedPart(s, X, R, mn, highCorner(0.0));
        const Reference ref = rayIntegral(s, X, R, mn, highCorner(0.0), 400);
        worstV = std::max(worstV, std::abs(p.volume - ref.volume) / V);
        if (ref.volume > 0.02 * V) worstC = std::max(worstC, (p.centroid - ref.centroid).norm() / D);
        EXPECT_NEAR(p.volume, ref.volume, kLatheVolumeError * V)
            << rigid::shapeTypeName(s.type) << " " << i << " " << corner;
        if (ref.volume > 0.02 * V) {  // the centroid of a sliver is a small lever anyway
          EXPECT_NEAR((p.centroid - ref.centroid).norm(), 0.0, kLatheCentroidError * D)
              << rigid::shapeTypeName(s.type) << " " << i << " " << corner;
        }
      }
    }
  }
  std::printf("cylinder/capsule polyhedra: worst volume error %.2e of V, centroid %.2e of D\n", worstV, worstC);
}

// ---- buoyancy and drag through addMediumForces -------------------------------------------

namespace {

using rigid::test::bodyOf;

rigid::Medium fluid(double density, double viscosity, const Vec3& mn, const Vec3& mx) {
  rigid::Medium m;
  m.name = "m";
  m.type = rigid::FluidType::Custom;
  m.min = mn;
  m.max = mx;
  m.density = density;
  m.viscosity = viscosity;
  return m;
}

// Medium force and torque on a body at X with rotation R, velocity V, angular velocity w.
struct Load {
  Vec3 F, T;
};
Load mediumLoad(const rigid::Medium& m, const rigid::BodyConstants& b, const Vec3& X, const Quat& q, const Vec3& V,
                const Vec3& w, const Vec3& g) {
  rigid::BodyState y;
  y.X = X;
  y.q = q;
  y.P = b.mass * V;
  const Mat3 R = q.toRotationMatrix();
  y.L = R * b.Ibody * R.transpose() * w;
  rigid::BodyAux aux;
  rigid::computeAuxiliaries(b, y, aux);
  aux.F.setZero();
  aux.T.setZero();
  rigid::addMediumForces(m, b, y, g, aux);
  return {aux.F, aux.T};
}

const Vec3 kG(0.0, 0.0, -9.81);

}  // namespace

TEST(Buoyancy, IsTheWeightOfTheDisplacedFluidAtTheCentreOfBuoyancy) {
  const double rho = 998.2, r = 0.1;
  const auto b = bodyOf(sphere(r), 1.0);
  const rigid::Medium water = fluid(rho, 0.0, lowCorner(), highCorner(0.0));
  for (double h : {0.0, 0.03, 0.1, 0.17, 0.2}) {
    const Vec3 X(0, 0, r - h);  // cap of height h below the surface z = 0
    const Load L = mediumLoad(water, b, X, Quat::Identity(), Vec3::Zero(), Vec3::Zero(), kG);
    EXPECT_NEAR(L.F.z(), rho * 9.81 * capVolume(r, h), 1e-12) << h;
    EXPECT_NEAR(L.F.head<2>().norm(), 0.0, 1e-15);
    EXPECT_NEAR(L.T.norm(), 0.0, 1e-15);  // the centroid is below the centre of mass
  }
  // The gravity given is the one used: along x, buoyancy pushes along -x.
  const Load L =
      mediumLoad(water, b, Vec3(0, 0, -1), Quat::Identity(), Vec3::Zero(), Vec3::Zero(), Vec3(3.0, 0.0, 0.0));
  EXPECT_NEAR(L.F.x(), -rho * 3.0 * 4.0 / 3.0 * kPi * r * r * r, 1e-12);
  // Density 0: no buoyancy at all.
  const Load none = mediumLoad(fluid(0.0, 1e-3, lowCorner(), highCorner(0.0)), b, Vec3(0, 0, -1), Quat::Identity(),
                               Vec3::Zero(), Vec3::Zero(), kG);
  EXPECT_EQ(none.F, Vec3::Zero());
  EXPECT_EQ(none.T, Vec3::Zero());
}

TEST(Buoyancy, TiltedFloatingBoxFeelsTheWallSidedRightingMoment) {
  // A 1 x 1 x 0.5 m box floating at draft T = 0.25 m (centre of mass on the waterline),
  // heeled by theta about x. Wall-sided: the displacement stays B L T and the righting
  // lever is GZ = sin(theta) (GM + BM tan^2(theta) / 2), with KB = T/2, KG = 0.25 m,
  // BM = B^2 / (12 T) (valid while neither the deck edge dips nor the bilge emerges:
  // tan(theta) B/2 < T).
  const double rho = 1000.0, g = 9.81, B = 1.0, T = 0.25;
  const auto b = bodyOf(box(1.0, B, 0.5), 250.0);
  const rigid::Medium water = fluid(rho, 0.0, lowCorner(), highCorner(0.0));
  const double V = B * 1.0 * T, BM = B * B / (12.0 * T), GM = T / 2 + BM - 0.25;
  for (double deg : {2.0, 10.0, 20.0, 25.0}) {
    const double th = deg * kPi / 180.0;
    const Quat q(Eigen::AngleAxisd(th, Vec3::UnitX()));
    const Load L = mediumLoad(water, b, Vec3(0.3, -0.2, 0.0), q, Vec3::Zero(), Vec3::Zero(), kG);
    const double GZ = std::sin(th) * (GM + 0.5 * BM * std::tan(th) * std::tan(th));
    EXPECT_NEAR(L.F.z(), rho * g * V, 1e-9 * rho * g * V) << deg;
    // Heeled by +theta about x: the restoring moment is about -x.
    EXPECT_LT(L.T.x(), 0.0) << deg;
    EXPECT_NEAR(L.T.x(), -rho * g * V * GZ, 1e-9 * rho * g * V * GZ) << deg;
    EXPECT_NEAR(L.T.y(), 0.0, 1e-9);
    EXPECT_NEAR(L.T.z(), 0.0, 1e-9);
  }
}

TEST(Drag, ProjectedAreasObeyCauchysFormula) {
  // For a convex body the projected area averaged over all directions is S/4.
  const int n = 20000;
  for (const Shape& s : {sphere(0.3), box(0.2, 0.5, 1.3), cylinder(0.2, 0.9), capsule(0.1, 0.6), cylinder(0.5, 0.1)}) {
    double sum = 0.0;
    for (int i = 0; i < n; ++i) {  // Fibonacci lattice on the unit sphere
      const double z = 1.0 - (2.0 * i + 1.0) / n;
      const double phi = i * kPi * (3.0 - std::sqrt(5.0));
      const double rxy = std::sqrt(1.0 - z * z);
      sum += rigid::projectedArea(s, Vec3(rxy * std::cos(phi), rxy * std::sin(phi), z));
    }
    EXPECT_NEAR(sum / n, rigid::surfaceArea(s) / 4.0, 1e-4 * rigid::surfaceArea(s)) << rigid::shapeTypeName(s.type);
  }
  // Along the axes of a box: the face's area.
  EXPECT_DOUBLE_EQ(rigid::projectedArea(box(0.2, 0.5, 1.3), Vec3::UnitY()), 0.2 * 1.3);
  EXPECT_DOUBLE_EQ(rigid::projectedArea(cylinder(0.2, 0.9), Vec3::UnitZ()), kPi * 0.04);
  EXPECT_DOUBLE_EQ(rigid::projectedArea(capsule(0.1, 0.6), Vec3::UnitX()), kPi * 0.01 + 2 * 0.1 * 0.6);
}

TEST(Drag, SphereInAViscousFluidFeelsStokesDrag) {
  const double mu = 0.37, r = 0.12;
  const auto b = bodyOf(sphere(r), 2.0);
  const rigid::Medium syrup = fluid(0.0, mu, lowCorner(), highCorner(kBig));
  const Vec3 V(0.3, -1.2, 2.5), w(1.5, -0.5, 4.0);
  const Load L = mediumLoad(syrup, b, Vec3(0, 0, 1), Quat::Identity(), V, w, kG);
  EXPECT_LT((L.F + 6.0 * kPi * mu * r * V).norm(), 1e-13 * L.F.norm());
  // Rotational Stokes drag: -8 pi mu r^3 omega.
  EXPECT_LT((L.T + 8.0 * kPi * mu * r * r * r * w).norm(), 1e-13 * L.T.norm());
}

TEST(Drag, SphereInADenseFluidFeelsQuadraticDrag) {
  const double rho = 998.2, r = 0.05;
  const auto b = bodyOf(sphere(r), 2.0);
  const rigid::Medium water = fluid(rho, 0.0, lowCorner(), highCorner(kBig));
  const Vec3 V(0.3, -1.2, 2.5);
  const Load L = mediumLoad(water, b, Vec3(0, 0, 1), Quat::Identity(), V, Vec3::Zero(), Vec3::Zero());
  const Vec3 expected = -0.5 * rho * 0.47 * kPi * r * r * V.norm() * V;
  EXPECT_LT((L.F - expected).norm(), 1e-13 * expected.norm());
}

TEST(Drag, BoxQuadraticDragUsesItsProjectedArea) {
  const double rho = 1000.0;
  const auto b = bodyOf(box(0.2, 0.4, 0.8), 5.0);
  const rigid::Medium water = fluid(rho, 0.0, lowCorner(), highCorner(kBig));
  const Quat q(Eigen::AngleAxisd(0.6, Vec3(1, 2, 3).normalized()));
  const Mat3 R = q.toRotationMatrix();
  const Vec3 V(0.5, 0.7, -1.1);
  const Load L = mediumLoad(water, b, Vec3::Zero(), q, V, Vec3::Zero(), Vec3::Zero());
  // Shadow of the box: the sum over its three face pairs of |n . v^| A.
  const Vec3 d = V.normalized();
  const double A = std::abs(d.dot(R.col(0))) * 0.4 * 0.8 + std::abs(d.dot(R.col(1))) * 0.2 * 0.8 +
                   std::abs(d.dot(R.col(2))) * 0.2 * 0.4;
  const Vec3 expected = -0.5 * rho * 1.05 * A * V.norm() * V;
  EXPECT_LT((L.F - expected).norm(), 1e-13 * expected.norm());
}

TEST(Drag, BoxAngularPressureDragIsTheFlatStripIntegral) {
  // Spinning about body z at omega: each face normal to x or y, its element at s from the
  // axis moving at omega s, pushes back 1/2 rho Cd (omega s)^2 dA with lever |s|. Summed
  // here on a grid over the four faces.
  const double rho = 1000.0, lx = 0.3, ly = 0.5, lz = 0.7, w = 3.0;
  const auto b = bodyOf(box(lx, ly, lz), 40.0);
  const rigid::Medium water = fluid(rho, 0.0, lowCorner(), highCorner(kBig));
  const int n = 20000;
  double T = 0.0;
  for (int face = 0; face < 2; ++face) {
    const double width = face == 0 ? ly : lx;  // faces normal to x span y, and vice versa
    for (int i = 0; i < n; ++i) {
      const double s = width * ((i + 0.5) / n - 0.5);
      T += 2.0 * 0.5 * rho * 1.05 * (w * s) * (w * s) * std::abs(s) * lz * width / n;
    }
  }
  const Quat q(Eigen::AngleAxisd(0.4, Vec3(1, -1, 2).normalized()));
  const Vec3 axis = q.toRotationMatrix().col(2);
  const Load L = mediumLoad(water, b, Vec3::Zero(), q, Vec3::Zero(), w * axis, Vec3::Zero());
  EXPECT_NEAR(L.T.dot(axis), -T, 1e-6 * T);
  EXPECT_LT((L.T - L.T.dot(axis) * axis).norm(), 1e-12 * T);
  EXPECT_EQ(L.F, Vec3::Zero());  // the centre of mass is still, and fully submerged
}

TEST(Drag, OnlyTheSubmergedFractionFeelsDragAtTheCentreOfBuoyancy) {
  const double mu = 0.5, r = 0.2;
  const auto b = bodyOf(sphere(r), 1.0);
  const rigid::Medium syrup = fluid(0.0, mu, lowCorner(), highCorner(0.0));
  const Vec3 V(1.0, 0.0, 0.0);
  // Centre on the surface: half the ball is in; its centroid is 3r/8 below the centre.
  const Load half = mediumLoad(syrup, b, Vec3::Zero(), Quat::Identity(), V, Vec3::Zero(), kG);
  const Vec3 F = -0.5 * 6.0 * kPi * mu * r * V;
  EXPECT_LT((half.F - F).norm(), 1e-13 * F.norm());
  const Vec3 lever(0.0, 0.0, -3.0 * r / 8.0);
  EXPECT_LT((half.T - lever.cross(F)).norm(), 1e-12 * F.norm() * r);
  // Out of the fluid: nothing, to the bit.
  const Load out = mediumLoad(syrup, b, Vec3(0, 0, r + 1e-9), Quat::Identity(), V, Vec3(1, 2, 3), kG);
  EXPECT_EQ(out.F, Vec3::Zero());
  EXPECT_EQ(out.T, Vec3::Zero());
}

TEST(Drag, NeverGivesEnergy) {
  // With gravity off buoyancy is zero and the medium's power F.V + T.omega is the drag's:
  // never positive, for any shape, pose, and partial immersion.
  const rigid::Medium m = fluid(998.2, 1e-3, lowCorner(), highCorner(0.0));
  int n = 0;
  for (const Shape& s : {sphere(0.2), box(0.2, 0.4, 0.6), cylinder(0.1, 0.5), capsule(0.1, 0.3)}) {
    const auto b = bodyOf(s, 3.0);
    for (int i = 0; i < 40; ++i) {
      const Quat q(Eigen::AngleAxisd(0.3 * i, Vec3(std::sin(i), std::cos(2.0 * i), 0.3)));
      const Vec3 X(0.0, 0.0, 0.02 * (i - 20));
      const Vec3 V(std::sin(0.7 * i), std::cos(1.3 * i), std::sin(2.1 * i));
      const Vec3 w(3 * std::cos(0.4 * i), -2 * std::sin(1.1 * i), std::cos(0.9 * i));
      const Load L = mediumLoad(m, b, X, q, V, w, Vec3::Zero());
      EXPECT_LE(L.F.dot(V) + L.T.dot(w), 1e-12) << rigid::shapeTypeName(s.type) << " " << i;
      if (L.F.norm() > 0.0) ++n;
    }
  }
  EXPECT_GT(n, 80);  // most of the poses were in the fluid
}

TEST(Medium, CylinderAndCapsuleDragCoefficientsFollowTheTables) {
  // Cross flow on the side l d: 0.82 at l/d = 10; axial flow on the end: 0.85 at l/d = 2.
  const Shape c = cylinder(0.05, 1.0);  // l/d = 10
  EXPECT_NEAR(rigid::dragArea(c, Vec3::UnitX()), 0.82 * 0.1 * 1.0, 1e-12);
  const Shape c2 = cylinder(0.1, 0.4);  // l/d = 2
  EXPECT_NEAR(rigid::dragArea(c2, Vec3::UnitZ()), 0.85 * kPi * 0.01, 1e-12);
  // A capsule end-on: the ball's 0.47 on pi r^2.
  EXPECT_NEAR(rigid::dragArea(capsule(0.1, 0.4), -Vec3::UnitZ()), 0.47 * kPi * 0.01, 1e-12);
  // Linear drag of a sphere is Stokes' 6 pi r; of a cube face-on, Leith's 6 pi (r_n/3 + 2 r_s/3).
  EXPECT_NEAR(rigid::stokesFactor(sphere(0.3), Vec3::UnitX()), 6 * kPi * 0.3, 1e-13);
  const double a = 0.2;
  EXPECT_NEAR(rigid::stokesFactor(box(a, a, a), Vec3::UnitX()),
              6 * kPi * (a / std::sqrt(kPi) / 3 + 2.0 / 3 * a * std::sqrt(6 / (4 * kPi))), 1e-13);
}
