#include "ntn/hil/record_source.hpp"

#include <cstdio>

namespace ntn::hil {

std::optional<std::size_t> first_out_of_range(const InputSpec& spec,
                                              std::span<const double> values) {
  for (std::size_t s = 0; s < values.size(); ++s)
    if (!(values[s] >= spec.min && values[s] <= spec.max)) return s;
  return std::nullopt;
}

std::optional<std::string> load_input_record(const InputSpec& spec, const std::string& name,
                                             const std::string& file, const std::string& column,
                                             bool check_range, io::Record& record, double factor) {
  io::ReadResult r = io::read_record(file, column);
  if (r.error) return r.error->format();
  const io::Unit unit =
      io::input_unit(spec.kind == InputKind::kGroundAcceleration, spec.dof, spec.scale);
  if (const auto e = r.record->to_unit(unit)) return file + ": error: input '" + name + "': " + *e;
  r.record->scale(factor);
  if (check_range) {
    if (const auto s = first_out_of_range(spec, r.record->values)) {
      char text[512];
      const std::string scaled = factor != 1 ? " (the record x " + cli::num(factor) + ")" : "";
      std::snprintf(text, sizeof text,
                    "%s: error: sample %zu (t = %g s) = %g %s%s is outside the accepted range "
                    "[%g, %g] of input '%s'",
                    file.c_str(), *s + 1, r.record->t0 + static_cast<double>(*s) * r.record->dt,
                    r.record->values[*s], unit.name.c_str(), scaled.c_str(), spec.min, spec.max,
                    name.c_str());
      return std::string(text);
    }
  }
  record = std::move(*r.record);
  return std::nullopt;
}

std::optional<std::string> load_input_records(std::span<const InputSpec> specs,
                                              std::span<const std::string_view> names,
                                              std::span<const cli::InputArg> args, bool check_range,
                                              std::vector<io::Record>& records,
                                              std::vector<char>& given) {
  records.assign(specs.size(), io::Record{});
  given.assign(specs.size(), 0);
  for (const cli::InputArg& arg : args) {
    std::size_t c = 0;
    while (c < names.size() && names[c] != arg.name)
      ++c;
    if (c == names.size() || c >= specs.size())
      return "error: --input " + arg.name + "=...: the model has no input channel '" + arg.name +
             "'";
    if (auto e = load_input_record(specs[c], arg.name, arg.file, arg.column, check_range,
                                   records[c], arg.factor))
      return e;
    given[c] = 1;
  }
  return std::nullopt;
}

RecordSource::RecordSource(std::span<const io::Record> records, InputGate& gate, double period,
                           double dt)
    : records_(records), gate_(&gate), period_(period), dt_(dt), sample_(records.size()) {}

void RecordSource::frame_inputs(std::int64_t k, std::span<double> v, std::uint16_t& flags) {
  const double t = static_cast<double>(k) * period_;
  for (std::size_t c = 0; c < sample_.size(); ++c)
    sample_[c] = records_[c].at(t);
  gate_->begin_frame(k);
  (void)gate_->accept_values(k, sample_);
  gate_->end_frame(v, flags);
}

void RecordSource::step_inputs(std::int64_t n, std::span<double> v) const {
  const double t = static_cast<double>(n) * dt_;
  for (std::size_t c = 0; c < records_.size() && c < v.size(); ++c)
    v[c] = records_[c].at(t);
}

}  // namespace ntn::hil
