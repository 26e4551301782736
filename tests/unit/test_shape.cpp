// Mass properties of the solid shapes against closed forms and an independent
// numerical integration computed here, never against the code under test.
#include <gtest/gtest.h>

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "body.h"
#include "builders.h"
#include "shape.h"

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRel = 1e-13;  // closed forms: only rounding differs

using rigid::test::box;
using rigid::test::capsule;
using rigid::test::cylinder;
using rigid::test::sphere;

void expectRelNear(double expected, double actual, double rel, const char* what) {
  EXPECT_NEAR(actual, expected, rel * std::abs(expected)) << what;
}

// Composite Simpson rule over [a, b] with n (even) intervals.
double simpson(const std::function<double(double)>& f, double a, double b, int n) {
  const double h = (b - a) / n;
  double s = f(a) + f(b);
  for (int i = 1; i < n; ++i) s += f(a + i * h) * (i % 2 ? 4.0 : 2.0);
  return s * h / 3.0;
}

// Mass properties of a homogeneous solid of revolution about z with radius profile
// rho(z) on [z0, z1], by slicing it into thin discs: a disc of mass dm and radius rho
// at height z adds dm rho^2/2 about z and dm (rho^2/4 + z^2) about a transverse axis
// through the origin. Integrated piecewise so that every piece is smooth.
struct Revolution {
  double volume = 0, Ixx = 0, Izz = 0;  // Ixx, Izz per unit density
};
void addPiece(Revolution& out, const std::function<double(double)>& rho, double z0, double z1) {
  const int n = 20000;
  out.volume += simpson(
      [&](double z) {
        const double p = rho(z);
        return kPi * p * p;
      },
      z0, z1, n);
  out.Izz += simpson(
      [&](double z) {
        const double p = rho(z);
        return 0.5 * kPi * p * p * p * p;
      },
      z0, z1, n);
  out.Ixx += simpson(
      [&](double z) {
        const double p = rho(z);
        return kPi * p * p * (0.25 * p * p + z * z);
      },
      z0, z1, n);
}

}  // namespace

TEST(Shape, SphereVolumeAndInertia) {
  const double r = 0.37, m = 2.5;
  expectRelNear(4.0 / 3.0 * kPi * r * r * r, rigid::shapeVolume(sphere(r)), kRel, "volume");
  const rigid::Vec3 I = rigid::solidPrincipalInertia(sphere(r), m);
  for (int i = 0; i < 3; ++i) expectRelNear(2.0 / 5.0 * m * r * r, I[i], kRel, "I");
}

TEST(Shape, BoxVolumeAndInertia) {
  const double a = 0.3, b = 1.7, c = 0.05, m = 4.0;
  expectRelNear(a * b * c, rigid::shapeVolume(box(a, b, c)), kRel, "volume");
  const rigid::Vec3 I = rigid::solidPrincipalInertia(box(a, b, c), m);
  expectRelNear(m * (b * b + c * c) / 12.0, I.x(), kRel, "Ixx");
  expectRelNear(m * (a * a + c * c) / 12.0, I.y(), kRel, "Iyy");
  expectRelNear(m * (a * a + b * b) / 12.0, I.z(), kRel, "Izz");
}

TEST(Shape, CylinderVolumeAndInertia) {
  const double r = 0.2, l = 1.3, m = 3.0;
  expectRelNear(kPi * r * r * l, rigid::shapeVolume(cylinder(r, l)), kRel, "volume");
  const rigid::Vec3 I = rigid::solidPrincipalInertia(cylinder(r, l), m);
  expectRelNear(m * (3 * r * r + l * l) / 12.0, I.x(), kRel, "Ixx");
  expectRelNear(m * (3 * r * r + l * l) / 12.0, I.y(), kRel, "Iyy");
  expectRelNear(0.5 * m * r * r, I.z(), kRel, "Izz (axis)");
}

TEST(Shape, CylinderInertiaMatchesNumericalIntegration) {
  const double r = 0.2, l = 1.3, m = 3.0;
  Revolution rev;
  addPiece(
      rev, [&](double) { return r; }, -l / 2, l / 2);
  const double rhoDensity = m / rev.volume;
  const rigid::Vec3 I = rigid::solidPrincipalInertia(cylinder(r, l), m);
  expectRelNear(rev.volume, rigid::shapeVolume(cylinder(r, l)), 1e-10, "volume");
  expectRelNear(rhoDensity * rev.Ixx, I.x(), 1e-10, "Ixx");
  expectRelNear(rhoDensity * rev.Izz, I.z(), 1e-10, "Izz");
}

// Capsule: a cylinder of length l plus two hemispherical caps, axis z. Checked against
// a numerical integration over the solid (independent of any cap formula).
TEST(Shape, CapsuleMatchesNumericalIntegration) {
  const double m = 5.0;
  for (const auto& [r, l] : {std::pair{0.25, 1.0}, std::pair{0.5, 0.2}, std::pair{0.1, 3.0}}) {
    Revolution rev;
    const double h = l / 2;
    addPiece(
        rev, [&](double z) { return std::sqrt(std::max(0.0, r * r - (z + h) * (z + h))); }, -h - r, -h);
    addPiece(
        rev, [&](double) { return r; }, -h, h);
    addPiece(
        rev, [&](double z) { return std::sqrt(std::max(0.0, r * r - (z - h) * (z - h))); }, h, h + r);
    const double density = m / rev.volume;
    SCOPED_TRACE("r=" + std::to_string(r) + " l=" + std::to_string(l));
    // Simpson on the caps: sqrt profile squared is polynomial, so the integrands are
    // polynomials of degree <= 4; 20000 intervals leave ~1e-16 relative error.
    const double tol = 1e-10;
    expectRelNear(rev.volume, rigid::shapeVolume(capsule(r, l)), tol, "volume");
    const rigid::Vec3 I = rigid::solidPrincipalInertia(capsule(r, l), m);
    expectRelNear(density * rev.Ixx, I.x(), tol, "Ixx");
    expectRelNear(density * rev.Ixx, I.y(), tol, "Iyy");
    expectRelNear(density * rev.Izz, I.z(), tol, "Izz (axis)");
  }
}

// The same capsule from cylinder + two hemispheres derived here: a solid hemisphere
// of mass mc has 2/5 mc r^2 about its axis and about any diameter of its flat face;
// its centroid is 3r/8 from the face, so about its own centroid (transverse)
// I = 2/5 mc r^2 - mc (3r/8)^2, then shifted by d = l/2 + 3r/8 to the capsule centre.
TEST(Shape, CapsuleMatchesCylinderPlusHemispheres) {
  const double r = 0.3, l = 0.8, m = 7.0;
  const double vCyl = kPi * r * r * l, vHemi = 2.0 / 3.0 * kPi * r * r * r;
  const double vol = vCyl + 2 * vHemi;
  const double mCyl = m * vCyl / vol, mH = m * vHemi / vol;
  const double d = l / 2 + 3 * r / 8;
  const double hemiTransverseCm = 0.4 * mH * r * r - mH * (3 * r / 8) * (3 * r / 8);
  const double Ixx = mCyl * (3 * r * r + l * l) / 12 + 2 * (hemiTransverseCm + mH * d * d);
  const double Izz = 0.5 * mCyl * r * r + 2 * 0.4 * mH * r * r;
  expectRelNear(vol, rigid::shapeVolume(capsule(r, l)), 1e-13, "volume");
  const rigid::Vec3 I = rigid::solidPrincipalInertia(capsule(r, l), m);
  expectRelNear(Ixx, I.x(), 1e-12, "Ixx");
  expectRelNear(Ixx, I.y(), 1e-12, "Iyy");
  expectRelNear(Izz, I.z(), 1e-12, "Izz");
}

TEST(Shape, CapsuleOfZeroLengthIsASphere) {
  const double r = 0.4, m = 1.5;
  expectRelNear(4.0 / 3.0 * kPi * r * r * r, rigid::shapeVolume(capsule(r, 0.0)), kRel, "volume");
  const rigid::Vec3 I = rigid::solidPrincipalInertia(capsule(r, 0.0), m);
  for (int i = 0; i < 3; ++i) expectRelNear(0.4 * m * r * r, I[i], kRel, "I");
}

TEST(Shape, InertiaIsLinearInMass) {
  for (const rigid::Shape& s : {sphere(0.3), box(0.1, 0.2, 0.3), cylinder(0.1, 0.5), capsule(0.1, 0.5)}) {
    const rigid::Vec3 I1 = rigid::solidPrincipalInertia(s, 1.0);
    const rigid::Vec3 I7 = rigid::solidPrincipalInertia(s, 7.0);
    for (int i = 0; i < 3; ++i) expectRelNear(7.0 * I1[i], I7[i], 1e-14, rigid::shapeTypeName(s.type));
  }
}

TEST(Body, SetMassScalesShapeInertia) {
  rigid::BodyConstants b;
  b.shape = box(0.2, 0.4, 1.0);
  ASSERT_TRUE(b.inertiaFromShape);
  rigid::setMass(b, 2.0);
  EXPECT_EQ(b.mass, 2.0);
  const rigid::Vec3 expected2 = 2.0 / 12.0 * rigid::Vec3(0.16 + 1.0, 0.04 + 1.0, 0.04 + 0.16);
  rigid::setMass(b, 6.0);
  EXPECT_EQ(b.mass, 6.0);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const double want = r == c ? 3.0 * expected2[r] : 0.0;
      EXPECT_NEAR(b.Ibody(r, c), want, 1e-14) << r << "," << c;
      EXPECT_NEAR(b.IbodyInv(r, c), r == c ? 1.0 / want : 0.0, 1e-12) << r << "," << c;
    }
  EXPECT_TRUE(b.inertiaFromShape);
}

TEST(Body, SetInertiaIsKeptWhenMassChanges) {
  rigid::BodyConstants b;
  b.shape = sphere(0.5);
  rigid::setMass(b, 1.0);
  rigid::Mat3 I;
  I << 2.0, 0.3, -0.1, 0.3, 1.5, 0.2, -0.1, 0.2, 1.8;
  rigid::setInertia(b, I);
  EXPECT_FALSE(b.inertiaFromShape);
  rigid::setMass(b, 10.0);
  EXPECT_EQ(b.mass, 10.0);
  EXPECT_EQ(b.Ibody, I);  // bitwise: not rescaled
  const rigid::Mat3 Iinv = I.fullPivLu().inverse();
  EXPECT_LT((b.IbodyInv - Iinv).cwiseAbs().maxCoeff(), 1e-13);
  EXPECT_LT((b.IbodyInv * I - rigid::Mat3::Identity()).cwiseAbs().maxCoeff(), 1e-14);
}
