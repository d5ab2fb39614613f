#include "bench/model.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <sstream>

#include "core/lang/lang.h"
#include "core/physics/joints.h"

namespace asgard::bench {

namespace {

std::string Vec(double x, double y, double z) {
  std::ostringstream s;
  s.precision(17);
  s << "{" << x << " " << y << " " << z << "}";
  return s.str();
}

std::string Real(double v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

// Jacobi sn(u | m) by the arithmetic–geometric mean (Abramowitz & Stegun 16.4).
double JacobiSn(double u, double m) {
  constexpr int kMax = 20;
  double a[kMax + 1], c[kMax + 1];
  a[0] = 1.0;
  c[0] = std::sqrt(m);
  double b = std::sqrt(1.0 - m);
  int n = 0;
  while (n < kMax && std::abs(c[n]) > 1e-17) {
    a[n + 1] = 0.5 * (a[n] + b);
    c[n + 1] = 0.5 * (a[n] - b);
    b = std::sqrt(a[n] * b);
    ++n;
  }
  double phi = std::ldexp(a[n] * u, n);
  for (; n > 0; --n) phi = 0.5 * (phi + std::asin(c[n] / a[n] * std::sin(phi)));
  return std::sin(phi);
}

Pose ZPose(double x, double y, double angle) {
  Pose p;
  p.p[0] = x;
  p.p[1] = y;
  p.q[0] = std::cos(0.5 * angle);
  p.q[3] = std::sin(0.5 * angle);
  return p;
}

}  // namespace

std::string BallShape() { return "shape_set ball -desc {-sub {-pos {0 0 0} -sphere 0.5}}\n"; }

std::string PendulumText(const std::string& name, const double* pivot, double len, double theta0,
                         double g, double k, double mass) {
  const double s = std::sin(theta0), c = std::cos(theta0);
  std::ostringstream t;
  t << "body " << name << " -shape ball -mass " << Real(mass) << " -init_pos "
    << Vec(pivot[0] + len * s, pivot[1] - len * c, pivot[2]) << "\n"
    << "link -body1 " << name << " -offset1 " << Vec(-len * s, len * c, 0) << " -x "
    << Real(pivot[0]) << " -y " << Real(pivot[1]) << " -z " << Real(pivot[2]);
  if (k > 0) t << " -tightness " << Real(k);  // else an exact joint
  t << "\n"
    << "force -body " << name << " -x 0 -y " << Real(-g) << " -z 0 -gravitational 1\n";
  return t.str();
}

double PendulumAngle(double theta0, double omega, double t) {
  const double k = std::sin(0.5 * theta0);
  const double K = std::comp_ellint_1(k);
  return 2.0 * std::asin(k * JacobiSn(K - omega * t, k * k));
}

WpScene SimplePendulumScene() {
  WpScene s;
  s.name = "pendulum";
  const double pivot[3] = {0, 0, 0};
  s.text = BallShape() + PendulumText("m", pivot, 1.0, 1.0, 9.81, 0) + "simulator -finish 10\n";
  s.size = 2.0;
  s.radii = {0.5};
  RigidChain c;
  c.bodies = 1;
  c.mass = {1.0};
  c.inertia = {0.1};
  c.arm = {1.0};
  c.joint = {0.0};
  c.theta0 = {1.0};
  s.rigid = c;
  return s;
}

WpScene DoublePendulumScene() {
  WpScene s;
  s.name = "double_pendulum";
  const double th1 = 1.0, th2 = 0.3;
  const double u1[2] = {std::sin(th1), -std::cos(th1)}, u2[2] = {std::sin(th2), -std::cos(th2)};
  std::ostringstream t;
  t << BallShape() << "body a -shape ball -mass 1 -artbody dp -ct 0 -init_pos "
    << Vec(u1[0], u1[1], 0) << "\n"
    << "body b -shape ball -mass 1 -artbody dp -ct 0 -init_pos "
    << Vec(2 * u1[0] + u2[0], 2 * u1[1] + u2[1], 0) << "\n"
    << "link -body1 a -offset1 " << Vec(-u1[0], -u1[1], 0) << " -x 0 -y 0 -z 0\n"
    << "link -body1 b -offset1 " << Vec(-u2[0], -u2[1], 0) << " -body2 a -offset2 "
    << Vec(u1[0], u1[1], 0) << "\n"
    << "force -body a -x 0 -y -9.81 -z 0 -gravitational 1\n"
    << "force -body b -x 0 -y -9.81 -z 0 -gravitational 1\n"
    << "simulator -finish 10\n";
  s.text = t.str();
  s.size = 3.0;
  s.radii = {0.5, 0.5};
  RigidChain c;
  c.bodies = 2;
  c.mass = {1, 1};
  c.inertia = {0.1, 0.1};
  c.arm = {1, 1};
  c.joint = {2, 0};
  c.theta0 = {th1, th2};
  s.rigid = c;
  return s;
}

WpScene TopScene() {
  WpScene s;
  s.name = "top";
  s.text = BallShape() +
           "body top -shape ball -mass 1 -moment {1 2 2.5} -init_drot {0.3 3 0.4}\n"
           "simulator -finish 10\n";
  s.size = 1.0;
  s.radii = {0.5};
  s.top = std::array<double, 6>{1, 2, 2.5, 0.3, 3, 0.4};
  return s;
}

std::array<double, 2> RigidChain::Pivot0(int i) const {
  std::array<double, 2> p{0.0, 0.0};
  for (int a = Parent(i); a >= 0; a = Parent(a)) {
    p[0] += joint[a] * std::sin(theta0[a]);
    p[1] -= joint[a] * std::cos(theta0[a]);
  }
  return p;
}

double RigidChain::Reach() const {
  double best = 0.0;
  for (int i = 0; i < bodies; ++i) {
    double len = std::max(arm[i], joint[i]);
    for (int a = Parent(i); a >= 0; a = Parent(a)) len += joint[a];
    best = std::max(best, len);
  }
  return best;
}

std::string RigidChainText(const RigidChain& c, double t1) {
  std::ostringstream t;
  t << BallShape();
  for (int i = 0; i < c.bodies; ++i) {
    const auto pv = c.Pivot0(i);
    const double ux = std::sin(c.theta0[i]), uy = -std::cos(c.theta0[i]);
    const std::string name = "b" + std::to_string(i);
    t << "body " << name << " -shape ball -mass " << Real(c.mass[i]) << " -moment "
      << Vec(c.inertia[i], c.inertia[i], c.inertia[i]) << " -artbody rigid -ct 0 -init_pos "
      << Vec(pv[0] + c.arm[i] * ux, pv[1] + c.arm[i] * uy, 0) << "\n"
      << "link -body1 " << name << " -offset1 " << Vec(-c.arm[i] * ux, -c.arm[i] * uy, 0);
    const int p = c.Parent(i);
    if (p < 0) {
      t << " -x " << Real(pv[0]) << " -y " << Real(pv[1]) << " -z 0\n";
    } else {
      const double d = c.joint[p] - c.arm[p];
      t << " -body2 b" << p << " -offset2 "
        << Vec(d * std::sin(c.theta0[p]), -d * std::cos(c.theta0[p]), 0) << "\n";
    }
    t << "force -body " << name << " -x 0 -y " << Real(-c.g) << " -z 0 -gravitational 1\n";
  }
  t << "simulator -finish " << Real(t1) << "\n";
  return t.str();
}

WpScene TreeScene(int n, double t1) {
  RigidChain c;
  c.bodies = n;
  for (int i = 0; i < n; ++i) {
    const int p = i == 0 ? -1 : (i - 1) / 2;
    c.parent.push_back(p);
    c.mass.push_back(1.0);
    c.inertia.push_back((1.0 + 0.01) / 12.0);  // a 1 × 0.1 × 0.1 rod about z
    c.arm.push_back(0.5);
    c.joint.push_back(1.0);
    // Spread branches: left children turn one way, right children less the
    // other way, so no two bodies move alike.
    c.theta0.push_back(p < 0 ? 1.0 : c.theta0[p] + (i % 2 ? 0.45 : -0.3));
  }
  WpScene s;
  s.name = "tree" + std::to_string(n);
  s.text = RigidChainText(c, t1);
  s.t1 = t1;
  s.size = c.Reach();
  s.radii.assign(n, 0.5);
  s.rigid = c;
  return s;
}

WpScene ChainScene(int n, double t1) {
  WpScene s;
  s.name = "chain" + std::to_string(n);
  std::ostringstream t;
  t << "shape_set rod -desc {-sub {-box {1 0.1 0.1}}}\n";
  for (int i = 0; i < n; ++i) {
    t << "body r" << i << " -shape rod -mass 1 -artbody chain -ct 0 -init_pos "
      << Vec(i + 0.5, 0, 0) << "\n";
    if (i == 0) {
      t << "link -body1 r0 -offset1 {-0.5 0 0} -x 0 -y 0 -z 0\n";
    } else {
      t << "link -body1 r" << i << " -offset1 {-0.5 0 0} -body2 r" << i - 1
        << " -offset2 {0.5 0 0}\n";
    }
    t << "force -body r" << i << " -x 0 -y -9.81 -z 0 -gravitational 1\n";
  }
  t << "simulator -finish " << Real(t1) << "\n";  // chaotic: keep the span short
  s.text = t.str();
  s.t1 = t1;
  s.size = n;
  s.radii.assign(n, 0.5);
  RigidChain c;
  c.bodies = n;
  for (int i = 0; i < n; ++i) {
    c.mass.push_back(1.0);
    c.inertia.push_back((1.0 + 0.01) / 12.0);  // box 1 × 0.1 × 0.1 about z
    c.arm.push_back(0.5);
    c.joint.push_back(1.0);
    c.theta0.push_back(M_PI / 2);
  }
  s.rigid = c;
  return s;
}

// A ball on a critically damped link to the point (sin t, 0, 0), starting on
// it with its velocity: e = x − sin t obeys ë + 2ω ė + ω² e = sin t, e(0) = 0,
// ė(0) = 0, solved in closed form below.
WpScene StiffLinkScene(double k) {
  WpScene s;
  std::ostringstream name;
  name << "stiff_link_k1e" << std::lround(std::log10(k));
  s.name = name.str();
  s.text = BallShape() +
           "body d -shape ball -mass 1 -init_pos {0 0 0} -init_dpos {1 0 0}\n"
           "link -body1 d -offset1 {0 0 0} -x {sin(t)} -y 0 -z 0 -tightness " +
           Real(k) + "\nsimulator -finish 10\n";
  s.size = 1.0;
  s.radii = {0.5};
  const double w = std::sqrt(k);
  s.exact_name = "closed form";
  s.exact = [w](const std::vector<double>& times) {
    const double D = (w * w + 1) * (w * w + 1);
    const double A = (w * w - 1) / D, B = -2 * w / D;
    const double C1 = -B, C2 = -A + w * C1;
    Trajectory tr;
    tr.times = times;
    for (double t : times) {
      const double e = A * std::sin(t) + B * std::cos(t) + (C1 + C2 * t) * std::exp(-w * t);
      Pose p;
      p.p[0] = std::sin(t) + e;
      tr.poses.push_back({p});
    }
    return tr;
  };
  return s;
}

WpScene BallsInBoxScene(int n) {
  WpScene s;
  s.name = "balls_in_box" + std::to_string(n);
  HardSpheres hs;
  std::mt19937 rng(12345);
  std::uniform_real_distribution<double> pos(-4.0, 4.0), vel(-3.0, 3.0);
  while (static_cast<int>(hs.p.size()) < n) {
    std::array<double, 3> p{pos(rng), pos(rng), pos(rng)};
    bool clear = true;
    for (const auto& q : hs.p) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += (p[a] - q[a]) * (p[a] - q[a]);
      clear &= d2 > 1.2 * 1.2;
    }
    if (!clear) continue;
    hs.p.push_back(p);
    hs.v.push_back({vel(rng), vel(rng), vel(rng)});
  }
  std::ostringstream t;
  t << BallShape();
  for (int i = 0; i < n; ++i)
    t << "body b" << i << " -shape ball -mass 1 -init_pos "
      << Vec(hs.p[i][0], hs.p[i][1], hs.p[i][2]) << " -init_dpos "
      << Vec(hs.v[i][0], hs.v[i][1], hs.v[i][2]) << "\n";
  t << "shape_set wx -desc {-sub {-box {1 12 12}}}\n"
       "shape_set wy -desc {-sub {-box {12 1 12}}}\n"
       "shape_set wz -desc {-sub {-box {12 12 1}}}\n"
       "body xlo -shape wx -static 1 -init_pos {-5.5 0 0}\n"
       "body xhi -shape wx -static 1 -init_pos {5.5 0 0}\n"
       "body ylo -shape wy -static 1 -init_pos {0 -5.5 0}\n"
       "body yhi -shape wy -static 1 -init_pos {0 5.5 0}\n"
       "body zlo -shape wz -static 1 -init_pos {0 0 -5.5}\n"
       "body zhi -shape wz -static 1 -init_pos {0 0 5.5}\n"
       "simulator -finish 10\n";
  s.text = t.str();
  s.size = 10.0;
  s.radii.assign(n, 0.5);
  s.collisions = true;
  s.exact_name = "event-driven hard spheres (exact)";
  s.exact = [hs](const std::vector<double>& times) { return HardSpheresExact(hs, times); };
  return s;
}

Trajectory SampleAsgard(const pipeline::Run& run, const std::vector<double>& times) {
  Trajectory tr;
  tr.times = times;
  const auto& eq = *run.equations;
  for (double t : times) {
    std::vector<Pose> row;
    for (size_t b = 0; b < eq.bodies.size(); ++b) {
      if (eq.bodies[b].is_static) continue;
      const pipeline::BodyFrame f =
          pipeline::SampleBody(eq, *run.simulation, static_cast<int>(b), t);
      Pose p;
      for (int a = 0; a < 3; ++a) p.p[a] = f.p[a];
      for (int a = 0; a < 4; ++a) p.q[a] = f.q[a];
      row.push_back(p);
    }
    tr.poses.push_back(std::move(row));
  }
  return tr;
}

double SetupCpu(const std::string& text, int repeats) {
  std::vector<double> v;
  for (int i = 0; i < repeats; ++i) {
    const double c0 = ThreadCpuSeconds();
    pipeline::Run r = pipeline::Check(text);
    v.push_back(ThreadCpuSeconds() - c0);
  }
  return Median(v);
}

AsgardRun RunAsgard(const std::string& text, const pipeline::RunOptions& options,
                    const std::vector<double>& frame_times, double setup_cpu) {
  AsgardRun out;
  const double c0 = ThreadCpuSeconds();
  pipeline::Run run = pipeline::Check(lang::Evaluate(text), options);
  const double c1 = ThreadCpuSeconds();
  pipeline::Solve(run, options);
  const double c2 = ThreadCpuSeconds();
  out.total_cpu = c2 - c0;
  // The solver phase (simulation set-up and run) in thread CPU seconds, as
  // the peers are timed (load from other processes does not inflate it);
  // scene evaluation and equation forming are excluded, as they are for the
  // peers.  Falls back to CPU minus set-up when the run did not start.
  out.solver_wall = run.seconds;
  out.cpu = run.seconds > 0 ? std::max(1e-7, c2 - c1) : std::max(1e-7, out.total_cpu - setup_cpu);
  out.ok = run.ok;
  if (!run.ok) {
    out.error = run.solver_error;
    if (out.error.empty())
      for (const auto& d : run.diagnostics)
        if (d.severity == scene::Severity::kError) {
          out.error = d.message;
          break;
        }
  }
  if (run.simulation) {
    out.counters = run.simulation->totals();
    out.components = run.simulation->component_count();
  }
  if (run.collisions) out.impacts = static_cast<long>(run.collisions->impacts().size());
  if (run.ok && !frame_times.empty()) out.traj = SampleAsgard(run, frame_times);
  return out;
}

// ---- TapeOde --------------------------------------------------------------

TapeOde::TapeOde(const std::string& text) {
  pipeline::Run run = pipeline::Check(text);
  if (!run.ok || !run.equations) return;
  eq_ = std::move(run.equations);
  const auto& eq = *eq_;
  n_ = static_cast<int>(eq.variables.size());
  t0_ = eq.t0;
  t1_ = eq.t1;
  for (const auto& v : eq.variables) {
    if (!v.overrides.empty()) return;
    y0_.push_back(v.initial);
  }
  expr::Pool pool = eq.pool;
  std::vector<expr::NodeId> rhs;
  for (const auto& v : eq.variables) rhs.push_back(v.rhs);
  // Jacobian entries by column.  Exact joints have no symbolic form: their
  // Jacobian is dense and taken by difference quotients.
  std::vector<std::vector<std::pair<int, expr::NodeId>>> cols(n_);
  if (!eq.joints.empty()) {
    std::vector<int> joints(eq.joints.size());
    for (size_t j = 0; j < joints.size(); ++j) joints[j] = static_cast<int>(j);
    joints_ = std::make_shared<physics::JointSolver>(
        eq, joints, [&eq](int b) { return eq.bodies[b].first_var; });
    prescribed_.assign(n_, 0);
    for (int j = 0; j < n_; ++j)
      for (int i = 0; i < n_; ++i) cols[j].push_back({i, pool.Const(0.0)});
  }
  for (int i = 0; i < n_ && !joints_; ++i)
    for (int j : pool.Variables(rhs[i])) cols[j].push_back({i, pool.Derivative(rhs[i], j)});
  std::vector<expr::NodeId> jac;
  col_ptr_.push_back(0);
  for (int j = 0; j < n_; ++j) {
    std::sort(cols[j].begin(), cols[j].end());
    for (auto [i, d] : cols[j]) {
      row_index_.push_back(i);
      jac.push_back(d);
    }
    col_ptr_.push_back(static_cast<int>(row_index_.size()));
  }
  rhs_ = std::make_unique<expr::Tape>(expr::Tape::Compile(pool, rhs));
  jac_ = std::make_unique<expr::Tape>(expr::Tape::Compile(pool, jac));
  ext_ = eq.externs();
  for (const auto& b : eq.bodies) {
    BodyInfo info{b.first_var, {b.x0[0], b.x0[1], b.x0[2], b.q0.w(), b.q0.x(), b.q0.y(), b.q0.z()}};
    if (!b.is_static) bodies_.push_back(info);
  }
  ok_ = true;
}

void TapeOde::Rhs(double t, const double* y, double* f) const {
  ++rhs_count;
  rhs_->Evaluate(t, y, f, &ext_);
  if (joints_) joints_->Apply(t, y, f, prescribed_.data(), &ext_);
}

void TapeOde::Jacobian(double t, const double* y, double* values) const {
  ++jac_count;
  if (!joints_) {
    jac_->Evaluate(t, y, values, &ext_);
    return;
  }
  // Dense, column by column (CSC order is column-major).
  std::vector<double> yp(y, y + n_), f0(n_), f1(n_);
  Rhs(t, y, f0.data());
  for (int c = 0; c < n_; ++c) {
    const double d =
        std::sqrt(std::numeric_limits<double>::epsilon()) * std::max(std::abs(y[c]), 1e-3);
    yp[c] = y[c] + d;
    Rhs(t, yp.data(), f1.data());
    const double step = yp[c] - y[c];
    yp[c] = y[c];
    for (int r = 0; r < n_; ++r) values[static_cast<size_t>(c) * n_ + r] = (f1[r] - f0[r]) / step;
  }
}

std::vector<Pose> TapeOde::Poses(const double* y) const {
  std::vector<Pose> out;
  for (const auto& b : bodies_) {
    Pose p;
    if (b.first_var < 0) {
      for (int a = 0; a < 3; ++a) p.p[a] = b.fixed[a];
      for (int a = 0; a < 4; ++a) p.q[a] = b.fixed[3 + a];
    } else {
      for (int a = 0; a < 3; ++a) p.p[a] = y[b.first_var + physics::kX + a];
      double nq = 0;
      for (int a = 0; a < 4; ++a)
        nq += y[b.first_var + physics::kQw + a] * y[b.first_var + physics::kQw + a];
      nq = std::sqrt(nq);
      for (int a = 0; a < 4; ++a) p.q[a] = y[b.first_var + physics::kQw + a] / nq;
    }
    out.push_back(p);
  }
  return out;
}

// ---- rigid chain reference -------------------------------------------------

namespace {
// A planar chain or tree in absolute angles θ (from the downward vertical).
// Body k's centre is Σ_i L(k,i) (sin θ_i, −cos θ_i) with L(k,i) = joint[i] for
// i a strict ancestor of k, arm[k] for i = k, else 0, so Lagrange's equations
// are  Σ_j (H_ij cos(θ_i − θ_j) + I_i δ_ij) θ̈_j =
//        −g sin θ_i G_i − Σ_j H_ij sin(θ_i − θ_j) θ̇_j²,
// H_ij = Σ_k m_k L(k,i) L(k,j) and G_i = Σ_k m_k L(k,i) constant.  H_ij ≠ 0
// only where one of i, j is an ancestor of the other, so the mass matrix is
// factored as Lᵀ L from the leaves (Featherstone's LTL), with no fill: a
// tree costs Σ depth², a chain n³/6.
class RigidModel {
 public:
  explicit RigidModel(const RigidChain& c)
      : c_(c), n_(c.bodies), anc_(n_), H_(n_ * n_, 0.0), G_(n_, 0.0), M_(n_ * n_), s_(n_), co_(n_) {
    for (int k = 0; k < n_; ++k)
      for (int a = c.Parent(k); a >= 0; a = c.Parent(a)) anc_[k].push_back(a);  // nearest first
    for (int k = 0; k < n_; ++k) {
      std::vector<std::pair<int, double>> L{{k, c.arm[k]}};
      for (int a : anc_[k]) L.push_back({a, c.joint[a]});
      for (auto [i, li] : L) {
        G_[i] += c.mass[k] * li;
        for (auto [j, lj] : L) H_[i * n_ + j] += c.mass[k] * li * lj;
      }
    }
  }
  // θ̈ from θ and θ̇.
  void Accel(const double* th, const double* om, double* acc) {
    double* M = M_.data();  // row k, column a: a = k or an ancestor of k
    for (int i = 0; i < n_; ++i) {
      s_[i] = std::sin(th[i]), co_[i] = std::cos(th[i]);
      acc[i] = -c_.g * s_[i] * G_[i];
      M[i * n_ + i] = H_[i * n_ + i] + c_.inertia[i];
    }
    for (int i = 0; i < n_; ++i)
      for (int a : anc_[i]) {
        const double h = H_[i * n_ + a], sn = s_[i] * co_[a] - co_[i] * s_[a];
        M[i * n_ + a] = h * (co_[i] * co_[a] + s_[i] * s_[a]);
        acc[i] -= h * sn * om[a] * om[a];
        acc[a] += h * sn * om[i] * om[i];
      }
    for (int k = n_ - 1; k >= 0; --k) {  // M = Lᵀ L, leaves first
      const double d = std::sqrt(M[k * n_ + k]);
      M[k * n_ + k] = d;
      for (int a : anc_[k]) M[k * n_ + a] /= d;
      const auto& A = anc_[k];
      for (size_t p = 0; p < A.size(); ++p)
        for (size_t q = p; q < A.size(); ++q)
          M[A[p] * n_ + A[q]] -= M[k * n_ + A[p]] * M[k * n_ + A[q]];
    }
    for (int k = n_ - 1; k >= 0; --k) {  // Lᵀ y = b
      acc[k] /= M[k * n_ + k];
      for (int a : anc_[k]) acc[a] -= M[k * n_ + a] * acc[k];
    }
    for (int k = 0; k < n_; ++k) {  // L x = y
      for (int a : anc_[k]) acc[k] -= M[k * n_ + a] * acc[a];
      acc[k] /= M[k * n_ + k];
    }
  }
  std::vector<Pose> Poses(const double* th) const {
    std::vector<Pose> out;
    std::vector<double> jx(n_), jy(n_);  // joint positions
    for (int i = 0; i < n_; ++i) {
      const int p = c_.Parent(i);
      jx[i] = p < 0 ? 0.0 : jx[p] + c_.joint[p] * std::sin(th[p]);
      jy[i] = p < 0 ? 0.0 : jy[p] - c_.joint[p] * std::cos(th[p]);
      out.push_back(ZPose(jx[i] + c_.arm[i] * std::sin(th[i]), jy[i] - c_.arm[i] * std::cos(th[i]),
                          th[i] - c_.theta0[i]));
    }
    return out;
  }

 private:
  const RigidChain& c_;
  int n_;
  std::vector<std::vector<int>> anc_;  // strict ancestors, nearest first
  std::vector<double> H_, G_, M_, s_, co_;
};
}  // namespace

Trajectory RigidChainReference(const RigidChain& c, const std::vector<double>& times, double h) {
  Trajectory tr;
  tr.times = times;
  const int n = c.bodies;
  RigidModel model(c);
  if (n == 1) {
    const double leq = (c.inertia[0] + c.mass[0] * c.arm[0] * c.arm[0]) / (c.mass[0] * c.arm[0]);
    const double w = std::sqrt(c.g / leq);
    for (double t : times) {
      const double th = PendulumAngle(c.theta0[0], w, t);
      tr.poses.push_back(model.Poses(&th));
    }
    return tr;
  }
  std::vector<double> y(2 * n, 0.0), k1(2 * n), k2(2 * n), k3(2 * n), k4(2 * n), tmp(2 * n);
  for (int i = 0; i < n; ++i) y[i] = c.theta0[i];
  auto f = [&](const std::vector<double>& s, std::vector<double>& d) {
    for (int i = 0; i < n; ++i) d[i] = s[n + i];
    model.Accel(s.data(), s.data() + n, d.data() + n);
  };
  double t = times.front();
  for (double tf : times) {
    while (t < tf - 1e-15) {
      const double hh = std::min(h, tf - t);
      f(y, k1);
      for (int i = 0; i < 2 * n; ++i) tmp[i] = y[i] + 0.5 * hh * k1[i];
      f(tmp, k2);
      for (int i = 0; i < 2 * n; ++i) tmp[i] = y[i] + 0.5 * hh * k2[i];
      f(tmp, k3);
      for (int i = 0; i < 2 * n; ++i) tmp[i] = y[i] + hh * k3[i];
      f(tmp, k4);
      for (int i = 0; i < 2 * n; ++i) y[i] += hh / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
      t += hh;
    }
    tr.poses.push_back(model.Poses(y.data()));
  }
  return tr;
}

// ---- hard spheres ----------------------------------------------------------

Trajectory HardSpheresExact(const HardSpheres& s, const std::vector<double>& times,
                            long* collisions) {
  auto p = s.p;
  auto v = s.v;
  const int n = static_cast<int>(p.size());
  const double lim = 0.5 * s.box - s.radius;
  const double inf = std::numeric_limits<double>::infinity();
  double t = times.front();
  long count = 0;
  Trajectory tr;
  tr.times = times;
  auto advance = [&](double dt) {
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) p[i][a] += v[i][a] * dt;
  };
  for (double tf : times) {
    for (;;) {
      // Earliest event after t.
      double best = inf;
      int kind = -1, bi = -1, bj = -1;
      for (int i = 0; i < n; ++i)
        for (int a = 0; a < 3; ++a) {
          double dt = inf;
          if (v[i][a] > 0)
            dt = (lim - p[i][a]) / v[i][a];
          else if (v[i][a] < 0)
            dt = (-lim - p[i][a]) / v[i][a];
          dt = std::max(dt, 0.0);
          if (dt < best) best = dt, kind = 0, bi = i, bj = a;
        }
      for (int i = 0; i < n; ++i)
        for (int j = i + 1; j < n; ++j) {
          double dp[3], dv[3], b = 0, vv = 0, pp = 0;
          for (int a = 0; a < 3; ++a) {
            dp[a] = p[j][a] - p[i][a];
            dv[a] = v[j][a] - v[i][a];
            b += dp[a] * dv[a];
            vv += dv[a] * dv[a];
            pp += dp[a] * dp[a];
          }
          if (b >= 0 || vv == 0) continue;
          const double d = 2 * s.radius;
          const double disc = b * b - vv * (pp - d * d);
          if (disc < 0) continue;
          const double dt = std::max(0.0, (-b - std::sqrt(disc)) / vv);
          if (dt < best) best = dt, kind = 1, bi = i, bj = j;
        }
      if (t + best > tf) break;
      advance(best);
      t += best;
      ++count;
      if (kind == 0) {
        v[bi][bj] = -v[bi][bj];
      } else {
        double nrm[3], nn = 0, vn = 0;
        for (int a = 0; a < 3; ++a) {
          nrm[a] = p[bj][a] - p[bi][a];
          nn += nrm[a] * nrm[a];
        }
        nn = std::sqrt(nn);
        for (int a = 0; a < 3; ++a) {
          nrm[a] /= nn;
          vn += (v[bj][a] - v[bi][a]) * nrm[a];
        }
        for (int a = 0; a < 3; ++a) {  // equal masses, elastic
          v[bi][a] += vn * nrm[a];
          v[bj][a] -= vn * nrm[a];
        }
      }
    }
    advance(tf - t);
    t = tf;
    std::vector<Pose> row(n);
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < 3; ++a) row[i].p[a] = p[i][a];
    tr.poses.push_back(std::move(row));
  }
  if (collisions) *collisions = count;
  return tr;
}

}  // namespace asgard::bench
