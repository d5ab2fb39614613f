// Partitioning the state equations into strongly connected components
// (seed 5.2.1).
//
//   reference graph: one node per state variable; an arc j → i when the
//   equation of i reads variable j (data flows from j to i).
//
//        dx₁ ──▶ x₁ ──┐            Tarjan's algorithm finds the cycles:
//         ▲           │            {x₁, dx₁, x₂, dx₂} form one component when
//         └─── F(x₁−x₂)◀┘           a mutual force couples them; a free axis
//                                  gives {x} and {dx}, each on its own.
//
// Components come out in dependency order: every component appears after
// all the components it reads from, so that order is a valid schedule.
// The search is iterative (no recursion), so 10⁵ variables cannot overflow
// the stack.
#pragma once

#include <span>
#include <utility>
#include <vector>

namespace asgard::solver {

// The reference graph in flat arrays: the variables that the equation of
// variable i reads are vars[start[i]] … vars[start[i + 1] − 1], sorted.  One
// allocation for the whole graph rather than one per variable (a scene of
// many idle bodies builds it for every one of their variables).
struct ReadGraph {
  ReadGraph() = default;      // not an aggregate: a braced list means lists per variable
  std::vector<int> start{0};  // size: variables + 1
  std::vector<int> vars;
  // Ranges of variables (first, count) that form a body's island: they read
  // only each other and no variable outside reads them.  Their arcs are left
  // out (of() is empty for them) and, with body fusion, each range becomes
  // one component — the one the fusion would make of it — without a search.
  std::vector<std::pair<int, int>> islands;
  int size() const { return static_cast<int>(start.size()) - 1; }
  std::span<const int> of(int i) const {
    return {vars.data() + start[i], static_cast<size_t>(start[i + 1] - start[i])};
  }
  // From one list per variable.
  static ReadGraph From(const std::vector<std::vector<int>>& reads);
};

struct Partition {
  std::vector<std::vector<int>> components;  // variables of each component, sorted
  std::vector<int> component_of;             // variable → component
  std::vector<std::vector<int>> upstream;    // components each one reads from (sorted)
  std::vector<std::vector<int>> downstream;  // components reading each one (sorted)
};

// `reads[i]` lists the variables that the equation of variable i reads.
// With `single` every variable goes into one component (the seed's
// unpartitioned variant).  With `fuse_chains` a component joins the
// components it reads where it alone reads each of them: {dx} ─▶ {x} becomes
// {x, dx}, and a body's spins ─▶ its quaternion one component.  Such groups
// share their time scale (x moves as fast as dx changes), so apart they take
// about the same steps several times, and the reader pays an interpolation
// of the others' waveforms at every stage; together they take one set of
// steps.
//
// With `body_of` (per variable: its body, or -1 to keep it apart; empty: no
// body fusion) a body's components that form an island — each holds only
// that body's variables, and none reads or is read by a component outside
// them — become one component: a free ball's three axes and its rotation
// take one step together (one ballistic step when it flies under constant
// forces with its spin at rest) rather than one each.  Nothing else reads
// them, so no other component's steps change.
Partition PartitionEquations(const ReadGraph& reads, bool single = false, bool fuse_chains = false,
                             const std::vector<int>& body_of = {});
Partition PartitionEquations(const std::vector<std::vector<int>>& reads, bool single = false,
                             bool fuse_chains = false, const std::vector<int>& body_of = {});

}  // namespace asgard::solver
