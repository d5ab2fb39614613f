// Boost.Odeint runners behind odeint_iface.h (compiled as C++17).
#include <boost/numeric/odeint.hpp>
#include <cmath>

#include "bench/odeint_iface.h"

namespace asgard::bench::odeint_iface {

namespace odeint = boost::numeric::odeint;
namespace ublas = boost::numeric::ublas;

Result Dopri5(const System& s, double rtol, double atol, const std::vector<double>& times) {
  Result out;
  std::vector<double> y = s.y0;
  auto sys = [&](const std::vector<double>& x, std::vector<double>& dx, double t) {
    dx.resize(x.size());
    s.rhs(t, x.data(), dx.data());
  };
  auto stepper =
      odeint::make_dense_output(atol, rtol, odeint::runge_kutta_dopri5<std::vector<double>>());
  try {
    out.steps = static_cast<long>(odeint::integrate_times(
        stepper, sys, y, times.begin(), times.end(), 1e-4 * (s.t1 - s.t0),
        [&](const std::vector<double>& x, double) { s.observe(x.data()); },
        odeint::max_step_checker(100000000)));
    out.ok = true;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

Result Rosenbrock4(const System& s, double rtol, double atol, const std::vector<double>& times) {
  Result out;
  const size_t n = static_cast<size_t>(s.n);
  ublas::vector<double> y(n);
  for (size_t i = 0; i < n; ++i) y[i] = s.y0[i];
  std::vector<double> J(n * n), xs(n), f0(n), f1(n);
  auto sys = [&](const ublas::vector<double>& x, ublas::vector<double>& dx, double t) {
    s.rhs(t, &x[0], &dx[0]);
  };
  auto jac = [&](const ublas::vector<double>& x, ublas::matrix<double>& M, double t,
                 ublas::vector<double>& dfdt) {
    std::fill(J.begin(), J.end(), 0.0);
    s.jacobian(t, &x[0], J.data());
    for (size_t r = 0; r < n; ++r)
      for (size_t c = 0; c < n; ++c) M(r, c) = J[r * n + c];
    // ∂f/∂t by a central difference (explicit time dependence only).
    for (size_t i = 0; i < n; ++i) xs[i] = x[i];
    const double dt = 1e-7 * std::max(1.0, std::abs(t));
    s.rhs(t + dt, xs.data(), f1.data());
    s.rhs(t - dt, xs.data(), f0.data());
    for (size_t i = 0; i < n; ++i) dfdt[i] = (f1[i] - f0[i]) / (2 * dt);
  };
  auto stepper = odeint::make_dense_output(atol, rtol, odeint::rosenbrock4<double>());
  try {
    out.steps = static_cast<long>(odeint::integrate_times(
        stepper, std::make_pair(sys, jac), y, times.begin(), times.end(), 1e-4 * (s.t1 - s.t0),
        [&](const ublas::vector<double>& x, double) { s.observe(&x[0]); },
        odeint::max_step_checker(100000000)));
    out.ok = true;
  } catch (const std::exception& e) {
    out.error = e.what();
  }
  return out;
}

}  // namespace asgard::bench::odeint_iface
