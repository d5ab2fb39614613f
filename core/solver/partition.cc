// Tarjan's strongly connected components, iterative (design note in
// partition.h).
#include "core/solver/partition.h"

#include <algorithm>
#include <numeric>

namespace asgard::solver {
namespace {

// Emits components in an order where each component follows every component
// reachable from it along `reads` arcs, i.e. its dependencies.
// An island's range (ReadGraph::islands) comes out whole, where the search
// would have reached its first variable: no arc enters it, so every one of
// its components would have come out then, one after another.
std::vector<std::vector<int>> Tarjan(const ReadGraph& reads) {
  const int n = reads.size();
  std::vector<int> index(n, -1), low(n, 0);
  std::vector<int> island(n, 0);  // at an island's first variable: its size
  for (const auto& [first, count] : reads.islands) {
    island[first] = count;
    for (int v = first; v < first + count; ++v) index[v] = 0;  // never searched
  }
  std::vector<char> on_stack(n, 0);
  std::vector<int> stack;
  std::vector<std::vector<int>> out;
  struct Frame {
    int v;
    size_t next;
  };
  std::vector<Frame> calls;
  int counter = 0;
  for (int root = 0; root < n; ++root) {
    if (island[root] > 0) {
      out.emplace_back(island[root]);
      std::iota(out.back().begin(), out.back().end(), root);
      continue;
    }
    if (index[root] >= 0) continue;
    calls.push_back({root, 0});
    index[root] = low[root] = counter++;
    stack.push_back(root);
    on_stack[root] = 1;
    while (!calls.empty()) {
      Frame& f = calls.back();
      if (const auto arcs = reads.of(f.v); f.next < arcs.size()) {
        const int w = arcs[f.next++];
        if (index[w] < 0) {
          index[w] = low[w] = counter++;
          stack.push_back(w);
          on_stack[w] = 1;
          calls.push_back({w, 0});
        } else if (on_stack[w]) {
          low[f.v] = std::min(low[f.v], index[w]);
        }
        continue;
      }
      const int v = f.v;
      calls.pop_back();
      if (!calls.empty()) low[calls.back().v] = std::min(low[calls.back().v], low[v]);
      if (low[v] == index[v]) {
        std::vector<int> comp;
        int w;
        do {
          w = stack.back();
          stack.pop_back();
          on_stack[w] = 0;
          comp.push_back(w);
        } while (w != v);
        std::sort(comp.begin(), comp.end());
        out.push_back(std::move(comp));
      }
    }
  }
  return out;
}

// Upstream and downstream lists of each component, from the variables' reads.
void LinkComponents(const ReadGraph& reads, Partition& p) {
  const int n = reads.size();
  p.component_of.assign(n, -1);
  for (size_t c = 0; c < p.components.size(); ++c)
    for (int v : p.components[c]) p.component_of[v] = static_cast<int>(c);
  p.upstream.assign(p.components.size(), {});
  p.downstream.assign(p.components.size(), {});
  for (int i = 0; i < n; ++i) {
    const int ci = p.component_of[i];
    for (int j : reads.of(i)) {
      const int cj = p.component_of[j];
      if (cj != ci) p.upstream[ci].push_back(cj);
    }
  }
  for (size_t c = 0; c < p.components.size(); ++c) {
    auto& up = p.upstream[c];
    std::sort(up.begin(), up.end());
    up.erase(std::unique(up.begin(), up.end()), up.end());
    for (int u : up) p.downstream[u].push_back(static_cast<int>(c));
  }
}

// Replaces the components by their groups: `head[c]` is the member whose
// place in the order c's group takes (head[head[c]] == head[c]).
void Contract(const ReadGraph& reads, const std::vector<int>& head, Partition& p) {
  const int nc = static_cast<int>(p.components.size());
  std::vector<std::vector<int>> fused;
  std::vector<int> slot(nc, -1);  // head → index in `fused`
  for (int c = 0; c < nc; ++c) {
    if (head[c] != c) continue;  // placed with the group's head
    slot[c] = static_cast<int>(fused.size());
    fused.emplace_back();
  }
  if (static_cast<int>(fused.size()) == nc) return;
  std::vector<int> members(nc, 0);  // per head
  for (int c = 0; c < nc; ++c) ++members[head[c]];
  for (int c = 0; c < nc; ++c) {
    auto& group = fused[slot[head[c]]];
    if (members[head[c]] == 1)  // a group of one keeps its sorted list
      group = std::move(p.components[c]);
    else
      group.insert(group.end(), p.components[c].begin(), p.components[c].end());
  }
  for (int c = 0; c < nc; ++c)
    if (head[c] == c && members[c] > 1) std::sort(fused[slot[c]].begin(), fused[slot[c]].end());
  p.components = std::move(fused);
  LinkComponents(reads, p);
}

// Fuses each component with the components it reads when it alone reads
// each of them ({dx} ─▶ {x}; a ball's three spins ─▶ its quaternion;
// transitively, so a chain becomes one component).  Inductively only a
// group's last member has arcs leaving the group, so contracting these arcs
// keeps the graph acyclic, and the group takes the place of its last member,
// after everything any member reads.
void FuseChains(const ReadGraph& reads, Partition& p) {
  const int nc = static_cast<int>(p.components.size());
  std::vector<int> parent(nc);  // union–find over components
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  };
  // Every union makes the reader, which comes after all it reads, the root:
  // a group's root is its last member.
  for (int c = 0; c < nc; ++c) {
    const auto& up = p.upstream[c];
    bool alone = !up.empty();
    for (int u : up) alone = alone && p.downstream[u].size() == 1;
    if (alone)
      for (int u : up) parent[find(u)] = c;
  }
  std::vector<int> head(nc);  // per component: its group's root (last member)
  for (int c = 0; c < nc; ++c) head[c] = find(c);
  Contract(reads, head, p);
}

// Fuses the components of each body (`body_of[v]`: v's body, or -1 for a
// variable that must stay apart) that form an island: every component holds
// only that body's variables, and none is read by or reads a component
// outside them.  With no arc leaving or entering the group, its place in the
// order does not matter; it takes its last member's.
void FuseBodies(const ReadGraph& reads, const std::vector<int>& body_of, Partition& p) {
  const int nc = static_cast<int>(p.components.size());
  std::vector<int> body(nc, -1);  // per component: its one body, or -1
  for (int c = 0; c < nc; ++c) {
    body[c] = body_of[p.components[c].front()];
    for (int v : p.components[c])
      if (body_of[v] != body[c]) body[c] = -1;
  }
  // A body is fused when no component of it is mixed or coupled outside it.
  const size_t nb = static_cast<size_t>(*std::max_element(body_of.begin(), body_of.end()) + 1);
  std::vector<char> apart(nb, 0);  // per body
  for (int c = 0; c < nc; ++c) {
    bool island = body[c] >= 0;
    for (const auto* arcs : {&p.upstream[c], &p.downstream[c]})
      for (int u : *arcs) island = island && body[u] == body[c];
    if (island) continue;
    for (int v : p.components[c])
      if (body_of[v] >= 0) apart[body_of[v]] = 1;
  }
  std::vector<int> last(nb, -1);  // per body: its last component
  for (int c = 0; c < nc; ++c)
    if (body[c] >= 0 && !apart[body[c]]) last[body[c]] = c;
  std::vector<int> head(nc);
  for (int c = 0; c < nc; ++c) head[c] = body[c] >= 0 && !apart[body[c]] ? last[body[c]] : c;
  Contract(reads, head, p);
}

}  // namespace

ReadGraph ReadGraph::From(const std::vector<std::vector<int>>& reads) {
  ReadGraph g;
  g.start.reserve(reads.size() + 1);
  for (const auto& r : reads) {
    g.vars.insert(g.vars.end(), r.begin(), r.end());
    g.start.push_back(static_cast<int>(g.vars.size()));
  }
  return g;
}

Partition PartitionEquations(const std::vector<std::vector<int>>& reads, bool single,
                             bool fuse_chains, const std::vector<int>& body_of) {
  return PartitionEquations(ReadGraph::From(reads), single, fuse_chains, body_of);
}

Partition PartitionEquations(const ReadGraph& reads, bool single, bool fuse_chains,
                             const std::vector<int>& body_of) {
  const int n = reads.size();
  Partition p;
  if (single) {
    if (n > 0) {
      p.components.emplace_back(n);
      std::iota(p.components[0].begin(), p.components[0].end(), 0);
    }
  } else {
    p.components = Tarjan(reads);
  }
  LinkComponents(reads, p);
  if (fuse_chains && !single) FuseChains(reads, p);
  if (!body_of.empty() && !single && !p.components.empty()) FuseBodies(reads, body_of, p);
  return p;
}

}  // namespace asgard::solver
