// Shared compiled tapes (design note in tape_cache.h).
#include "core/solver/tape_cache.h"

#include <algorithm>
#include <bit>

namespace asgard::solver {
namespace {

uint64_t Mix(uint64_t h, uint64_t v) {
  h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
  return h;
}

}  // namespace

int TapeCache::Anchor(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs) {
  for (expr::NodeId id : outputs)
    for (;;) {
      const expr::Node& n = pool.node(id);
      if (n.op == expr::Op::kVar) return n.index;
      if (n.args.empty()) break;
      id = n.args[0];
    }
  // No such path meets a variable: the lowest variable read, by a walk.
  int lowest = -1;
  Walk(pool, outputs, [&](const expr::Node& n) {
    if (n.op == expr::Op::kVar && (lowest < 0 || n.index < lowest)) lowest = n.index;
    return false;
  });
  return lowest;
}

template <class Visit>
bool TapeCache::Walk(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs,
                     Visit visit) {
  if (mark_.size() < pool.size()) mark_.resize(pool.size(), 0);
  bool stopped = false;
  stack_.assign(outputs.begin(), outputs.end());
  touched_.clear();
  while (!stack_.empty() && !stopped) {
    const expr::NodeId id = stack_.back();
    stack_.pop_back();
    if (mark_[id]) continue;
    mark_[id] = 1;
    touched_.push_back(id);
    const expr::Node& n = pool.node(id);
    stopped = visit(n);
    stack_.insert(stack_.end(), n.args.begin(), n.args.end());
  }
  for (expr::NodeId id : touched_) mark_[id] = 0;
  return stopped;
}

bool TapeCache::ReadsTime(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs) {
  return Walk(pool, outputs, [](const expr::Node& n) {
    return n.op == expr::Op::kTime || n.op == expr::Op::kExtern;
  });
}

uint64_t TapeCache::Hash(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs,
                         int anchor) const {
  uint64_t h = outputs.size();
  for (expr::NodeId id : outputs) {
    const expr::Node& n = pool.node(id);
    h = Mix(h, static_cast<uint64_t>(n.op));
    h = Mix(h, n.args.size());
    if (n.op == expr::Op::kConst) h = Mix(h, std::bit_cast<uint64_t>(n.value));
    if (n.op == expr::Op::kVar) h = Mix(h, static_cast<uint64_t>(n.index - anchor));
  }
  return h;
}

// Whether DAG `b` is DAG `a` with every variable index larger by `shift`.
// A pair of operands that is one constant node (the pool interns them:
// masses, gravity, ½) is equal without a visit; a third of a rigid body's
// pairs are.
bool TapeCache::Same(const expr::Pool& pool, const std::vector<expr::NodeId>& a,
                     const std::vector<expr::NodeId>& b, int shift) {
  if (a.size() != b.size()) return false;
  if (mark_.size() < pool.size()) mark_.resize(pool.size(), 0);
  pairs_.clear();
  touched_.clear();
  auto push = [&](expr::NodeId x, expr::NodeId y) {
    if (x != y || !pool.IsConst(x)) pairs_.push_back({x, y});
  };
  for (size_t i = 0; i < a.size(); ++i) push(a[i], b[i]);
  bool same = true;
  while (same && !pairs_.empty()) {
    const auto [x, y] = pairs_.back();
    pairs_.pop_back();
    if (mark_[x]) {  // x met before: it must meet the same partner
      same = mark_[x] == y + 1;
      continue;
    }
    const expr::Node& p = pool.node(x);
    const expr::Node& q = pool.node(y);
    const size_t arity = p.args.size();
    same = p.op == q.op && arity == q.args.size() && p.order == q.order &&
           std::bit_cast<uint64_t>(p.value) == std::bit_cast<uint64_t>(q.value) &&
           (p.op == expr::Op::kVar ? q.index == p.index + shift : q.index == p.index);
    if (!same) break;
    mark_[x] = y + 1;
    touched_.push_back(x);
    const expr::NodeId* pa = p.args.data();
    const expr::NodeId* qa = q.args.data();
    for (size_t k = 0; k < arity; ++k) push(pa[k], qa[k]);
  }
  for (expr::NodeId id : touched_) mark_[id] = 0;
  return same;
}

TapeCache::Shared TapeCache::Get(const expr::Pool& pool, const std::vector<expr::NodeId>& outputs) {
  const int anchor = Anchor(pool, outputs);
  auto& bucket = entries_[Hash(pool, outputs, anchor)];
  for (const Entry& e : bucket) {
    const int shift = anchor < 0 || e.anchor < 0 ? 0 : anchor - e.anchor;
    if ((anchor < 0) != (e.anchor < 0) || shift < 0) continue;
    if (!Same(pool, e.outputs, outputs, shift)) continue;
    ++shared_;
    return {e.tape, shift, e.reads_time};
  }
  auto tape = std::make_shared<const expr::Tape>(expr::Tape::Compile(pool, outputs));
  const bool reads_time = ReadsTime(pool, outputs);
  ++compiled_;
  if (bucket.size() < kCandidates) bucket.push_back({outputs, anchor, tape, reads_time});
  return {tape, 0, reads_time};
}

}  // namespace asgard::solver
