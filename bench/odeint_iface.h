// Plain interface to the Boost.Odeint runners.  odeint_impl.cc is compiled
// as C++17 on its own: Boost 1.74's uBLAS (needed by rosenbrock4) uses
// std::allocator members that C++20 removed.
#pragma once

#include <functional>
#include <string>
#include <vector>

namespace asgard::bench::odeint_iface {

struct System {
  int n = 0;
  std::vector<double> y0;
  double t0 = 0, t1 = 0;
  std::function<void(double t, const double* y, double* f)> rhs;
  // Dense Jacobian, row-major n × n, written into J (zeroed by the caller).
  std::function<void(double t, const double* y, double* J)> jacobian;
  // Called at each output time with the state.
  std::function<void(const double* y)> observe;
};

struct Result {
  bool ok = false;
  std::string error;
  long steps = 0;
};

Result Dopri5(const System& s, double rtol, double atol, const std::vector<double>& times);
Result Rosenbrock4(const System& s, double rtol, double atol, const std::vector<double>& times);

}  // namespace asgard::bench::odeint_iface
