// SUNDIALS peers: CVODE (BDF) and ARKODE (TR-BDF2), both with KLU and
// Asgard's symbolic Jacobian, on Asgard's own equations.
#include <arkode/arkode_arkstep.h>
#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include <cstring>

#include "bench/peers.h"

namespace asgard::bench {

namespace {

int Rhs(sunrealtype t, N_Vector y, N_Vector f, void* user) {
  static_cast<const TapeOde*>(user)->Rhs(t, N_VGetArrayPointer(y), N_VGetArrayPointer(f));
  return 0;
}

int Jac(sunrealtype t, N_Vector y, N_Vector /*fy*/, SUNMatrix J, void* user, N_Vector, N_Vector,
        N_Vector) {
  const auto* ode = static_cast<const TapeOde*>(user);
  sunindextype* cp = SUNSparseMatrix_IndexPointers(J);
  sunindextype* ri = SUNSparseMatrix_IndexValues(J);
  for (size_t i = 0; i < ode->col_ptr().size(); ++i) cp[i] = ode->col_ptr()[i];
  for (size_t i = 0; i < ode->row_index().size(); ++i) ri[i] = ode->row_index()[i];
  ode->Jacobian(t, N_VGetArrayPointer(y), SUNSparseMatrix_Data(J));
  return 0;
}

struct Common {
  SUNContext ctx = nullptr;
  N_Vector y = nullptr;
  SUNMatrix A = nullptr;
  SUNLinearSolver ls = nullptr;
  explicit Common(const TapeOde& ode) {
    SUNContext_Create(nullptr, &ctx);
    y = N_VNew_Serial(ode.size(), ctx);
    std::memcpy(N_VGetArrayPointer(y), ode.initial().data(), sizeof(double) * ode.size());
    A = SUNSparseMatrix(ode.size(), ode.size(), std::max(1, ode.nnz()), CSC_MAT, ctx);
    ls = SUNLinSol_KLU(y, A, ctx);
  }
  ~Common() {
    SUNLinSolFree(ls);
    SUNMatDestroy(A);
    N_VDestroy(y);
    SUNContext_Free(&ctx);
  }
  Common(const Common&) = delete;
  Common& operator=(const Common&) = delete;
};

PeerRun RunCvode(const TapeOde& ode, double rtol, double atol, const std::vector<double>& times) {
  PeerRun out;
  const double c0 = ThreadCpuSeconds();
  Common c(ode);
  void* mem = CVodeCreate(CV_BDF, c.ctx);
  CVodeInit(mem, Rhs, ode.t0(), c.y);
  CVodeSStolerances(mem, rtol, atol);
  CVodeSetUserData(mem, const_cast<TapeOde*>(&ode));
  CVodeSetLinearSolver(mem, c.ls, c.A);
  CVodeSetJacFn(mem, Jac);
  CVodeSetMaxNumSteps(mem, 50000000);
  out.ok = true;
  out.traj.times = times;
  for (double tout : times) {
    double t = ode.t0();
    if (tout > ode.t0()) {
      const int rc = CVode(mem, tout, c.y, &t, CV_NORMAL);
      if (rc < 0) {
        out.ok = false;
        out.error = "CVode flag " + std::to_string(rc) + " at t=" + Num(t);
        break;
      }
    }
    out.traj.poses.push_back(ode.Poses(N_VGetArrayPointer(c.y)));
  }
  out.cpu = ThreadCpuSeconds() - c0;
  long v = 0;
  CVodeGetNumSteps(mem, &v), out.steps = v;
  CVodeGetNumRhsEvals(mem, &v), out.rhs = v;
  CVodeGetNumJacEvals(mem, &v), out.jac = v;
  CVodeGetNumLinSolvSetups(mem, &v), out.factorizations = v;
  CVodeGetNumErrTestFails(mem, &v), out.rejected = v;
  CVodeFree(&mem);
  return out;
}

PeerRun RunArkode(const TapeOde& ode, double rtol, double atol, const std::vector<double>& times) {
  PeerRun out;
  const double c0 = ThreadCpuSeconds();
  Common c(ode);
  void* mem = ARKStepCreate(nullptr, Rhs, ode.t0(), c.y, c.ctx);
  ARKStepSetTableNum(mem, ARKODE_TRBDF2_3_3_2, ARKODE_ERK_NONE);
  ARKStepSStolerances(mem, rtol, atol);
  ARKStepSetUserData(mem, const_cast<TapeOde*>(&ode));
  ARKStepSetLinearSolver(mem, c.ls, c.A);
  ARKStepSetJacFn(mem, Jac);
  ARKStepSetMaxNumSteps(mem, 50000000);
  out.ok = true;
  out.traj.times = times;
  for (double tout : times) {
    double t = ode.t0();
    if (tout > ode.t0()) {
      const int rc = ARKStepEvolve(mem, tout, c.y, &t, ARK_NORMAL);
      if (rc < 0) {
        out.ok = false;
        out.error = "ARKStepEvolve flag " + std::to_string(rc) + " at t=" + Num(t);
        break;
      }
    }
    out.traj.poses.push_back(ode.Poses(N_VGetArrayPointer(c.y)));
  }
  out.cpu = ThreadCpuSeconds() - c0;
  long v = 0, fe = 0, fi = 0;
  ARKStepGetNumSteps(mem, &v), out.steps = v;
  ARKStepGetNumRhsEvals(mem, &fe, &fi), out.rhs = fe + fi;
  ARKStepGetNumJacEvals(mem, &v), out.jac = v;
  ARKStepGetNumLinSolvSetups(mem, &v), out.factorizations = v;
  ARKStepGetNumErrTestFails(mem, &v), out.rejected = v;
  ARKStepFree(&mem);
  return out;
}

}  // namespace

void AddSundialsPeers(std::vector<OdePeer>& out) {
  out.push_back({"cvode_bdf_klu", RunCvode});
  out.push_back({"arkode_trbdf2", RunArkode});
}

}  // namespace asgard::bench
