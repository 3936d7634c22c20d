// The kernel integrates the library's modes: free vibration of ntn_exact started from a mode
// shape of ntn::modal stays in that mode and oscillates at its frequency. This ties the modal
// analysis (an exact elimination u = T q built independently of the kernel's forest) to what
// step() actually integrates, for every joint kind of modal_models.hpp.
//
// Measurement (as tests/validation/hinge_release_test.cpp): the modal coordinate phi^T M u(t) over
// ~30 periods; its zero crossings give the frequency, compared with central difference's
// discrete one, omega_h = (2 / dt) asin(omega dt / 2) (STYLE). A single mode advanced by central
// difference has exactly that phase, and the crossings resolve it to ~1e-7 (measured: at most
// 1.2e-7 below), so the tolerance is
// 1e-6 (hinge_release_test's tight bound); and the state must stay a multiple of the shape:
// max |u - q phi| below 1e-9 of the initial amplitude (1 mm). A wrong tie or effective mass in
// either code leaks energy into other modes and shifts the frequency by 1e-3 or more.
//
// The eccentric chain is checked both ways round. With the beam ends as the hinges' node 2 and
// the plate (node 1) as the root, the kernel's forest first tied T (u2 - phi2 x e) to T u1, where
// DESIGN §7's d_L = T [u2 - u1 - phi1 x e; ...] ties T (u2 - phi1 x e): the two differ when the
// hinge is eccentric and a rotation is released (phi2 != phi1). This test found it; the forest
// now puts the lever arm on node 1's side whichever node is the child.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "modal_models.hpp"
#include "ntn/kernel.hpp"
#include "ntn/modal/modal.hpp"
#include "support/init_model.hpp"
#include "support/zero_crossings.hpp"

namespace modal_kernel_test {

using ntn_test::Sim;

struct Measured {
  double frequency_error = 1;  // measured omega / omega_h - 1
  double leak = 1;             // max |u - q phi| / initial amplitude at the end
};

constexpr int kModes = 4;

// Free vibration of mode i of the library's analysis of sim.spec, integrated by the kernel.
template <ntn::Sizes S>
Measured measure(Sim<S>& sim, const ntn::modal::ModalResult& r, int i) {
  Measured out;
  const Eigen::VectorXd m = ntn_test::lumped_mass(ntn::view(sim.spec));
  const Eigen::VectorXd phi = r.shapes.col(i);
  const double amplitude = 1e-3;  // m, at the largest shape entry
  sim.state = {};
  const double top = phi.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 0; j < phi.size(); ++j)
    sim.state.u[static_cast<std::size_t>(j)] = amplitude / top * phi(j);
  auto coordinate = [&]() {
    double q = 0;
    for (Eigen::Index j = 0; j < phi.size(); ++j)
      q += phi(j) * m(j) * sim.state.u[static_cast<std::size_t>(j)];
    return q;
  };
  const double dt = sim.model.dt;
  const double omega_h = 2.0 / dt * std::asin(r.omega(i) * dt / 2.0);
  const auto steps = static_cast<long>(30.25 * 2 * 3.14159265358979323846 / omega_h / dt);
  ntn_test::ZeroCrossings zc(coordinate());
  EXPECT_EQ(ntn::start(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
  for (long n = 0; n < steps; ++n) {
    EXPECT_EQ(ntn::step(sim.model, sim.state, sim.scratch, {}), ntn::StepStatus::kOk);
    zc.add(coordinate(), static_cast<double>(sim.state.tick) * dt, dt);
  }
  EXPECT_GE(zc.count(), 50);
  out.frequency_error = zc.omega() / omega_h - 1.0;
  const double q = coordinate();
  double leak = 0;
  for (Eigen::Index j = 0; j < phi.size(); ++j)
    leak = std::max(leak, std::abs(sim.state.u[static_cast<std::size_t>(j)] - q * phi(j)));
  out.leak = leak / amplitude;
  return out;
}

// Runs the first kModes modes; asserts them unless `assert_agreement` is false (then prints).
template <ntn::Sizes S>
void check(const char* name, Sim<S>& sim, bool assert_agreement = true) {
  ntn::modal::ModalOptions o;
  o.modes = kModes;
  const ntn::modal::ModalResult r = ntn::modal::modal_analysis(ntn::view(sim.spec), o);
  ASSERT_TRUE(r.ok()) << r.error;
  sim.spec.settings.dt = 0.9 * ntn_test::hinged_stable_step(sim.spec).dt_stable;
  ASSERT_TRUE(ntn_test::init_model(sim.spec, sim.model).ok()) << name;
  for (int i = 0; i < kModes; ++i) {
    const Measured m = measure(sim, r, i);
    std::printf(
        "  %s, mode %d (%.4f Hz): kernel / omega_h - 1 = %+.2e, |u - q phi| / amplitude "
        "%.2e%s\n",
        name, i + 1, r.frequency(i), m.frequency_error, m.leak,
        assert_agreement ? "" : "  (reported, see the file comment)");
    if (!assert_agreement) continue;
    EXPECT_LT(std::abs(m.frequency_error), 1e-6) << name << " mode " << i + 1;
    EXPECT_LT(m.leak, 1e-9) << name << " mode " << i + 1;
  }
}

Sim<modal_test::kStar> star;
Sim<modal_test::kChain> chain;
Sim<modal_test::kSupported> supported;
Sim<modal_test::kEccentricChain> eccentric;

TEST(ModalKernel, KernelIntegratesTheLibrarysModes) {
  modal_test::build_star(star.spec);
  check("star joint", star);
  modal_test::build_chain(chain.spec);
  check("chain", chain);
  modal_test::build_supported(supported.spec);
  check("supports through hinges", supported);
}

TEST(ModalKernel, EccentricHingesWithReleasedRotations) {
  // Written with the beam ends as node 1 (the kernel eliminates them as node 1): agrees.
  modal_test::build_eccentric_chain(eccentric.spec);
  for (ntn::HingeSpec& h : eccentric.spec.hinges) {
    std::swap(h.node1, h.node2);
    for (double& e : h.eccentricity)
      e = -e;
  }
  check("eccentric chain, beam ends as node 1", eccentric);
  // Every direction rigid: agrees (phi1 = phi2 then).
  modal_test::build_eccentric_chain(eccentric.spec);
  for (ntn::HingeSpec& h : eccentric.spec.hinges)
    h.behaviour.fill(ntn::HingeBehaviour::kRigid);
  check("eccentric chain, all rigid", eccentric);
  // Beam ends as node 2 with released rotations (the case the file comment describes).
  modal_test::build_eccentric_chain(eccentric.spec);
  check("eccentric chain, beam ends as node 2", eccentric);
}

}  // namespace modal_kernel_test
