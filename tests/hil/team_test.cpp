// The multi-core step (kernel/include/ntn/team.hpp, hil_sim's WorkerTeam): the same states, bit
// for bit, as the single-core step for teams of 1, 2, 3 and 4 workers, in a model without hinges
// (the team also takes the residual and the update) and with hinges (the element pass only).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "ntn/hil/worker_team.hpp"
#include "ntn/kernel.hpp"
#include "support/alloc_counter.hpp"
#include "support/frames.hpp"
#include "support/init_model.hpp"

namespace team_test {

constexpr auto S = ntn_test::kFeatureSizes;

TEST(Team, SameBitsForAnyNumberOfWorkers) {
  static ntn_test::Sim<S> ref, par;
  static ntn::TeamWork<S> work;
  for (const double beta : {0.0, 1e-4}) {
    ASSERT_TRUE(ntn_test::feature_frame(ref.spec));
    ref.spec.settings.beta = beta;
    ref.spec.settings.dt = 0.5 * ntn::stable_time_step(ntn::view(ref.spec)).dt_stable;
    ASSERT_TRUE(ntn_test::init_model(ref.spec, ref.model).ok());
    ASSERT_TRUE(ntn_test::init_model(ref.spec, par.model).ok());
    for (int size = 1; size <= 4; ++size) {
      ntn::hil::WorkerTeam workers({size, -1});
      const ntn::Team team = workers.team();
      ASSERT_TRUE(ntn::prepare_team(par.model, size, work));
      ntn::initial_state(ref.model, ref.state), ntn::initial_state(par.model, par.state);
      std::array<double, S.inputs> in{};
      (void)ntn::start(ref.model, ref.state, ref.scratch, in);
      (void)ntn::start(par.model, par.state, par.scratch, in);
      for (long n = 0; n < 400; ++n) {
        for (std::size_t c = 0; c < S.inputs; ++c)
          in[c] = ntn_test::input_sample(static_cast<int>(c), n);
        (void)ntn::step(ref.model, ref.state, ref.scratch, in);
        (void)ntn::step(par.model, par.state, par.scratch, in, team, work);
        ASSERT_EQ(std::memcmp(ref.state.u.data(), par.state.u.data(), sizeof(ref.state.u)), 0)
            << size << " workers, step " << n << ", beta " << beta;
        ASSERT_EQ(std::memcmp(ref.state.v.data(), par.state.v.data(), sizeof(ref.state.v)), 0);
        ASSERT_EQ(std::memcmp(ref.scratch.outputs.data(), par.scratch.outputs.data(),
                              sizeof(ref.scratch.outputs)),
                  0);
      }
    }
  }
}

// The step's energy books over the DOFs (Model::books, books.hpp) in a model without hinges,
// where the DOF pass makes them: the same bits on the scalar path alone and on the SIMD path with
// teams of 1 to 4 workers (fixed sums by book group, whole groups per worker); the state's bits
// are those of a run without books; and each step's sums are the scheme's identity: K_{n+1/2} -
// K_{n-1/2} = Delta . (P - F - alpha M v), the kinetic energy 1/2 v^T M v. Tolerance 1e-12 of the
// work scale: the two sides differ by the rounding of sums over a few hundred DOFs. The portal
// of 9 divisions has 72 nodes: four whole book groups and a part one, a load slot among them.
constexpr auto kBooked = ntn_test::portal_frame_sizes(9, {.loads = 1, .inputs = 1});

TEST(Team, EnergyBooksSameBitsOnEveryPathAndTeam) {
  static ntn_test::Sim<kBooked> ref, par, plain;
  static ntn::TeamWork<kBooked> work;
  static_assert(kBooked.nodes % ntn::kBookNodes != 0);
  ASSERT_TRUE(ntn_test::portal_frame(ref.spec, 9));
  ref.spec.loads[0] = {37, ntn::kUy, 2e3, ntn::kConstant};
  ref.spec.inputs[0] = {ntn::InputKind::kGroundAcceleration, 0, 0, 9.80665, -5, 5};
  ref.spec.settings.gravity = {0, 0, -9.81};
  ref.spec.settings.alpha = 0.5;
  ref.spec.settings.dt = 0.9 * ntn::stable_time_step(ntn::view(ref.spec)).dt_stable;
  for (auto* sim : {&ref, &par, &plain})
    ASSERT_TRUE(ntn_test::init_model(ref.spec, sim->model).ok());
  ref.model.element_pass = ntn::ElementPass::kScalar;
  ref.model.books = par.model.books = true;
  for (int size = 1; size <= 4; ++size) {
    ntn::hil::WorkerTeam workers({size, -1});
    const ntn::Team team = workers.team();
    ASSERT_TRUE(ntn::prepare_team(par.model, size, work));
    for (int k = 0; k < size; ++k)
      EXPECT_EQ(work.node_split[static_cast<std::size_t>(k)] % static_cast<int>(ntn::kBookNodes),
                0);
    for (auto* sim : {&ref, &par, &plain})
      ntn::initial_state(sim->model, sim->state);
    std::array<double, kBooked.inputs> in{};
    for (auto* sim : {&ref, &par, &plain})
      (void)ntn::start(sim->model, sim->state, sim->scratch, in);
    double kinetic = 0, scale = 0;
    for (std::size_t j = 0; j < ref.model.dofs(); ++j)
      kinetic += 0.5 * ref.model.mass[j] * ref.state.v[j] * ref.state.v[j];
    for (long n = 0; n < 400; ++n) {
      in[0] = ntn_test::input_sample(0, n);
      (void)ntn::step(ref.model, ref.state, ref.scratch, in);
      (void)ntn::step(par.model, par.state, par.scratch, in, team, work);
      (void)ntn::step(plain.model, plain.state, plain.scratch, in);
      const ntn::StepBooks& b = ref.scratch.books;
      ASSERT_EQ(std::memcmp(&b, &par.scratch.books, sizeof b), 0) << size << " workers, step " << n;
      ASSERT_EQ(std::memcmp(ref.state.u.data(), plain.state.u.data(), sizeof(ref.state.u)), 0);
      ASSERT_EQ(std::memcmp(ref.state.v.data(), plain.state.v.data(), sizeof(ref.state.v)), 0);
      double k1 = 0;
      for (std::size_t j = 0; j < ref.model.dofs(); ++j)
        k1 += 0.5 * ref.model.mass[j] * ref.state.v[j] * ref.state.v[j];
      scale = std::max({scale, std::abs(b.external), std::abs(b.internal), k1});
      EXPECT_NEAR(b.kinetic, k1, 1e-12 * scale) << "step " << n;
      EXPECT_NEAR(k1 - kinetic, b.external - b.internal - b.damping, 1e-12 * scale) << "step " << n;
      kinetic = k1;
    }
    EXPECT_GT(scale, 0.0);
  }
}

// The workers' threads are made before the run (their only allocations); preparing the team's
// partition and every step with the team, in both team shapes (with the residual and update in
// the team, and the element pass alone), allocate nothing.
TEST(Team, NoAllocationInPrepareOrStep) {
  static ntn_test::Sim<S> sim;
  static ntn::TeamWork<S> work;
  ASSERT_TRUE(ntn_test::feature_frame(sim.spec));
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  ntn::hil::WorkerTeam workers({3, -1});
  const ntn::Team team = workers.team();
  const ntn_test::AllocationScope scope;
  ASSERT_TRUE(ntn::prepare_team(sim.model, 3, work));
  ntn::initial_state(sim.model, sim.state);
  std::array<double, S.inputs> in{};
  (void)ntn::start(sim.model, sim.state, sim.scratch, in);
  for (long n = 0; n < 2000; ++n) {
    for (std::size_t c = 0; c < S.inputs; ++c)
      in[c] = ntn_test::input_sample(static_cast<int>(c), n);
    ASSERT_EQ(ntn::step(sim.model, sim.state, sim.scratch, in, team, work), ntn::StepStatus::kOk);
  }
  EXPECT_EQ(scope.counts().allocations, 0U);
  EXPECT_EQ(scope.counts().deallocations, 0U);
}

TEST(Team, PartitionCoversEveryBlockAndNodeOnce) {
  static ntn_test::Sim<S> sim;
  static ntn::TeamWork<S> work;
  ASSERT_TRUE(ntn_test::feature_frame(sim.spec));
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok());
  EXPECT_FALSE(ntn::prepare_team(sim.model, 0, work));
  EXPECT_FALSE(ntn::prepare_team(sim.model, ntn::kMaxTeam + 1, work));
  ASSERT_TRUE(ntn::prepare_team(sim.model, 3, work));
  EXPECT_EQ(work.block_split[0], 0);
  EXPECT_EQ(work.block_split[3], static_cast<int>(ntn::TeamWork<S>::kBlocks));
  EXPECT_EQ(work.node_split[3], static_cast<int>(S.nodes));
  EXPECT_EQ(work.node_start[S.nodes], static_cast<int>(2 * S.elements));
  for (std::size_t n = 0; n < S.nodes; ++n) {  // each list in element order
    for (auto k = work.node_start[n] + 1; k < work.node_start[n + 1]; ++k)
      EXPECT_LT(work.incidence[static_cast<std::size_t>(k - 1)],
                work.incidence[static_cast<std::size_t>(k)]);
  }
  // A node is shared, or every end at it is added directly by one worker: the worker whose
  // blocks hold all of the node's elements.
  for (int size = 1; size <= 4; ++size) {
    ASSERT_TRUE(ntn::prepare_team(sim.model, size, work));
    const auto shared_end =
        static_cast<std::size_t>(work.shared_split[static_cast<std::size_t>(size)]);
    std::vector<bool> shared(S.nodes, false);
    for (std::size_t i = 0; i < shared_end; ++i)
      shared[static_cast<std::size_t>(work.shared[i])] = true;
    std::vector<int> owner(S.nodes, -1);
    for (std::size_t e = 0; e < S.elements; ++e) {
      const std::size_t b = e / ntn::kBeamLanes, l = e % ntn::kBeamLanes;
      int k = 0;
      while (work.block_split[static_cast<std::size_t>(k) + 1] <= static_cast<int>(b))
        ++k;
      const int nodes[2] = {sim.model.beams[b].dof_i[l] / 6, sim.model.beams[b].dof_j[l] / 6};
      for (std::size_t end = 0; end < 2; ++end) {
        const auto n = static_cast<std::size_t>(nodes[end]);
        EXPECT_NE(ntn::direct_end(work.direct[b], l, end), shared[n]) << "node " << n;
        if (shared[n]) continue;
        if (owner[n] < 0) owner[n] = k;
        EXPECT_EQ(owner[n], k) << "node " << n << " is interior to two workers";
      }
    }
    // Phase A does not zero F_n: each node that is not shared has exactly one first end
    // (BeamBlock::first), added directly by its owner, which writes F_n there; a shared node's
    // ends are all stored (phase B writes it).
    std::vector<int> firsts(S.nodes, 0);
    for (std::size_t e = 0; e < S.elements; ++e) {
      const std::size_t b = e / ntn::kBeamLanes, l = e % ntn::kBeamLanes;
      const int nodes[2] = {sim.model.beams[b].dof_i[l] / 6, sim.model.beams[b].dof_j[l] / 6};
      for (std::size_t end = 0; end < 2; ++end) {
        if (!ntn::direct_end(sim.model.beams[b].first, l, end)) continue;
        const auto n = static_cast<std::size_t>(nodes[end]);
        ++firsts[n];
        EXPECT_EQ(ntn::direct_end(work.direct[b], l, end), !shared[n]) << "node " << n;
      }
    }
    for (std::size_t n = 0; n < S.nodes; ++n)
      EXPECT_EQ(firsts[n], work.node_start[n + 1] > work.node_start[n] ? 1 : 0) << "node " << n;
    if (size == 1) {
      EXPECT_EQ(shared_end, 0U) << "every node has elements: all interior";
    } else {
      EXPECT_GT(shared_end, 0U) << "ranges that meet share nodes";
    }
  }
}

}  // namespace team_test
