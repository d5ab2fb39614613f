// Scene sampling for rendering and export (seed 4.1.9).
//
// A SceneSampler reads a scene, its equations and their finished simulation
// and answers what every output needs: each body's geometry in body
// coordinates (origin at the centre of mass, shape axes), its pose at any time
// t (pipeline::SampleBody: the Hermite interpolant of the integrator's own
// samples, so playback matches what was integrated), the frame times, the
// default framing view (SceneBound), the lights, and overlay geometry (link
// springs, force vectors, body paths).
#pragma once

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "core/geometry/geometry.h"
#include "core/physics/equations.h"
#include "core/pipeline/pipeline.h"
#include "core/render/color.h"
#include "core/render/view.h"

namespace asgard::render {

// One convex piece in body coordinates as physics built it (a sphere, or
// its hull: vertices, CCW triangles, merged faces with outward normals),
// with the colour it is drawn in: the body's, else the piece's, else the
// palette's.
struct Piece : physics::BodyPiece {
  Rgb rgb;  // drawn in; `color` is the name the scene gave the piece, if any
};

struct BodyShape {
  std::string name;
  bool is_static = false;
  std::vector<Piece> pieces;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();      // centre of mass, shape coordinates
  Eigen::Vector3d bound_center = Eigen::Vector3d::Zero();  // body coordinates
  double bound_radius = 0.0;
};

// Where a body is: world = p + q · body.
struct Pose {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();

  Eigen::Vector3d Apply(const Eigen::Vector3d& body) const { return p + q * body; }
  Eigen::Matrix4d Matrix() const;
};

struct Segment {
  Eigen::Vector3d a, b;
};

struct Bound {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 1.0;
};

class ViewMotion;

class SceneSampler {
 public:
  // The simulation must have run to its end; all three must outlive the
  // sampler.
  SceneSampler(const scene::Scene& scene, const physics::EquationSystem& equations,
               const solver::Simulation& simulation);
  ~SceneSampler();
  SceneSampler(const SceneSampler&) = delete;
  SceneSampler& operator=(const SceneSampler&) = delete;

  double t0() const;
  double t1() const;
  double frame_rate() const { return frame_rate_; }
  const std::vector<BodyShape>& bodies() const { return bodies_; }
  // Colour names that were not understood (the palette was used instead).
  const std::vector<std::string>& unknown_colors() const { return unknown_colors_; }

  std::vector<Pose> Poses(double t) const;
  // The scene's frame times (simulator -frames per second, t0..t1 inclusive,
  // the last frame at t1), as pipeline::SampleFrames.
  std::vector<double> FrameTimes() const;
  // `count` frames evenly spaced over [start, end] (count 1: start).
  static std::vector<double> FrameTimes(double start, double end, int count);

  // Sphere (centred on the smallest box) holding every body's bounding sphere
  // at the start, and along its path until it first strays beyond twice that
  // radius (all of the paths when fewer than two bodies have geometry).
  Bound SceneBound() const;
  // The framing view (DefaultTilt, centre and radius of SceneBound), with the
  // options of the scene's last `view` element (or the one named `name`)
  // overriding it.  Returns nullopt when `name` is given and not found.
  std::optional<ViewState> SceneView(const std::string& name = "") const;
  // The view of one `view` element (null: the framing view alone) from its
  // constant options; see Motion for one that moves.
  ViewState ElementView(const scene::View* element) const;
  // The scene's last `view` element, or the one named `name`; null when
  // there is none (or none of that name).
  const scene::View* FindView(const std::string& name = "") const;
  // The camera motion of a `view` element (null: the framing view).
  ViewMotion Motion(const scene::View* element) const;
  // The scene's light sources (empty: the caller adds DefaultLight).
  std::vector<Light> SceneLights() const;

  // Overlays at time t for the given poses.
  std::vector<Segment> LinkSegments(double t, const std::vector<Pose>& poses) const;
  // Force vectors: base at the point of application, `b − a` the force in
  // scene units (the caller scales it).  Forces whose expressions cannot be
  // evaluated here are left out.
  std::vector<Segment> ForceVectors(double t, const std::vector<Pose>& poses) const;
  // Each scene force's world vector at time t (mass included for
  // -gravitational 1), in the order of scene.forces; nullopt where it cannot
  // be evaluated here.
  std::vector<std::optional<Eigen::Vector3d>> ForceValues(double t) const;
  // Each scene torque's world vector at time t, in the order of
  // scene.torques; nullopt where it cannot be evaluated here.
  std::vector<std::optional<Eigen::Vector3d>> TorqueValues(double t) const;
  // Path of each moving body's centre of mass over `times`.
  std::vector<std::vector<Eigen::Vector3d>> Paths(const std::vector<double>& times) const;

 private:
  friend class ViewMotion;
  struct Evaluator;
  std::vector<std::optional<Eigen::Vector3d>> VectorValues(const std::vector<int>& first,
                                                           double t) const;
  const scene::Scene& scene_;
  const physics::EquationSystem& equations_;
  const solver::Simulation& simulation_;
  double frame_rate_;
  std::vector<BodyShape> bodies_;
  std::vector<std::string> unknown_colors_;
  std::unique_ptr<Evaluator> eval_;
  mutable std::optional<Bound> bound_;
};

// One `view` element's camera over time (seed 4.1.7): the framing view
// with the element's constant options, its -pos, -rot and -scale
// expressions of time and state evaluated at t (parsed once with the
// overlays' name table into one tape: the expression module, as forces),
// and its centre on -follow's body or -trajectory's curve.  The sampler must
// outlive it.
class ViewMotion {
 public:
  ViewMotion(const SceneSampler& sampler, const scene::View* element);

  // The view at time t.  An expression whose value is unusable there (not
  // finite, a -scale <= 0, a zero quaternion) leaves that option at its
  // default and, when `problem` is given, says so in it.
  ViewState At(double t, std::string* problem = nullptr) const;
  // Whether the view changes over time (-follow, -trajectory, expressions).
  bool moves() const { return follow_ >= 0 || curve_ >= 0 || tape_.has_value(); }
  // Why the element cannot be followed (an unknown body or trajectory, an
  // expression the name table cannot resolve); empty when it can.
  const std::string& error() const { return error_; }

 private:
  const SceneSampler& sampler_;
  std::string label_;  // "view 'NAME'" in messages
  ViewState base_;
  int follow_ = -1;                       // body index
  int curve_ = -1;                        // trajectory curve index (the sampler's)
  int pos_ = -1, rot_ = -1, scale_ = -1;  // first tape output of each expression
  int rot_count_ = 0;                     // 3: rotation vector; 4: quaternion
  expr::Pool pool_;
  std::optional<expr::Tape> tape_;
  size_t outputs_ = 0;
  std::string error_;
};

}  // namespace asgard::render
