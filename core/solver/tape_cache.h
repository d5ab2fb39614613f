// Compiled tapes shared among components whose equations are the same up to
// a shift of the variable indices: the idle pendulums of a scene, a crowd of
// identical balls.  Compiling a body's rate tape costs ~30k instructions, a
// third of a resting component's whole set-up; a component whose equations
// equal another's (each node the same operation, constant, extern and
// operand order, every variable index larger by one shift) evaluates that
// component's tape on the value array offset by the shift instead, with
// bit-identical results (the same instructions on the same values).
//
// Lookup: a hash of the outputs' top nodes picks the candidates (at most
// kCandidates per hash, so a scene of many different equations with equal
// hashes costs a bounded number of comparisons per component); a full
// comparison of the two DAGs, memoized per node, confirms the match.  The
// shift is read off an anchor, the first variable on the path of first
// operands from the first output that reaches one (a few nodes: for a
// body's rates, ẋ = dx is one; else the lowest variable read), so a hit
// walks a DAG only in the comparison.  The shift must not be negative: every variable the tape
// reads plus the shift is one the component reads, so the offset array stays inside the value
// array.
#pragma once

#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

#include "core/expr/expr.h"

namespace asgard::solver {

class TapeCache {
 public:
  struct Shared {
    std::shared_ptr<const expr::Tape> tape;
    int shift = 0;            // evaluate on values + shift
    bool reads_time = false;  // some output depends on t (Time or an extern)
  };
  // A tape computing `outputs`, compiled now or shared with an earlier call.
  Shared Get(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs);
  // Tapes compiled and tapes shared so far.
  long compiled() const { return compiled_; }
  long shared() const { return shared_; }

 private:
  struct Entry {
    std::vector<expr::NodeId> outputs;
    int anchor;  // Anchor(outputs)
    std::shared_ptr<const expr::Tape> tape;
    bool reads_time;
  };
  static constexpr size_t kCandidates = 4;
  // The index of the first variable met following first operands from each
  // output in turn; when no such path meets one, the lowest variable read
  // (a walk), or -1.  DAGs equal up to a shift have anchors that differ by
  // the shift.
  int Anchor(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs);
  // Whether one of `outputs` depends on t (Time or an extern).
  bool ReadsTime(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs);
  // Visits each node reachable from `outputs` once, until `visit` returns
  // true; whether it did.
  template <class Visit>
  bool Walk(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs, Visit visit);
  uint64_t Hash(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs, int anchor) const;
  bool Same(const expr::Pool& pool, const std::vector<expr::NodeId>& a,
            const std::vector<expr::NodeId>& b, int shift);

  std::unordered_map<uint64_t, std::vector<Entry>> entries_;
  // Scratch over pool nodes: per node of a compared DAG, its partner + 1
  // (Same), or 1 once visited (ReadsTime).
  std::vector<expr::NodeId> mark_;
  std::vector<expr::NodeId> touched_, stack_;
  std::vector<std::pair<expr::NodeId, expr::NodeId>> pairs_;
  long compiled_ = 0, shared_ = 0;
};

}  // namespace asgard::solver
