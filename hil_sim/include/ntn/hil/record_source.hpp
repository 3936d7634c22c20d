// Recorded inputs (AT2 or CSV records, tools/io) as a source of the frame loop (loop.hpp), for
// ntn-run-<model> and ntn-hil-<model> alike (hil_sim/README.md "Input sampling").
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cli.hpp"  // tools/io: InputArg
#include "ntn/hil/gate.hpp"
#include "ntn/model_spec.hpp"
#include "record.hpp"  // tools/io

namespace ntn::hil {

// Reads `file` (`column` of a CSV, empty: its first data column) for the model input `spec`
// named `name`, converts its values to the input's unit (Record::to_unit: gal to g, ...) and
// multiplies them by `factor` (FILE*FACTOR: the record scaled is what the channel receives, so
// its range and the input gate apply to the scaled values, as to those a feeder sends scaled;
// the model file's own `scale` acts after them, in the kernel: InputSpec::factor).
// With `check_range`, every sample must also lie in [spec.min, spec.max]: a run that feeds
// the records at every kernel step (InputSampling::kStep) does not pass them through the input
// gate, so they are checked whole here, before the run. Returns the message (one line, as the
// programs print it: "FILE:LINE:COL: error: ..." or "FILE: error: ..."), or nothing when
// `record` holds the converted record.
// The first sample outside the input's accepted range [spec.min, spec.max] (a NaN is outside
// it), or nothing: what load_input_record checks, and ntn-ida for a record it scaled.
std::optional<std::size_t> first_out_of_range(const InputSpec& spec,
                                              std::span<const double> values);

std::optional<std::string> load_input_record(const InputSpec& spec, const std::string& name,
                                             const std::string& file, const std::string& column,
                                             bool check_range, io::Record& record,
                                             double factor = 1);

// Every --input argument's record by its channel (`names`, the model's input names, in the
// order of `specs`), read and scaled by load_input_record: records[c] and given[c] = 1 for each
// channel given. Returns the first problem's message (an unknown channel: "error: --input NAME=...:
// the model has no input channel 'NAME'"), or nothing.
std::optional<std::string> load_input_records(std::span<const InputSpec> specs,
                                              std::span<const std::string_view> names,
                                              std::span<const cli::InputArg> args, bool check_range,
                                              std::vector<io::Record>& records,
                                              std::vector<char>& given);

// Frame k's inputs are the records at t_k = k period (Record::at: linear between samples, 0
// after the end), through the input gate (finite and in range, else the last accepted value
// held, counted and flagged). For InputSampling::kStep the loop also asks for every kernel
// step's inputs: the records at t_n = n dt, not gated (see load_input_record). The records and
// the gate are the caller's and must outlive the source; nothing here allocates after the
// constructor.
class RecordSource {
 public:
  RecordSource(std::span<const io::Record> records, InputGate& gate, double period, double dt);
  void frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags);
  void step_inputs(std::int64_t n, std::span<double> v) const;

 private:
  std::span<const io::Record> records_;
  InputGate* gate_;
  double period_;
  double dt_;
  std::vector<double> sample_;  // frame k's values before the gate
};

}  // namespace ntn::hil
