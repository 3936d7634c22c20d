// ntn_exact (default, DESIGN §7.1): the rigid hinge directions join nodes into trees, and the
// constraint forest (constraint_forest.hpp) gives their accelerations exactly: built at init,
// an upward and a downward pass every step, a projection after the update.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>

#include "ntn/clamp.hpp"
#include "ntn/constraint_forest.hpp"
#include "ntn/hinge.hpp"
#include "ntn/model_spec.hpp"
#include "ntn/residual.hpp"
#include "ntn/slip.hpp"
#include "ntn/state.hpp"
#include "ntn/status.hpp"

namespace ntn {

template <Sizes S>
struct Model;  // model.hpp
template <Sizes S>
struct InitWorkspace;  // model.hpp

namespace detail {

// The coupled R_n of one rigid tree in w.r, as the step's upward pass makes it (the same
// expressions in the same order, so the same bits): the step itself keeps only accelerations.
template <Sizes S>
void tree_coupled_residual(const Model<S>& m, const State<S>& s, Scratch<S>& w, int tree) {
  for_each_node(m, ClampPart{tree, -1},
                [&](int n) { node_residual(m, s, w, n, node_block(w.r, n)); });
  const ForestTree& t = m.trees[static_cast<std::size_t>(tree)];
  const auto first = static_cast<std::size_t>(t.first_edge);
  forest_up(std::span(m.edges).subspan(first), std::span(m.edge_matrices).subspan(first),
            t.end_edge - t.first_edge, w.r.data());
}

}  // namespace detail

// The method's functions, called only through hinge_methods.hpp.
struct NtnExactMethod {
  // Rigid direction k of a hinge: an edge of the constraint forest.
  static bool rigid_direction(const Settings&, std::size_t k, HingeData& h) {
    h.rigid |= static_cast<std::uint8_t>(1U << k);
    return true;
  }

  // Rigid-plastic direction k: free in the forest, held (stick) or slid (slip) by the slip stage
  // after the update, exactly (slip.hpp); its hardening with the slip, if any, a spring of that
  // stiffness in parallel (the slider and the spring: linear kinematic hardening).
  static bool slip_direction(const Settings&, std::size_t k, HingeData& h) {
    h.slip |= static_cast<std::uint8_t>(1U << k);
    if (h.stiffness[k] > 0) h.springs |= static_cast<std::uint8_t>(1U << k);
    return true;
  }

  // The forest of the step mass (InitWorkspace::divided_mass; build_forest: trees, edges parents
  // first, each edge's matrices, the roots' inverse masses, the mechanism DOFs held), hinge ->
  // edge, the trees, and which edges the step re-projects (select_projected_edges).
  template <Sizes S>
  static InitStatus init(const ModelSpec<S>& spec, Model<S>& model, InitWorkspace<S>& work) {
    const ForestBuild fb =
        build_forest(model.hinges, spec.nodes, work.divided_mass, model.node_tree, model.edges,
                     model.edge_matrices, model.roots, work.forest, model.held);
    if (!fb.status.ok()) return fb.status;
    model.num_edges = fb.edges, model.num_roots = fb.roots, model.held_dofs = fb.held_dofs;
    for (int k = 0; k < fb.edges; ++k) {
      const int h = model.edges[static_cast<std::size_t>(k)].hinge;
      model.hinge_edge[static_cast<std::size_t>(h)] = k;
    }
    const bool any_branch = std::any_of(model.hinges.begin(), model.hinges.end(),
                                        [](const HingeData& h) { return h.branches != 0; });
    const auto edges =
        std::span<const ForestEdge>(model.edges.data(), static_cast<std::size_t>(fb.edges));
    model.num_trees = forest_trees(edges, model.node_tree, model.trees);
    init_tree_stops(model);
    sort_slip_hinges(model);
    init_slip_mobility(model, work);
    model.num_project_edges = select_projected_edges(
        edges,
        std::span<const ForestTree>(model.trees.data(), static_cast<std::size_t>(model.num_trees)),
        model.clamp == ClampRule::kPaper && any_branch, model.project_edges);
    return {};
  }

  // R_n - C v (S 2-3) into coupling_input(): R itself (scale 1, Model::residual_scale) at tree
  // DOFs, a_n = R/m elsewhere: one store per DOF, the forest finishes the trees in place.
  template <Sizes S>
  static void residual(const Model<S>& m, const State<S>& s, Scratch<S>& w) {
    detail::residual(m, s, w, m.residual_scale.data(), w.coupling_input().data());
  }
  // Upward pass (each child hands its parent its force), roots, downward pass (each child's
  // acceleration from its parent's): a_n at tree DOFs (DESIGN §7.1).
  template <Sizes S>
  static void couple(const Model<S>& m, const State<S>&, Scratch<S>& w) {
    double* r = w.coupling_input().data();
    forest_up(m.edges, m.edge_matrices, m.num_edges, r);
    forest_down(m.roots, m.num_roots, m.edges, m.edge_matrices, m.num_edges, r, w.a.data());
  }

  // The slip directions (slip.hpp), then the stops' clamp.
  template <Sizes S>
  static void stops(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    slip_stage(m, s, w);
    clamp_stops(m, s, w);
  }
  // start(): the slip directions' forces, then the stops' (the momentum clamp's).
  template <Sizes S>
  static void start_forces(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    slip_forces(m, s, w);
    clamp_start_forces(m, s, w);
  }
  // Each child's rigid components from its parent's, in the trees that round (rotated or
  // eccentric hinges; every tree under the S 33 clamp); v, a follow (S 35-37).
  template <Sizes S>
  static void project(const Model<S>& m, State<S>& s, Scratch<S>& w) {
    forest_project(m.edges, m.edge_matrices, m.project_edges, m.num_project_edges, s.u.data(),
                   s.v.data(), w.a.data(), m.inv_dt, w.clamp.moved.data(), ++w.clamp.events);
  }
  // u_0, v_0 onto the constraints, every edge (so the step need only re-project what rounds).
  template <Sizes S>
  static void project_initial(const Model<S>& m, State<S>& s) {
    forest_project_initial(m.edges, m.edge_matrices, m.num_edges, s.u.data(), s.v.data());
  }

  // lambda of rigid direction k (on node 1, hinge frame) from its tree's coupled R, which
  // `coupled_tree` remembers (-1: none yet) so that several channels of one tree compute it once.
  template <Sizes S>
  static double constraint_force(const Model<S>& m, const State<S>& s, Scratch<S>& w, int hinge,
                                 int k, int& coupled_tree) {
    const auto edge = static_cast<std::size_t>(m.hinge_edge[static_cast<std::size_t>(hinge)]);
    const ForestEdge& e = m.edges[edge];
    const int tree = m.node_tree[static_cast<std::size_t>(e.child)];
    if (tree != coupled_tree) detail::tree_coupled_residual(m, s, w, tree);
    coupled_tree = tree;
    double lambda[6];
    forest_hinge_force(e, m.edge_matrices[edge], w.a.data(), w.r.data(), lambda);
    return lambda[k];
  }
};

}  // namespace ntn
