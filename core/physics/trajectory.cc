// Evaluation of piecewise cubic Bézier trajectories (see trajectory.h).
#include "core/physics/trajectory.h"

#include <algorithm>

namespace asgard::physics {

TrajectoryCurve::TrajectoryCurve(const std::vector<scene::TrajectoryKnot>& knots) {
  for (const auto& k : knots) {
    times.push_back(k.t);
    points.emplace_back(k.p[0], k.p[1], k.p[2]);
  }
  const size_t n = times.size();
  tangents.assign(n, Eigen::Vector3d::Zero());
  if (n < 2) return;
  for (size_t i = 0; i < n; ++i) {
    const size_t lo = i == 0 ? 0 : i - 1;
    const size_t hi = i + 1 == n ? n - 1 : i + 1;
    tangents[i] = (points[hi] - points[lo]) / (times[hi] - times[lo]);
  }
}

Eigen::Vector3d TrajectoryCurve::Value(double t, int order) const {
  const size_t n = times.size();
  if (n == 0) return Eigen::Vector3d::Zero();
  if (n == 1) return order == 0 ? points[0] : Eigen::Vector3d::Zero();
  // Linear extrapolation outside the knots.
  if (t <= times.front() || t >= times.back()) {
    const size_t e = t <= times.front() ? 0 : n - 1;
    if (order == 0) return points[e] + tangents[e] * (t - times[e]);
    if (order == 1) return tangents[e];
    return Eigen::Vector3d::Zero();
  }
  const size_t i =
      static_cast<size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  const double h = times[i + 1] - times[i];
  const double s = (t - times[i]) / h;
  const Eigen::Vector3d b0 = points[i];
  const Eigen::Vector3d b1 = points[i] + tangents[i] * (h / 3.0);
  const Eigen::Vector3d b2 = points[i + 1] - tangents[i + 1] * (h / 3.0);
  const Eigen::Vector3d b3 = points[i + 1];
  const double u = 1.0 - s;
  switch (order) {
    case 0:
      return u * u * u * b0 + 3 * u * u * s * b1 + 3 * u * s * s * b2 + s * s * s * b3;
    case 1:
      return 3.0 / h * (u * u * (b1 - b0) + 2 * u * s * (b2 - b1) + s * s * (b3 - b2));
    case 2:
      return 6.0 / (h * h) * (u * (b2 - 2 * b1 + b0) + s * (b3 - 2 * b2 + b1));
    case 3:
      return 6.0 / (h * h * h) * (b3 - 3 * b2 + 3 * b1 - b0);
    default:
      return Eigen::Vector3d::Zero();
  }
}

double TrajectoryCurve::Evaluate(int axis, int order, double t) const {
  return Value(t, order)[axis];
}

}  // namespace asgard::physics
