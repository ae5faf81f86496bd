#pragma once
// A large contact problem solved group by group (docs/solvers.md "Large islands by their active
// groups"). An island is every body linked by a contact, and a contact links two bodies even when
// it is separating or a speculative gap that r = 0 already satisfies: when box_pile_1000 lands,
// its 100 columns of ten boxes touch their neighbours' margins for a few steps and form one island
// of up to 4 254 contacts (12 762 unknowns), past Newton's size (ChooserSettings::
// newtonMaxUnknowns), which Gauss-Seidel left at residuals of 4e-4..1.3e-3. Without the contacts
// that do not act at the start, the same island is 110 groups of at most 32 contacts.
//
// The groups: the contacts that act (at first those approaching or resting, q_N <= 0, or pushed
// in the warm start, r_N > 0), linked when W couples them (they share a body). Each group is
// solved alone with its own automatic plan; the contacts left out keep r = 0, which satisfies a
// contact's law exactly when u_N >= 0 there. Where the groups' impulses drive a left-out contact
// into approach (a box falling on a column that its group stops), that contact acts too: the
// groups are formed again and solved from their last answers (a group that did not change is
// solved by its warm start, no iteration), until no left-out contact approaches. The whole
// problem's residual is then the groups', checked. When the contacts that act no longer split
// (one group), the caller solves the whole problem as before.
#include <coulomb/solvers/ContactProblem.hpp>
#include <coulomb/solvers/SolveWithFallback.hpp>
#include <coulomb/solvers/SolverChooser.hpp>
#include <coulomb/solvers/UnionFind.hpp>

#include <optional>
#include <vector>

namespace coulomb::solvers {

struct ActiveGroups {
  std::vector<int> groupOfBlock;  // per block: its group, or -1 (a contact that does not act)
  std::vector<int> indexInGroup;  // per block: its position in its group (-1: none)
  // The blocks of group g, ascending: members[memberStart[g] .. memberStart[g + 1]).
  std::vector<int> memberStart, members;
  int count = 0;    // groups
  int largest = 0;  // blocks of the largest group
};

// Whether the contacts acting at the start form two groups or more (the test before
// solveByActiveGroups, on every large island's step): from the bodies they share, with no copy of
// W; `scratch` keeps its storage between calls. False for a problem with other rows.
bool splitsByActingContacts(const ContactProblem& problem, UnionFind& scratch);

// The groups of the blocks marked in `acts` (one flag per block), linked through W's blocks.
ActiveGroups activeGroups(const BlockSparseMatrix& W, const std::vector<char>& acts);

// The group's own problem of contacts: its blocks of W (a block-sparse copy), q, mu, and as warm
// start the group's part of `warmStart` (problem size; null: none).
ContactProblem groupProblem(const ContactProblem& problem, const BlockSparseMatrix& W,
                            const ActiveGroups& groups, int group,
                            const Eigen::VectorXd* warmStart);

// Solves a problem of isotropic contacts by its active groups, each with `chooser`'s plan for
// `choice`: the outcome (solver "groups"; its attempts: the whole answer, then every group's in
// order) when the whole residual meets options.tolerance; nullopt when the problem has other rows,
// the acting contacts do not split (one group) or the whole residual misses the tolerance
// (`failedCheck`, when given, is set then). `instances`, when given, are the solvers the groups
// run (created once, kept by the caller: a World island's); else they are made for this call.
std::optional<PlanOutcome> solveByActiveGroups(
    const ContactProblem& problem, const SolverChooser& chooser, const SolverChoice& choice,
    const SolverOptions& options, const SolverRegistry& registry, bool* failedCheck = nullptr,
    SolverInstances* instances = nullptr);

}  // namespace coulomb::solvers
