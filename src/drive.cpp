#include "drive.h"

#include "integrator.h"
#include "world.h"

namespace rigid {

std::vector<DriveInput> startDrive(const WorldModel& model) {
  std::vector<DriveInput> drive(model.bodies.size());
  for (size_t i = 0; i < drive.size(); ++i) {
    const BodyStart& start = model.bodies[i].start;
    drive[i].position = start.position;
    drive[i].orientation = start.orientation.normalized();
    drive[i].velocity = start.velocity;
    drive[i].angularVelocity = start.angularVelocity;
  }
  return drive;
}

DrivePath drivePath(const BodyState& y, const DriveInput& in, double h) {
  DrivePath p;
  const Vec3 gap = in.position - y.X;
  p.jump = gap.norm();
  p.closing = gap / h;
  // the rotation from where the body is to where the inputs put it, the short way
  Quat turn = in.orientation.normalized() * y.q.conjugate();
  if (turn.w() < 0.0) turn.coeffs() = -turn.coeffs();
  const Eigen::AngleAxisd axisAngle(turn);
  p.closingTurn = axisAngle.angle() * axisAngle.axis() / h;
  return p;
}

void setDriveVelocities(const WorldModel& model, WorldData& data, const std::vector<DriveInput>& in,
                        const std::vector<DrivePath>& paths, double from, double to) {
  const double mid = 0.5 * (from + to);
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    if (!driven(model.bodies[i])) continue;
    const Vec3 V = paths[i].closing + in[i].velocity + mid * in[i].acceleration;
    const Vec3 omega = paths[i].closingTurn + in[i].angularVelocity + mid * in[i].angularAcceleration;
    data.Y[i].P = V;  // mass 1, Ibody = 1
    data.Y[i].L = omega;
    data.aux[i].V = V;
    data.aux[i].omega = omega;
  }
}

BodyState driveStep(const BodyState& y, double h) {
  BodyState next = y;
  next.X = y.X + h * y.P;
  next.q = rotationQuaternion(h * y.L) * y.q;
  return next;
}

}  // namespace rigid
