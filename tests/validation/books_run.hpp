// The energy books of a run from a model's initial state for `seconds`, for the validation tests
// that close them on a model from its text (text_model.hpp): the accounts printed, and their
// residual relative to the input returned.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <span>
#include <vector>

#include "ntn/hil/energy.hpp"
#include "ntn/hil/loaded_model.hpp"
#include "ntn/kernel.hpp"

namespace ntn_test {

inline double books_residual(ntn::hil::LoadedModel& rt, double seconds) {
  ntn::Model<ntn::kRunTime>& m = rt.model();
  ntn::State<ntn::kRunTime>& s = rt.state();
  ntn::Scratch<ntn::kRunTime>& w = rt.scratch();
  ntn::initial_state(m, s);
  const std::vector<double> none;
  EXPECT_EQ(ntn::start(m, s, w, std::span<const double>(none)), ntn::StepStatus::kOk);
  ntn::hil::EnergyBalance<ntn::kRunTime> books;  // begin() turns the kernel's books on
  books.reserve(m.dofs());
  books.begin(m, s);
  const long steps = std::lround(seconds / m.dt);
  for (long n = 0; n < steps; ++n) {
    EXPECT_EQ(ntn::step(m, s, w, std::span<const double>(none)), ntn::StepStatus::kOk);
    books.after_step(m, s, w);
  }
  const ntn::hil::EnergyAccounts a = books.accounts(m, s);
  std::printf(
      "  external %.6g J = kinetic %.4g + elastic %.6g + viscous %.6g + hysteretic %.6g; "
      "residual %.2e of the input\n",
      a.external, a.kinetic, a.elastic, a.viscous, a.hysteretic, a.relative_residual());
  m.books = false;
  return a.relative_residual();
}

}  // namespace ntn_test
