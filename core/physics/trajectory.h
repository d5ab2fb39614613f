// Trajectories: vector functions of time built from cubic Bézier segments.
//
//   p(t)   knots (t_i, p_i) joined by cubic Bézier segments
//   ─●────●──────●───●─   control points of segment i:
//                           b0 = p_i, b1 = p_i + h m_i / 3,
//                           b2 = p_{i+1} − h m_{i+1} / 3, b3 = p_{i+1}
//   tangents m_i are Catmull–Rom (central differences; one-sided at the ends),
//   so the curve is C¹ and passes through every knot at its time.
//   Before the first and after the last knot the curve continues linearly with
//   the end tangent (seed 5.1.3: "linearly extrapolated from the closest
//   endpoint and the derivative of the curve at that point").
#pragma once

#include <Eigen/Dense>
#include <vector>

#include "core/scene/scene.h"

namespace asgard::physics {

struct TrajectoryCurve {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector3d> tangents;

  explicit TrajectoryCurve(const std::vector<scene::TrajectoryKnot>& knots);

  // Component `axis` (0..2) of the `order`-th time derivative at t.
  double Evaluate(int axis, int order, double t) const;
  Eigen::Vector3d Value(double t, int order = 0) const;
};

}  // namespace asgard::physics
