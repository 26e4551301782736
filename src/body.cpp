#include "body.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace rigid {

namespace {

// Ibody and what is derived from it once: its inverse, principal moments and axes.
void storeInertia(BodyConstants& body, const Mat3& Ibody) {
  body.Ibody = Ibody;
  // Symmetric positive definite: invert through the eigen-decomposition, which stays
  // accurate for the strongly anisotropic (needle-like) tensors that a scene may give.
  Eigen::SelfAdjointEigenSolver<Mat3> eig(Ibody);
  body.IbodyInv = eig.eigenvectors() * eig.eigenvalues().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
  Mat3 axes = eig.eigenvectors();
  if (axes.determinant() < 0.0) axes.col(2) = -axes.col(2);  // a rotation, not a reflection
  body.principalMoments = eig.eigenvalues();
  body.principalFrame = Quat(axes).normalized();
}

}  // namespace

void setMass(BodyConstants& body, double mass) {
  body.mass = mass;
  if (!body.inertiaFromShape) return;
  if (body.shape.type == ShapeType::Mesh || body.shape.type == ShapeType::Compound) {  // axes need not be principal
    storeInertia(body, solidInertia(body.shape, mass));
    return;
  }
  const Vec3 I = solidPrincipalInertia(body.shape, mass);
  body.Ibody = I.asDiagonal();
  body.IbodyInv = I.cwiseInverse().asDiagonal();
  body.principalMoments = I;
  body.principalFrame = Quat::Identity();
}

void setInertia(BodyConstants& body, const Mat3& Ibody) {
  body.inertiaFromShape = false;
  storeInertia(body, Ibody);
}

void makeDriven(BodyConstants& body) {
  body.motion = Motion::Driven;
  body.inertiaFromShape = false;
  body.mass = 1.0;
  body.Ibody = body.IbodyInv = Mat3::Identity();
  body.principalMoments = Vec3::Ones();
  body.principalFrame = Quat::Identity();
}

void computeAuxiliaries(const BodyConstants& body, const BodyState& y, BodyAux& aux) {
  aux.V = y.P / body.mass;
  aux.R = rotationOf(y.q);
  aux.Iinv = aux.R * body.IbodyInv * aux.R.transpose();
  aux.omega = aux.Iinv * y.L;
}

void computeVelocities(const BodyConstants& body, const BodyState& y, BodyAux& aux) {
  aux.V = y.P / body.mass;
  aux.R = rotationOf(y.q);
  aux.omega = angularVelocity(body, aux.R, y.L);
}

BodyState initialState(const BodyConstants& body) {
  BodyState y;
  y.X = body.start.position;
  y.q = body.start.orientation.normalized();
  y.P = body.mass * body.start.velocity;
  const Mat3 R = y.q.toRotationMatrix();
  y.L = R * body.Ibody * R.transpose() * body.start.angularVelocity;
  return y;
}

bool isFinite(const BodyState& y) {
  return y.X.allFinite() && y.q.coeffs().allFinite() && y.P.allFinite() && y.L.allFinite();
}

}  // namespace rigid
