// A generated model under El Centro 1940 N-S (config/ground-motions/elCentro.AT2, in g, the demo
// models' input unit), started from its initial state: the record and the model's Model, State
// and Scratch on the heap (a large model's do not fit the stack). For the validation tests that
// run a config/ model through a real record (energy_balance_test, slip_portal_test).
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <string>

#include "ntn/kernel.hpp"
#include "record.hpp"
#include "support/init_model.hpp"

namespace ntn_test {

template <ntn::Sizes S>
struct ElCentroRun {
  ntn::io::Record record;
  std::unique_ptr<ntn::Model<S>> model = std::make_unique<ntn::Model<S>>();
  std::unique_ptr<ntn::State<S>> state = std::make_unique<ntn::State<S>>();
  std::unique_ptr<ntn::Scratch<S>> scratch = std::make_unique<ntn::Scratch<S>>();

  // Reads the record, initializes the model from `spec` and starts it at rest in its initial
  // state with the record's first sample.
  ::testing::AssertionResult start(const ntn::ModelSpec<S>& spec) {
    const ntn::io::ReadResult rec =
        ntn::io::read_at2(std::string(NTN_CONFIG_DIR) + "/ground-motions/elCentro.AT2");
    if (!rec.record)
      return ::testing::AssertionFailure() << (rec.error ? rec.error->format() : "no record");
    record = *rec.record;
    const ntn::InitStatus st = init_model(spec, *model);
    if (!st.ok())
      return ::testing::AssertionFailure() << ntn::to_string(st.error) << " at " << st.where;
    ntn::initial_state(*model, *state);
    if (ntn::start(*model, *state, *scratch, {record.at(0.0)}) != ntn::StepStatus::kOk)
      return ::testing::AssertionFailure() << "start failed";
    return ::testing::AssertionSuccess();
  }

  // One step at t_n = n dt with the record's sample.
  ntn::StepStatus step(long n) {
    const double t = static_cast<double>(n) * model->dt;
    return ntn::step(*model, *state, *scratch, {record.at(t)});
  }
};

}  // namespace ntn_test
