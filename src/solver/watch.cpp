// Stops a running CBC or Clp solve from outside: event handlers, in the form COIN-OR's C++
// classes take them, that CBC's branch and bound (CbcEventHandler) and Clp's simplex and
// barrier iterations (ClpEventHandler) consult at every node and every iteration. Each one
// watches a flag the caller's thread raises (cancel, the caller's deadline) and, for Clp, a
// wall-clock deadline of its own (Clp's own limit counts the processor time of the whole
// process, which a busy host spends many times faster than the clock).
//
// Built by build.rs against the headers of the COIN-OR that is linked (the -src crates' or
// the system's), and called from src/solver (the only Rust that calls out to C).

#include <chrono>
#include <string>
#include <vector>

#include "CbcEventHandler.hpp"
#include "CbcModel.hpp"
#include "CbcSolver.hpp"
#include "ClpEventHandler.hpp"
#include "ClpSimplex.hpp"
#include "OsiClpSolverInterface.hpp"

// The structures behind the C interfaces' opaque pointers, which Coin_C_defines.h shows to
// C++ code that asks for them.
#define CBC_EXTERN_C
#define CLP_EXTERN_C
#include "Coin_C_defines.h"

namespace {

using Clock = std::chrono::steady_clock;

// When to stop: once `*flag` is non-zero, or (if `limited`) once the clock passes `deadline`.
// The flag belongs to the caller, who keeps it alive until the solve has returned.
struct Watch {
  const int *flag;
  bool limited;
  Clock::time_point deadline;

  bool over() const {
    if (__atomic_load_n(flag, __ATOMIC_RELAXED) != 0) {
      return true;
    }
    return limited && Clock::now() >= deadline;
  }
};

Watch make_watch(const int *flag, double seconds) {
  Watch watch;
  watch.flag = flag;
  watch.limited = seconds >= 0.0;
  watch.deadline = Clock::now();
  if (watch.limited) {
    watch.deadline += std::chrono::duration_cast<Clock::duration>(
        std::chrono::duration<double>(seconds));
  }
  return watch;
}

// CBC asks at every node, tree-status interval, solution and heuristic pass; `stop` ends the
// branch and bound at the next opportunity. CBC copies its handler (clone) into every model it
// makes from the one it is given (the preprocessed model, sub-searches of its heuristics).
class CbcStop : public CbcEventHandler {
public:
  explicit CbcStop(const Watch &watch) : CbcEventHandler(), watch_(watch) {}
  CbcStop(const CbcStop &other) : CbcEventHandler(other), watch_(other.watch_) {}
  CbcStop &operator=(const CbcStop &) = delete;
  CbcEventHandler *clone() const override { return new CbcStop(*this); }

  CbcAction event(CbcEvent which) override {
    return watch_.over() ? stop : CbcEventHandler::event(which);
  }
  CbcAction event(CbcEvent which, void *data) override {
    return watch_.over() ? stop : CbcEventHandler::event(which, data);
  }

private:
  Watch watch_;
};

// Clp asks at the end of every simplex and barrier iteration; a non-negative answer there
// ends the solve with status 5 ("stopped by event"). Other events keep Clp's defaults.
class ClpStop : public ClpEventHandler {
public:
  explicit ClpStop(const Watch &watch) : ClpEventHandler(), watch_(watch) {}
  ClpStop(const ClpStop &other) : ClpEventHandler(other), watch_(other.watch_) {}
  ClpStop &operator=(const ClpStop &) = delete;
  ClpEventHandler *clone() const override { return new ClpStop(*this); }

  int event(Event which) override {
    if (which == endOfIteration && watch_.over()) {
      return 0;
    }
    return ClpEventHandler::event(which);
  }

private:
  Watch watch_;
};

void watch_clp(ClpSimplex *simplex, const Watch &watch) {
  if (simplex != NULL) {
    ClpStop handler(watch);
    simplex->passInEventHandler(&handler); // keeps a clone
  }
}

} // namespace

extern "C" {

// Makes the CBC model behind `model` (a Cbc_Model of CBC's C interface, before Cbc_solve)
// stop once `*flag` is non-zero: its branch and bound, and the Clp simplex under it (the root
// linear program, which CBC does not time, and every resolve). Returns 0, or -1 for a null
// model. Throws nothing.
int tp_cbc_watch(void *model, const int *flag) {
  Cbc_Model *cbc = static_cast<Cbc_Model *>(model);
  if (cbc == NULL || cbc->model_ == NULL || flag == NULL) {
    return -1;
  }
  try {
    Watch watch = make_watch(flag, -1.0);
    CbcStop handler(watch);
    cbc->model_->passInEventHandler(&handler); // keeps a clone
    OsiClpSolverInterface *solver =
        dynamic_cast<OsiClpSolverInterface *>(cbc->model_->solver());
    if (solver != NULL) {
      watch_clp(solver->getModelPtr(), watch);
    }
    if (cbc->solver_ != NULL && cbc->solver_ != solver) {
      watch_clp(cbc->solver_->getModelPtr(), watch);
    }
  } catch (...) {
    return -1;
  }
  return 0;
}

// Makes the Clp model behind `model` (a Clp_Simplex of Clp's C interface) stop once `*flag`
// is non-zero or `seconds` of wall-clock time (from now) have passed; a negative `seconds`
// sets no limit. Returns 0, or -1 for a null model. Throws nothing.
int tp_clp_watch(void *model, const int *flag, double seconds) {
  Clp_Simplex *clp = static_cast<Clp_Simplex *>(model);
  if (clp == NULL || clp->model_ == NULL || flag == NULL) {
    return -1;
  }
  try {
    watch_clp(clp->model_, make_watch(flag, seconds));
  } catch (...) {
    return -1;
  }
  return 0;
}

} // extern "C"
