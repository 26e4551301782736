#include "integrator.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <utility>

#include "body_packs.h"
#include "dynamics.h"
#include "world.h"

namespace rigid {

namespace {

// out = y + h * k, body by body.
void addScaled(const std::vector<int>& bodies, const std::vector<BodyState>& y, double h,
               const std::vector<BodyDerivative>& k, std::vector<BodyState>& out) {
  for (int i : bodies) {
    out[i].X = y[i].X + h * k[i].dX;
    out[i].q.coeffs() = y[i].q.coeffs() + h * k[i].dq;
    out[i].P = y[i].P + h * k[i].dP;
    out[i].L = y[i].L + h * k[i].dL;
  }
}

void eulerStep(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
               std::vector<BodyState>& next) {
  std::vector<BodyDerivative>& k1 = d.scratch.k[0];
  evaluateDerivative(m, bodies, d.input, d.Y, d.aux, k1);
  addScaled(bodies, d.Y, h, k1, next);
}

// dq/dt = 1/2 q (0, omega_body) with omega_body = Ibody^-1 R^T L, for q of any norm.
// The body-frame form equals 1/2 (0, omega) q and saves the product by R that the
// world-frame omega needs.
EIGEN_STRONG_INLINE QuatPack orientationRate(const QuatPack& q, const Pack (&L)[3], const Pack (&Iinv)[9]) {
  const RotationPack R = rotationOf(q);
  Pack Lbody[3], half[3];
  multiplyTransposed(R.r, L, Lbody);
  multiply(Iinv, Lbody, half);
  const Pack o0 = 0.5 * half[0], o1 = 0.5 * half[1], o2 = 0.5 * half[2];
  return {-(q.x * o0 + q.y * o1 + q.z * o2), q.w * o0 + q.y * o2 - q.z * o1, q.w * o1 + q.z * o0 - q.x * o2,
          q.w * o2 + q.x * o1 - q.y * o0};
}

EIGEN_STRONG_INLINE QuatPack plus(const QuatPack& q, double c, const QuatPack& k) {
  return {q.w + c * k.w, q.x + c * k.x, q.y + c * k.y, q.z + c * k.z};
}

// RK4 when the forces are held over the step (forcesHeldOverStep): dP/dt = F and
// dL/dt = T are constant, so the momenta at the stages are P + c h F and L + c h T
// exactly and X(t + h) = X + h (P + h F / 2) / M, which is what the classic tableau
// gives them; only the orientation needs its four stage derivatives, taken for four
// bodies at once, with the stages in registers instead of the k arrays. Free bodies
// are the common case, and this is their cost per step.
void rk4HeldForcesStep(const WorldModel& m, WorldData& d, double h, const std::vector<int>& bodies,
                       std::vector<BodyState>& next) {
  const size_t n = bodies.size();
  const double w1 = h / 6.0, w2 = h / 3.0;
  for (size_t first = 0; first < n; first += kLanes) {
    QuatPack q;
    Pack L[3], Lhalf[3], Lend[3], Iinv[9];
    for (int lane = 0; lane < kLanes; ++lane) {
      const int i = bodies[laneBody(first, lane, n)];
      const BodyState& y = d.Y[i];
      BodyAux& aux = d.aux[i];
      accumulateAppliedForces(m, m.bodies[i], d.input[i], y, aux);
      setLane(Iinv, lane, m.bodies[i].IbodyInv);
      setLane(q, lane, y.q);
      setLane(L, lane, y.L);
      setLane(Lhalf, lane, y.L + 0.5 * h * aux.T);
      setLane(Lend, lane, y.L + h * aux.T);
    }
    const QuatPack k1 = orientationRate(q, L, Iinv);
    const QuatPack k2 = orientationRate(plus(q, 0.5 * h, k1), Lhalf, Iinv);
    const QuatPack k3 = orientationRate(plus(q, 0.5 * h, k2), Lhalf, Iinv);
    const QuatPack k4 = orientationRate(plus(q, h, k3), Lend, Iinv);
    // Each k is scaled before the sum, as in rk4Step.
    // one component a line
    // clang-format off
    const QuatPack qNext = {q.w + (w1 * k1.w + w2 * k2.w + w2 * k3.w + w1 * k4.w),
                            q.x + (w1 * k1.x + w2 * k2.x + w2 * k3.x + w1 * k4.x),
                            q.y + (w1 * k1.y + w2 * k2.y + w2 * k3.y + w1 * k4.y),
                            q.z + (w1 * k1.z + w2 * k2.z + w2 * k3.z + w1 * k4.z)};
    // clang-format on
    for (int lane = 0; lane < kLanes && first + lane < n; ++lane) {
      const int i = bodies[first + lane];
      const BodyState& y = d.Y[i];
      const BodyAux& aux = d.aux[i];
      BodyState& out = next[i];
      out.q = Quat(qNext.w[lane], qNext.x[lane], qNext.y[lane], qNext.z[lane]);
      out.X = y.X + (h / m.bodies[i].mass) * (y.P + 0.5 * h * aux.F);
      out.P = y.P + h * aux.F;
      out.L = y.L + h * aux.T;
    }
  }
}

// Classic RK4 of the bodies in `bodies` (a body's derivative depends on its own state
// alone: bodies interact only through contacts, answered after the step).
void rk4Bodies(const WorldModel& m, WorldData& d, double h, const std::vector<int>& bodies,
               std::vector<BodyState>& next) {
  std::vector<BodyDerivative>& k1 = d.scratch.k[0];
  std::vector<BodyDerivative>& k2 = d.scratch.k[1];
  std::vector<BodyDerivative>& k3 = d.scratch.k[2];
  std::vector<BodyDerivative>& k4 = d.scratch.k[3];
  std::vector<BodyState>& stage = d.scratch.stage;
  auto derivative = [&](const std::vector<BodyState>& Y, std::vector<BodyDerivative>& k) {
    for (int i : bodies) evaluateBodyDerivative(m, m.bodies[i], d.input[i], Y[i], d.aux[i], k[i]);
  };
  auto toStage = [&](double c, const std::vector<BodyDerivative>& k) {
    for (int i : bodies) {
      stage[i].X = d.Y[i].X + c * k[i].dX;
      stage[i].q.coeffs() = d.Y[i].q.coeffs() + c * k[i].dq;
      stage[i].P = d.Y[i].P + c * k[i].dP;
      stage[i].L = d.Y[i].L + c * k[i].dL;
    }
  };
  derivative(d.Y, k1);
  toStage(0.5 * h, k1);
  derivative(stage, k2);
  toStage(0.5 * h, k2);
  derivative(stage, k3);
  toStage(h, k3);
  derivative(stage, k4);
  // Each k is scaled before the sum, so that derivatives near the largest double do
  // not overflow in k1 + 2 k2 + 2 k3 + k4 when the step itself is finite.
  const double w1 = h / 6.0, w2 = h / 3.0;
  for (int i : bodies) {
    const BodyState& y = d.Y[i];
    BodyState& out = next[i];
    out.X = y.X + (w1 * k1[i].dX + w2 * k2[i].dX + w2 * k3[i].dX + w1 * k4[i].dX);
    out.q.coeffs() = y.q.coeffs() + (w1 * k1[i].dq + w2 * k2[i].dq + w2 * k3[i].dq + w1 * k4[i].dq);
    out.P = y.P + (w1 * k1[i].dP + w2 * k2[i].dP + w2 * k3[i].dP + w1 * k4[i].dP);
    out.L = y.L + (w1 * k1[i].dL + w2 * k2[i].dL + w2 * k3[i].dL + w1 * k4[i].dL);
  }
}

// Bodies whose forces are held over the step (forcesHeldOverStep: no medium) take the
// packed kernel; the others the classic stages.
void rk4Step(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
             std::vector<BodyState>& next) {
  std::vector<int>& held = d.scratch.held;
  std::vector<int>& felt = d.scratch.felt;
  held.clear();
  felt.clear();
  for (int i : bodies) (forcesHeldOverStep(m, m.bodies[i]) ? held : felt).push_back(i);
  if (!held.empty()) rk4HeldForcesStep(m, d, h, held, next);
  if (!felt.empty()) rk4Bodies(m, d, h, felt, next);
}

// The free rotation of one body for a time tau with world angular momentum L, split
// into exact rotations about its principal axes (Dullweber, Leimkuhler & McLachlan
// 1997): R1(tau/2) R2(tau/2) R3(tau) R2(tau/2) R1(tau/2). Each keeps L and one term
// of the kinetic energy exactly, so |L| is exact and the energy error stays bounded.
Quat freeRotation(const BodyConstants& body, const Quat& q, const Vec3& L, double tau) {
  static constexpr int kAxis[5] = {0, 1, 2, 1, 0};
  static constexpr double kFraction[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
  Quat qP = q * body.principalFrame;  // principal axes -> world
  for (int s = 0; s < 5; ++s) {
    const int k = kAxis[s];
    const double Lk = (qP.conjugate() * L)[k];  // body (principal) component
    const double theta = kFraction[s] * tau * Lk / body.principalMoments[k];
    Vec3 axis = Vec3::Zero();
    axis[k] = 1.0;
    qP = qP * Quat(Eigen::AngleAxisd(theta, axis));
  }
  return (qP * body.principalFrame.conjugate()).normalized();
}

// Semi-implicit (symplectic) Euler, the game engines' choice, on the rotation group:
// the momenta take the forces of the step's start (kick), then X moves with the new
// velocity and the orientation follows the free rotation under the new L (drift).
// Turning q by the new omega held for the step, as game engines do, is Lie-Euler: a
// torque-free body's energy then grows by ~(h |omega|)^2 a step and a needle-like
// body blows up (scripts/stress.sh). The splitting drift keeps |L| exactly and the
// energy bounded; with forces the method stays first order.
void symplecticEulerStep(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
                         std::vector<BodyState>& next) {
  std::vector<BodyDerivative>& k1 = d.scratch.k[0];
  evaluateDerivative(m, bodies, d.input, d.Y, d.aux, k1);
  for (int i : bodies) {
    const BodyState& y = d.Y[i];
    BodyState& out = next[i];
    out.P = y.P + h * k1[i].dP;
    out.L = y.L + h * k1[i].dL;
    out.X = y.X + h / m.bodies[i].mass * out.P;
    out.q = freeRotation(m.bodies[i], y.q, out.L, h);
  }
}

// Kick-drift-kick: half a step of forces on the momenta, the positions drift and the
// orientation turns freely with the half-kicked L, half a step of the new forces.
// Forces that depend on velocity (drag) are evaluated at the end with the momenta
// predicted to the end of the step (P + h F), not the half-kicked ones, which would
// cost the method its second order.
void splittingStep(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
                   std::vector<BodyState>& next) {
  std::vector<BodyDerivative>& k = d.scratch.k[0];
  std::vector<BodyState>& end = d.scratch.stage;
  evaluateDerivative(m, bodies, d.input, d.Y, d.aux, k);
  for (int i : bodies) {
    const BodyState& y = d.Y[i];
    BodyState& out = next[i];
    out.P = y.P + 0.5 * h * k[i].dP;
    out.L = y.L + 0.5 * h * k[i].dL;
    out.X = y.X + h / m.bodies[i].mass * out.P;
    out.q = freeRotation(m.bodies[i], y.q, out.L, h);
    end[i] = out;
    end[i].P = y.P + h * k[i].dP;
    end[i].L = y.L + h * k[i].dL;
  }
  evaluateDerivative(m, bodies, d.input, end, d.aux, k);
  for (int i : bodies) {
    next[i].P += 0.5 * h * k[i].dP;
    next[i].L += 0.5 * h * k[i].dL;
  }
}

// dexp^-1_u(v) on so(3), truncated after the terms a fourth-order method needs.
Vec3 dexpInverse(const Vec3& u, const Vec3& v) { return v - 0.5 * u.cross(v) + (1.0 / 12.0) * u.cross(u.cross(v)); }

// Runge-Kutta-Munthe-Kaas 4: the classic tableau applied to the rotation vector of
// q = exp(Theta) q0 (world frame) and to X, P, L; q moves only by exponentials, so it
// is unit by construction.
void lieRk4Step(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
                std::vector<BodyState>& next) {
  // Each stage's rotation increment h dexp^-1(u, omega) is kept in its dq.head<3>().
  std::vector<BodyDerivative>* ks[4] = {&d.scratch.k[0], &d.scratch.k[1], &d.scratch.k[2], &d.scratch.k[3]};
  std::vector<BodyDerivative>& k1 = *ks[0];
  std::vector<BodyDerivative>& k2 = *ks[1];
  std::vector<BodyDerivative>& k3 = *ks[2];
  std::vector<BodyDerivative>& k4 = *ks[3];
  std::vector<BodyState>& stage = d.scratch.stage;
  std::vector<Vec3>& theta = d.scratch.u;
  const double c[4] = {0.0, 0.5, 0.5, 1.0};
  for (int s = 0; s < 4; ++s) {
    std::vector<BodyDerivative>& k = *ks[s];
    if (s == 0) {
      evaluateDerivative(m, bodies, d.input, d.Y, d.aux, k);
      for (int i : bodies) k[i].dq.head<3>() = h * d.aux[i].omega;
      continue;
    }
    const std::vector<BodyDerivative>& prev = *ks[s - 1];
    for (int i : bodies) {
      const BodyState& y = d.Y[i];
      const Vec3 u = c[s] * Vec3(prev[i].dq.head<3>());
      theta[i] = u;
      stage[i].X = y.X + c[s] * h * prev[i].dX;
      stage[i].P = y.P + c[s] * h * prev[i].dP;
      stage[i].L = y.L + c[s] * h * prev[i].dL;
      stage[i].q = rotationQuaternion(u) * y.q;
    }
    evaluateDerivative(m, bodies, d.input, stage, d.aux, k);
    for (int i : bodies) k[i].dq.head<3>() = h * dexpInverse(theta[i], d.aux[i].omega);
  }
  const double w1 = h / 6.0, w2 = h / 3.0;
  for (int i : bodies) {
    const BodyState& y = d.Y[i];
    BodyState& out = next[i];
    out.X = y.X + (w1 * k1[i].dX + w2 * k2[i].dX + w2 * k3[i].dX + w1 * k4[i].dX);
    out.P = y.P + (w1 * k1[i].dP + w2 * k2[i].dP + w2 * k3[i].dP + w1 * k4[i].dP);
    out.L = y.L + (w1 * k1[i].dL + w2 * k2[i].dL + w2 * k3[i].dL + w1 * k4[i].dL);
    const Vec3 Theta = (Vec3(k1[i].dq.head<3>()) + 2.0 * Vec3(k2[i].dq.head<3>()) + 2.0 * Vec3(k3[i].dq.head<3>()) +
                        Vec3(k4[i].dq.head<3>())) /
                       6.0;
    out.q = rotationQuaternion(Theta) * y.q;
  }
}

// Dormand-Prince 5(4) (Hairer, Norsett & Wanner, Solving ODEs I, table 5.2).
constexpr double kC[7] = {0.0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1.0, 1.0};
constexpr double kA[7][6] = {
    {},
    {1.0 / 5},
    {3.0 / 40, 9.0 / 40},
    {44.0 / 45, -56.0 / 15, 32.0 / 9},
    {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729},
    {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656},
    {35.0 / 384, 0.0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84},
};
constexpr double kB4[7] = {5179.0 / 57600, 0.0, 7571.0 / 16695, 393.0 / 640, -92097.0 / 339200, 187.0 / 2100, 1.0 / 40};

// out = y + h sum_j a[j] k[j], j < count.
void combine(const std::vector<int>& bodies, const std::vector<BodyState>& y, double h, const double* a, int count,
             const std::vector<BodyDerivative>* k, std::vector<BodyState>& out) {
  for (int i : bodies) {
    BodyState& o = out[i];
    o = y[i];
    for (int j = 0; j < count; ++j) {
      if (a[j] == 0.0) continue;
      const double w = h * a[j];
      o.X += w * k[j][i].dX;
      o.q.coeffs() += w * k[j][i].dq;
      o.P += w * k[j][i].dP;
      o.L += w * k[j][i].dL;
    }
  }
}

// One Dormand-Prince step from y: the 5th-order solution into y5, the 4th-order one
// into y4 (the 7th stage is the derivative at y5, first-same-as-last).
void dopri5Step(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, const std::vector<BodyState>& y,
                double h, std::vector<BodyState>& y5, std::vector<BodyState>& y4) {
  std::vector<BodyDerivative>* k = d.scratch.k;
  std::vector<BodyState>& stage = d.scratch.stage;
  evaluateDerivative(m, bodies, d.input, y, d.aux, k[0]);
  for (int s = 1; s < 7; ++s) {
    combine(bodies, y, h, kA[s], s, k, stage);
    evaluateDerivative(m, bodies, d.input, stage, d.aux, k[s]);
  }
  for (int i : bodies) y5[i] = stage[i];  // the 7th stage is evaluated at the 5th-order solution
  combine(bodies, y, h, kB4, 7, k, y4);
}

// Error of a step, relative to the tolerance: max over components of
// |y5 - y4| / (tol (1 + max(|y|, |y5|))), i.e. absolute and relative tolerance both tol.
double scaledError(const std::vector<int>& bodies, const std::vector<BodyState>& y, const std::vector<BodyState>& y5,
                   const std::vector<BodyState>& y4, double tol) {
  double e = 0.0;
  auto part = [&](const auto& a, const auto& b, const auto& c) {
    const auto scale = (1.0 + a.cwiseAbs().cwiseMax(b.cwiseAbs()).array()) * tol;
    e = std::max(e, ((b - c).cwiseAbs().array() / scale).maxCoeff());
  };
  for (int i : bodies) {
    part(y[i].X, y5[i].X, y4[i].X);
    part(y[i].q.coeffs(), y5[i].q.coeffs(), y4[i].q.coeffs());
    part(y[i].P, y5[i].P, y4[i].P);
    part(y[i].L, y5[i].L, y4[i].L);
  }
  return e;
}

// Adaptive Dormand-Prince over [0, h]: steps chosen by the standard controller
// (safety 0.9, factor within [0.2, 5]) so that each local error estimate meets
// solver.tolerance; the last step shortened to end at h. Tolerance 0: one fixed step.
int dopri5Adaptive(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
                   std::vector<BodyState>& next) {
  Scratch& s = d.scratch;
  IntegratorState& state = d.integrator;
  if (m.tolerance <= 0.0) {
    dopri5Step(m, d, bodies, d.Y, h, next, s.y4);
    state.errorEstimate = 0.0;
    return 1;
  }
  for (int i : bodies) s.y[i] = d.Y[i];
  double t = 0.0;
  double trial = state.adaptiveStep > 0.0 ? std::min(state.adaptiveStep, h) : h;
  double memory = state.adaptiveStep;  // the controller's step, not one shortened to end at h
  int accepted = 0;
  while (t < h) {
    const bool last = trial >= h - t;
    const double step = last ? h - t : trial;
    dopri5Step(m, d, bodies, s.y, step, next, s.y4);
    const double err = scaledError(bodies, s.y, next, s.y4, m.tolerance);
    const double factor = err > 0.0 ? 0.9 * std::pow(err, -0.2) : 5.0;
    if (!(err <= 1.0)) {  // also when err is NaN
      trial = step * std::max(0.2, std::min(1.0, factor));
      if (!(trial > 1e-14 * h) || !std::isfinite(err)) return 0;
      continue;
    }
    ++accepted;
    state.errorEstimate = err * m.tolerance;
    for (int i : bodies) next[i].q.normalize();
    std::swap(s.y, next);
    t = last ? h : t + step;
    trial = step * std::min(5.0, std::max(0.2, factor));
    if (!last || memory <= 0.0) memory = trial;
  }
  state.adaptiveStep = memory;
  for (int i : bodies) next[i] = s.y[i];
  return accepted;
}

// ---- Rosenbrock ROS2 (Verwer, Spee, Blom & Hundsdorfer 1999) ------------------------------
// (I - gamma h J) k1 = f(y),  (I - gamma h J) k2 = f(y + h k1) - 2 k1,
// y1 = y + 3/2 h k1 + 1/2 h k2, gamma = 1 + 1/sqrt(2): second order for any J, L-stable.
// q then turns by the free rotation (DLM) with the step's mean L.
// J is each body's 13 x 13 Jacobian of dY/dt by finite differences (bodies exert no
// forces on each other outside contacts), so stiff drag, angular drag and buoyancy's
// restoring force are taken implicitly. The surfaces' support and friction are left
// out of J (their switches would spoil a difference quotient); ROS2 keeps its order
// for any J, so they are simply explicit.
using Vec13 = Eigen::Matrix<double, 13, 1>;
using Mat13 = Eigen::Matrix<double, 13, 13>;

Vec13 pack(const BodyState& y) {
  Vec13 v;
  v << y.X, y.q.coeffs(), y.P, y.L;
  return v;
}

BodyState unpack(const Vec13& v) {
  BodyState y;
  y.X = v.segment<3>(0);
  y.q.coeffs() = v.segment<4>(3);
  y.P = v.segment<3>(7);
  y.L = v.segment<3>(10);
  return y;
}

Vec13 pack(const BodyDerivative& d) {
  Vec13 v;
  v << d.dX, d.dq, d.dP, d.dL;
  return v;
}

Vec13 bodyRate(const WorldModel& m, size_t i, const BodyInput& in, const Vec13& y, BodyAux& aux) {
  BodyDerivative d;
  evaluateBodyDerivative(m, m.bodies[i], in, unpack(y), aux, d);
  return pack(d);
}

void rosenbrockStep(const WorldModel& m, WorldData& d, const std::vector<int>& bodies, double h,
                    std::vector<BodyState>& next) {
  const double gamma = 1.0 + 1.0 / std::sqrt(2.0);
  for (int i : bodies) {
    const BodyInput& in = d.input[i];
    const Vec13 y = pack(d.Y[i]);
    const Vec13 f0 = bodyRate(m, i, in, y, d.aux[i]);
    Mat13 J;
    for (int j = 0; j < 13; ++j) {
      const double delta = 1e-7 * std::max(1.0, std::abs(y[j]));
      Vec13 yp = y, ym = y;
      yp[j] += delta;
      ym[j] -= delta;
      J.col(j) = (bodyRate(m, i, in, yp, d.aux[i]) - bodyRate(m, i, in, ym, d.aux[i])) / (2.0 * delta);
    }
    // q's rows are left out: q is turned by the free rotation below, not by the stages.
    J.middleRows<4>(3).setZero();
    const Eigen::PartialPivLU<Mat13> W(Mat13::Identity() - gamma * h * J);
    const Vec13 k1 = W.solve(f0);
    const Vec13 k2 = W.solve(bodyRate(m, i, in, y + h * k1, d.aux[i]) - 2.0 * k1);
    next[i] = unpack(y + 1.5 * h * k1 + 0.5 * h * k2);
    // q turns by the free rotation with the step's mean L (Dullweber-Leimkuhler-
    // McLachlan, as in the splitting method): second order, and a free rotation keeps
    // its energy bounded, which polynomial stages on q do not.
    next[i].q = freeRotation(m.bodies[i], d.Y[i].q, 0.5 * (d.Y[i].L + next[i].L), h);
  }
}

}  // namespace

Quat rotationQuaternion(const Vec3& theta) {
  const double angle = theta.norm();
  // sin(a/2)/a by its series near 0, where the division would lose digits
  const double half = 0.5 * angle;
  const double s = angle < 1e-4 ? 0.5 - angle * angle / 48.0 : std::sin(half) / angle;
  return Quat(std::cos(half), s * theta.x(), s * theta.y(), s * theta.z());
}

int integrate(const WorldModel& model, WorldData& data, const std::vector<int>& bodies, double h,
              std::vector<BodyState>& next) {
  switch (model.method) {
    case Method::Euler: eulerStep(model, data, bodies, h, next); return 1;
    case Method::RK4: rk4Step(model, data, bodies, h, next); return 1;
    case Method::SymplecticEuler: symplecticEulerStep(model, data, bodies, h, next); return 1;
    case Method::Splitting: splittingStep(model, data, bodies, h, next); return 1;
    case Method::LieRK4: lieRk4Step(model, data, bodies, h, next); return 1;
    case Method::Dopri5: return dopri5Adaptive(model, data, bodies, h, next);
    case Method::Rosenbrock: rosenbrockStep(model, data, bodies, h, next); return 1;
  }
  return 0;
}

}  // namespace rigid
