// Boost.Odeint peers on Asgard's equations: Dormand–Prince 5(4) and
// Rosenbrock 4(3) (dense Jacobian from Asgard's symbolic one), with dense
// output at the frame times.  The odeint code itself is in odeint_impl.cc.
#include "bench/odeint_iface.h"
#include "bench/peers.h"

namespace asgard::bench {

namespace {

odeint_iface::System Wrap(const TapeOde& ode, PeerRun& out, std::vector<double>& vals) {
  odeint_iface::System s;
  s.n = ode.size();
  s.y0 = ode.initial();
  s.t0 = ode.t0();
  s.t1 = ode.t1();
  s.rhs = [&ode](double t, const double* y, double* f) { ode.Rhs(t, y, f); };
  vals.resize(static_cast<size_t>(ode.nnz()));
  s.jacobian = [&ode, &vals](double t, const double* y, double* J) {
    ode.Jacobian(t, y, vals.data());
    const int n = ode.size();
    for (int c = 0; c < n; ++c)
      for (int k = ode.col_ptr()[c]; k < ode.col_ptr()[c + 1]; ++k)
        J[ode.row_index()[k] * n + c] = vals[k];
  };
  s.observe = [&ode, &out](const double* y) { out.traj.poses.push_back(ode.Poses(y)); };
  return s;
}

PeerRun Run(const TapeOde& ode, double rtol, double atol, const std::vector<double>& times,
            bool rosenbrock) {
  PeerRun out;
  const double c0 = ThreadCpuSeconds();
  const long rhs0 = ode.rhs_count, jac0 = ode.jac_count;
  std::vector<double> vals;
  out.traj.times = times;
  const auto sys = Wrap(ode, out, vals);
  const auto r = rosenbrock ? odeint_iface::Rosenbrock4(sys, rtol, atol, times)
                            : odeint_iface::Dopri5(sys, rtol, atol, times);
  out.cpu = ThreadCpuSeconds() - c0;
  out.ok = r.ok;
  out.error = r.error;
  out.steps = r.steps;
  out.rhs = ode.rhs_count - rhs0;
  out.jac = ode.jac_count - jac0;
  out.factorizations = out.jac;  // rosenbrock4: one LU per Jacobian
  return out;
}

PeerRun Dopri5(const TapeOde& o, double r, double a, const std::vector<double>& t) {
  return Run(o, r, a, t, false);
}
PeerRun Rosenbrock4(const TapeOde& o, double r, double a, const std::vector<double>& t) {
  return Run(o, r, a, t, true);
}

}  // namespace

void AddOdeintPeers(std::vector<OdePeer>& out) {
  out.push_back({"odeint_dopri5", Dopri5});
  out.push_back({"odeint_rosenbrock4", Rosenbrock4});
}

}  // namespace asgard::bench
