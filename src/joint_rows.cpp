#include "joint_rows.h"

#include <algorithm>
#include <cmath>

#include "constraint_solver.h"
#include "world.h"

namespace rigid {

using namespace solver;
using namespace joint_solver;

namespace {

constexpr double kPi = 3.14159265358979323846;

// An angle into (-pi, pi].
double wrap(double angle) { return angle - 2.0 * kPi * std::floor((angle + kPi) / (2.0 * kPi)); }

// The turn of b relative to a since the start, world frame: qB (qA rest)^-1, taken
// with w >= 0 (the shorter way round).
Quat relativeTurn(const JointConstants& j, const Quat& qA, const Quat& qB) {
  Quat e = qB * (qA * j.rest).conjugate();
  if (e.w() < 0.0) e.coeffs() = -e.coeffs();
  return e;
}

// A hinge's angle within (-pi, pi]: the twist of the relative turn about the axis.
double rawAngle(const Quat& e, const Vec3& axis) { return 2.0 * std::atan2(e.vec().dot(axis), e.w()); }

// A joint's geometry in one pose of its two bodies.
struct Pose {
  Vec3 rA, rB;  // m, the anchors from the centres of mass, world frame
  Vec3 d;       // m, anchor b - anchor a
  Vec3 axis;    // unit: a's axis (revolute, prismatic), the anchors' line (distance)
  Quat turn;    // relativeTurn
};

// `turning`: whether to find the relative turn too (a weld's and a slider's rows and a
// hinge's angle need it).
Pose poseOf(const JointConstants& j, const Vec3& xA, const Quat& qA, const Vec3& xB, const Quat& qB,
            bool turning = true) {
  Pose p;
  p.rA = qA * j.anchorA;
  p.rB = qB * j.anchorB;
  p.d = (xB + p.rB) - (xA + p.rA);
  if (turning) p.turn = relativeTurn(j, qA, qB);
  if (j.type == JointType::Distance) {
    const double length = p.d.norm();
    p.axis = length > 1e-12 ? Vec3(p.d / length) : Vec3(qA * j.axisA);
  } else {
    p.axis = qA * j.axisA;
  }
  return p;
}

// The coordinate of a pose, given a revolute joint's angle at a pose `angle0` whose
// raw angle was `raw0`: within a step the angle moves by less than a half turn.
double coordinateOf(const JointConstants& j, const Pose& p, double angle0, double raw0) {
  switch (j.type) {
    case JointType::Revolute: return angle0 + wrap(rawAngle(p.turn, p.axis) - raw0);
    case JointType::Prismatic: return p.axis.dot(p.d);
    case JointType::Distance: return p.d.norm();
    default: return 0.0;
  }
}

// Rows a joint type has.
std::array<bool, kJointRows> rowsOf(const JointConstants& j) {
  std::array<bool, kJointRows> on{};
  const bool point = j.type == JointType::Revolute || j.type == JointType::Spherical || j.type == JointType::Fixed;
  on[kPoint0] = on[kPoint1] = point || j.type == JointType::Prismatic;
  on[kPoint2] = point;
  on[kTurn0] = on[kTurn1] =
      j.type == JointType::Revolute || j.type == JointType::Prismatic || j.type == JointType::Fixed;
  on[kTurn2] = j.type == JointType::Prismatic || j.type == JointType::Fixed;
  on[kHold] = j.type == JointType::Distance && !j.spring && !j.rope;
  on[kSpring] = j.spring;
  on[kLower] = j.limited;
  on[kUpper] = hasStops(j);
  on[kMotor] = j.motor;
  return on;
}

// One joint in a solve.
struct Work {
  const JointConstants* joint = nullptr;
  int a = -1, b = -1;  // solver slots
  std::array<bool, kJointRows> on{};
  std::array<double, kJointRows> lambda{};  // N s (or N m s): the sub-step's accumulated impulse per row
  std::array<double, kJointRows> error{};   // m or rad: each row's position error now
  Jacobian row[kJointRows];
  Vec3 perpA[2], perpB[2];          // a slider's directions across a's axis, a hinge's across b's (body frames)
  double angle0 = 0.0, raw0 = 0.0;  // rad: a hinge's angle and raw angle at the step's start
  bool measured = false;            // whether a row needs the coordinate (a stop, a spring, a rod)
  double coordinate = 0.0;          // now
  double motorSpeed = 0.0, target = 0.0;
  Vec3 rB = Vec3::Zero();
  // What the joint gave the bodies over the step, summed as it was applied: the impulse
  // on b, its moment about b's anchor, and the angular impulses about a's and b's centres.
  Vec3 impulse = Vec3::Zero(), angularImpulse = Vec3::Zero();
  Vec3 turnA = Vec3::Zero(), turnB = Vec3::Zero();

  // The impulse `amount` along row J on both bodies, and into the step's sums.
  void push(Body& A, Body& B, const Jacobian& J, double amount) {
    applyImpulse(A, B, J, amount);
    impulse += amount * J.linear;
    angularImpulse += amount * (J.angularB - rB.cross(J.linear));
    turnA += amount * J.angularA;
    turnB += amount * J.angularB;
  }
};

// Every row of a joint for the bodies' poses now.
void build(Work& w, const Body& A, const Body& B) {
  const JointConstants& j = *w.joint;
  const bool held = j.type == JointType::Fixed || j.type == JointType::Prismatic;
  const Pose p =
      poseOf(j, A.x0 + A.moved, A.q, B.x0 + B.moved, B.q, held || (j.type == JointType::Revolute && w.measured));
  w.rB = p.rB;
  if (w.measured) w.coordinate = coordinateOf(j, p, w.angle0, w.raw0);
  if (j.type == JointType::Prismatic) {  // across the axis: levers of a to b's anchor
    for (int k = 0; k < 2; ++k) {
      const Vec3 n = A.q * w.perpA[k];
      w.row[kPoint0 + k] = jacobian(A, B, n, (p.rA + p.d).cross(n), p.rB.cross(n));
      w.error[kPoint0 + k] = n.dot(p.d);
    }
  } else if (w.on[kPoint0]) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = Vec3::Unit(k);
      w.row[kPoint0 + k] = jacobian(A, B, e, p.rA.cross(e), p.rB.cross(e));
      w.error[kPoint0 + k] = p.d[k];
    }
  }
  if (j.type == JointType::Revolute) {  // b's directions across its axis stay across a's
    for (int k = 0; k < 2; ++k) {
      const Vec3 across = B.q * w.perpB[k], n = across.cross(p.axis);
      w.row[kTurn0 + k] = jacobian(A, B, Vec3::Zero(), n, n);
      w.error[kTurn0 + k] = p.axis.dot(across);
    }
  } else if (w.on[kTurn0]) {
    for (int k = 0; k < 3; ++k) {
      const Vec3 e = Vec3::Unit(k);
      w.row[kTurn0 + k] = jacobian(A, B, Vec3::Zero(), e, e);
      w.error[kTurn0 + k] = 2.0 * p.turn.vec()[k];
    }
  }
  if (!hasCoordinate(j.type)) return;
  const Vec3& n = p.axis;
  const Jacobian along = j.type == JointType::Revolute    ? jacobian(A, B, Vec3::Zero(), n, n)
                         : j.type == JointType::Prismatic ? jacobian(A, B, n, (p.rA + p.d).cross(n), p.rB.cross(n))
                                                          : jacobian(A, B, n, p.rA.cross(n), p.rB.cross(n));
  Jacobian against = along;
  for (Vec3* v : {&against.linear, &against.angularA, &against.angularB, &against.spinA, &against.spinB}) *v = -*v;
  w.row[kHold] = w.row[kSpring] = w.row[kLower] = w.row[kMotor] = along;
  w.row[kUpper] = against;
  const double upper = j.rope && !j.spring ? (j.limited ? std::min(j.upper, j.length) : j.length) : j.upper;
  w.error[kHold] = w.coordinate - j.length;
  w.error[kSpring] = w.coordinate - (j.type == JointType::Distance ? j.length : w.target);
  w.error[kLower] = w.coordinate - j.lower;
  w.error[kUpper] = upper - w.coordinate;
}

// n equality rows from `first` solved as one block (n <= 3), softened while the bias
// is on.
void solveBlock(Work& w, int first, int n, Body& A, Body& B, const Softness& soft, bool useBias) {
  Mat3 K = Mat3::Identity();
  Vec3 rhs = Vec3::Zero(), lambda = Vec3::Zero();
  for (int x = 0; x < n; ++x) {
    rhs[x] = velocityAlong(A, B, w.row[first + x]) + (useBias ? soft.biasRate * w.error[first + x] : 0.0);
    lambda[x] = w.lambda[first + x];
    for (int y = 0; y < n; ++y) K(x, y) = coupling(A, B, w.row[first + x], w.row[first + y]);
  }
  const double massScale = useBias ? soft.massScale : 1.0, impulseScale = useBias ? soft.impulseScale : 0.0;
  const Vec3 impulse = -massScale * K.inverse() * rhs - impulseScale * lambda;
  for (int x = 0; x < n; ++x) {
    w.push(A, B, w.row[first + x], impulse[x]);
    w.lambda[first + x] += impulse[x];
  }
}

// A limit: one-sided like a contact's normal (its impulse only pushes the coordinate
// back into its range); apart from it, it may close its gap within the sub-step.
void solveLimit(Work& w, int k, Body& A, Body& B, const Softness& soft, double hSub, bool useBias) {
  const Jacobian& J = w.row[k];
  double bias = 0.0, massScale = 1.0, impulseScale = 0.0;
  if (w.error[k] > 0.0) {
    bias = w.error[k] / hSub;
  } else if (useBias) {
    bias = soft.biasRate * w.error[k];
    massScale = soft.massScale;
    impulseScale = soft.impulseScale;
  }
  const double mass = 1.0 / coupling(A, B, J, J);
  const double impulse = -mass * massScale * (velocityAlong(A, B, J) + bias) - impulseScale * w.lambda[k];
  const double total = std::max(w.lambda[k] + impulse, 0.0);
  w.push(A, B, J, total - w.lambda[k]);
  w.lambda[k] = total;
}

// The coordinate's spring (physical: in every pass; an elastic rope's only pulls, and
// only while stretched) and motor (bounded by its force).
void solveDrive(Work& w, Body& A, Body& B, double hSub) {
  const JointConstants& j = *w.joint;
  const double mass = 1.0 / coupling(A, B, w.row[kSpring], w.row[kSpring]);
  if (w.on[kSpring]) {
    const Softness s = makeSpring(j.stiffness, j.damping, mass, hSub);
    const double impulse = -s.massScale * mass * (velocityAlong(A, B, w.row[kSpring]) + s.biasRate * w.error[kSpring]) -
                           s.impulseScale * w.lambda[kSpring];
    double total = w.lambda[kSpring] + impulse;
    if (j.rope) total = w.error[kSpring] > 0.0 ? std::min(total, 0.0) : 0.0;
    w.push(A, B, w.row[kSpring], total - w.lambda[kSpring]);
    w.lambda[kSpring] = total;
  }
  if (w.on[kMotor]) {
    const double most = j.maxMotorForce * hSub;
    const double wanted = w.lambda[kMotor] - mass * (velocityAlong(A, B, w.row[kMotor]) - w.motorSpeed);
    const double total = std::clamp(wanted, -most, most);
    w.push(A, B, w.row[kMotor], total - w.lambda[kMotor]);
    w.lambda[kMotor] = total;
  }
}

class JointRows final : public ExtraRows {
 public:
  explicit JointRows(const WorldModel& model) : work_(model.joints.size()) {
    for (size_t k = 0; k < work_.size(); ++k) {
      const JointConstants& j = model.joints[k];
      Work& w = work_[k];
      w.joint = &j;
      w.on = rowsOf(j);
      w.measured = w.on[kHold] || w.on[kSpring] || w.on[kLower] || w.on[kUpper];
      w.perpA[0] = anyPerpendicular(j.axisA);
      w.perpA[1] = j.axisA.cross(w.perpA[0]);
      w.perpB[0] = anyPerpendicular(j.axisB);
      w.perpB[1] = j.axisB.cross(w.perpB[0]);
    }
  }

  void prepare(const WorldModel& model, const WorldData& data, double h, std::vector<int>& bodies) override {
    const double hSub = h / constraint_solver::kSubsteps;
    soft_ = makeSoft(kJointHertzShare * constraint_solver::kSubsteps / model.maxStep, kJointDampingRatio, hSub);
    static_ = static_cast<int>(data.Y.size());
    for (size_t k = 0; k < work_.size(); ++k) {
      Work& w = work_[k];
      const JointConstants& j = model.joints[k];
      w.joint = &j;  // (the model may have been copied since: an FMU state restored)
      w.a = j.a >= 0 ? j.a : static_;
      w.b = j.b;
      if (j.a >= 0) bodies.push_back(j.a);
      bodies.push_back(j.b);
      w.lambda = data.joints.memory[k];
      w.motorSpeed = data.joints.motorSpeed[k];
      w.target = data.joints.targetPosition[k];
      w.angle0 = data.joints.angle[k];
      if (j.type == JointType::Revolute) {
        const Quat qA = j.a >= 0 ? data.Y[j.a].q.normalized() : Quat::Identity();
        w.raw0 = rawAngle(relativeTurn(j, qA, data.Y[j.b].q.normalized()), qA * j.axisA);
      }
      w.impulse = w.angularImpulse = w.turnA = w.turnB = Vec3::Zero();
    }
  }

  bool any() const override { return !work_.empty(); }

  // A limit (or a rope's full length) that the coordinate reaches within the step at
  // more than a resting speed is struck as a contact is: j = -(1 + e) v m_eff, e the
  // joint's restitution; the sub-steps' one-sided rows then hold it there.
  bool impact(std::vector<Body>& bodies, double restingSpeed, double h) override {
    bool struck = false;
    for (Work& w : work_) {
      if (!w.on[kLower] && !w.on[kUpper]) continue;
      Body& A = bodies[w.a];
      Body& B = bodies[w.b];
      build(w, A, B);
      for (int k : {kLower, kUpper}) {
        const double approach = velocityAlong(A, B, w.row[k]);
        if (!w.on[k] || !(approach < -restingSpeed) || w.error[k] > -approach * h) continue;
        const double j = -(1.0 + w.joint->restitution) * approach / coupling(A, B, w.row[k], w.row[k]);
        w.push(A, B, w.row[k], j);
        struck = true;
      }
    }
    return struck;
  }

  void warmStart(std::vector<Body>& bodies) override {
    for (Work& w : work_) {
      Body& A = bodies[w.a];
      Body& B = bodies[w.b];
      build(w, A, B);
      for (int k = 0; k < kJointRows; ++k)
        if (w.on[k]) w.push(A, B, w.row[k], w.lambda[k]);
    }
  }

  void solve(std::vector<Body>& bodies, double hSub, bool useBias) override {
    for (Work& w : work_) {
      Body& A = bodies[w.a];
      Body& B = bodies[w.b];
      build(w, A, B);
      solveDrive(w, A, B, hSub);
      if (w.on[kLower]) solveLimit(w, kLower, A, B, soft_, hSub, useBias);
      if (w.on[kUpper]) solveLimit(w, kUpper, A, B, soft_, hSub, useBias);
      if (w.on[kHold]) solveBlock(w, kHold, 1, A, B, soft_, useBias);
      const int across = w.joint->type == JointType::Prismatic ? 2 : 3;
      if (w.on[kPoint0]) solveBlock(w, kPoint0, across, A, B, soft_, useBias);
      if (w.on[kTurn0]) solveBlock(w, kTurn0, w.on[kTurn2] ? 3 : 2, A, B, soft_, useBias);
    }
  }

  void commit(WorldData& data, ContactImpulses& contacts) const {
    for (size_t k = 0; k < work_.size(); ++k) {
      const Work& w = work_[k];
      data.joints.memory[k] = w.lambda;
      data.joints.impulse[k] += w.impulse;
      data.joints.angularImpulse[k] += w.angularImpulse;
      contacts.linear[w.b] -= w.impulse, contacts.angular[w.b] -= w.turnB;
      if (w.a != static_) contacts.linear[w.a] += w.impulse, contacts.angular[w.a] += w.turnA;
    }
  }

 private:
  std::vector<Work> work_;
  Softness soft_;
  int static_ = 0;
};

}  // namespace

std::unique_ptr<ExtraRows> makeJointRows(const WorldModel& model) { return std::make_unique<JointRows>(model); }

void commitJoints(const ExtraRows& rows, WorldData& data, ContactImpulses& contacts) {
  static_cast<const JointRows&>(rows).commit(data, contacts);
}

void measureJoints(const WorldModel& model, WorldData& data) {
  for (size_t k = 0; k < model.joints.size(); ++k) {
    const JointConstants& j = model.joints[k];
    const bool world = j.a < 0;
    const Vec3 xA = world ? Vec3::Zero() : data.Y[j.a].X;
    const Quat qA = world ? Quat::Identity() : data.Y[j.a].q.normalized();
    const Vec3 vA = world ? Vec3::Zero() : data.aux[j.a].V, wA = world ? Vec3::Zero() : data.aux[j.a].omega;
    const Pose p = poseOf(j, xA, qA, data.Y[j.b].X, data.Y[j.b].q.normalized());
    const double previous = data.joints.angle[k];
    const double coordinate = coordinateOf(j, p, previous, wrap(previous));
    if (j.type == JointType::Revolute) data.joints.angle[k] = coordinate;
    data.joints.position[k] = coordinate;
    // the anchors' relative velocity, and the turn of b relative to a
    const Vec3 slip = data.aux[j.b].V + data.aux[j.b].omega.cross(p.rB) - vA - wA.cross(p.rA);
    const Vec3 spin = data.aux[j.b].omega - wA;
    switch (j.type) {
      case JointType::Revolute: data.joints.speed[k] = p.axis.dot(spin); break;
      case JointType::Prismatic: data.joints.speed[k] = p.axis.dot(slip) + p.d.dot(wA.cross(p.axis)); break;
      case JointType::Distance: data.joints.speed[k] = p.axis.dot(slip); break;
      default: data.joints.speed[k] = 0.0;
    }
  }
}

void startJoints(const WorldModel& model, WorldData& data) {
  const size_t n = model.joints.size();
  JointData& d = data.joints;
  d.memory.assign(n, {});
  d.angle.assign(n, 0.0);
  d.motorSpeed.clear();
  d.targetPosition.clear();
  for (const JointConstants& j : model.joints) {
    d.motorSpeed.push_back(j.motorSpeed);
    d.targetPosition.push_back(j.targetPosition);
  }
  d.motorSpeedRate.assign(n, 0.0);
  d.targetPositionRate.assign(n, 0.0);
  d.impulse.assign(n, Vec3::Zero());
  d.angularImpulse.assign(n, Vec3::Zero());
  d.position.assign(n, 0.0);
  d.speed.assign(n, 0.0);
  measureJoints(model, data);
}

}  // namespace rigid
