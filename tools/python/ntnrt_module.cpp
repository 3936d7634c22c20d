// ntnrt: the kernel from Python (pybind11, numpy). A model file is loaded as ntn-run loads it
// (the model compiler's checks; run-time storage, one block bound before init), runs through the
// command-line tools' own code (ntn::run::simulate: the loop on the virtual clock, the output
// hash), so that its results are theirs bit for bit, and the loop runs in C++ with the GIL
// released. tools/python/README.md documents the API.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <new>
#include <stdexcept>
#include <string>
#include <vector>

#include "ntn/hil/geometry_report.hpp"
#include "ntn/hil/loaded_model.hpp"
#include "ntn/modal/modal.hpp"
#include "ntn/modecheck/modecheck.hpp"
#include "ntn/modelc/load_model.hpp"
#include "ntn/modelc/model_report.hpp"
#include "ntn/spectral/error.hpp"
#include "ntn/spectral/welch.hpp"
#include "ntn/spectral/window.hpp"
#include "record.hpp"
#include "run_driver.hpp"

namespace py = pybind11;

namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// A model file with errors: the compiler's messages, file:line:column each (ntnrt.ModelError).
class ModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

std::string trimmed(std::string s) {
  while (!s.empty() && s.back() == '\n')
    s.pop_back();
  return s;
}

Array to_numpy(const std::vector<double>& v) {
  Array a(static_cast<py::ssize_t>(v.size()));
  if (!v.empty()) std::memcpy(a.mutable_data(), v.data(), v.size() * sizeof(double));
  return a;
}

// A record (ntnrt.read_record, or built from an array): values, sample interval, unit.
struct PyRecord {
  ntn::io::Record r;
};

void check_path(const std::string& path);

PyRecord read_record(const std::string& path, const std::string& column) {
  check_path(path);
  ntn::io::ReadResult res = ntn::io::read_record(path, column);
  if (res.error) throw std::invalid_argument(res.error->format());
  return {std::move(*res.record)};
}

// A record's values: a one-dimensional array of real numbers (floats or integers), at least one.
// Booleans, complex numbers, strings and objects are refused rather than cast (forcecast would
// take the real part of a complex array and 1.0 for True).
Array record_values(const py::handle& values) {
  const py::array a = py::array::ensure(values);
  if (!a) throw py::type_error("values: give a sequence or array of numbers");
  const char kind = a.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u')
    throw py::type_error("values: give real numbers (floats or integers), got an array of dtype " +
                         std::string(py::str(a.dtype())));
  if (a.ndim() != 1)
    throw py::value_error("values: a record's values are one-dimensional, got " +
                          std::to_string(a.ndim()) + " dimensions");
  if (a.size() == 0) throw py::value_error("values: a record needs at least one value");
  return a.cast<Array>();
}

PyRecord make_record(const py::object& values_in, double dt, const std::string& units) {
  const Array values = record_values(values_in);
  if (!(dt >= ntn::io::kMinSampleInterval && dt <= ntn::io::kMaxSampleInterval))
    throw py::value_error("dt: the sample interval must be in [" +
                          ntn::cli::num(ntn::io::kMinSampleInterval) + ", " +
                          ntn::cli::num(ntn::io::kMaxSampleInterval) + "] s (as the record " +
                          "files'), got " + ntn::cli::num(dt));
  PyRecord p;
  p.r.source = "array";
  p.r.dt = dt;
  p.r.units = units;
  p.r.unit = ntn::io::parse_unit(units);
  if (!units.empty() && !p.r.unit) throw std::invalid_argument("unknown unit '" + units + "'");
  p.r.values.assign(values.data(), values.data() + values.size());
  return p;
}

// A copy of a run's State (Model.state() / restore()): its own block, bound like the model's.
class PyState {
 public:
  explicit PyState(const ntn::Sizes& s) : sizes_(s) {
    const std::size_t bytes = ntn::runtime_state_bytes(s);
    block_.reset(static_cast<std::byte*>(
        ::operator new (bytes > 0 ? bytes : 1, std::align_val_t{ntn::kRunTimeBlockAlign})));
    if (!ntn::runtime_bind_state(state_, s, std::span<std::byte>(block_.get(), bytes)))
      throw std::runtime_error("cannot bind a state");
  }
  ntn::State<ntn::kRunTime>& state() { return state_; }
  const ntn::Sizes& sizes() const { return sizes_; }
  bool started = false;
  std::uint64_t model = 0;  // the serial of the Model it came from

 private:
  struct Free {
    void operator()(std::byte* p) const {
      ::operator delete (p, std::align_val_t{ntn::kRunTimeBlockAlign});
    }
  };
  ntn::Sizes sizes_;
  std::unique_ptr<std::byte, Free> block_;
  ntn::State<ntn::kRunTime> state_;
};

// One call at a time on a Model: run() releases the GIL while it runs, and a second thread's
// call on the same Model (run, step, reset, restore, state) would share its state. It raises
// instead: a Model is one run's; load one per thread to run in parallel.
class Busy {
 public:
  explicit Busy(std::atomic<bool>& flag) : flag_(flag) {
    if (flag_.exchange(true))
      throw std::runtime_error(
          "the model is busy: another thread is running it (load one Model per thread)");
  }
  ~Busy() { flag_.store(false); }
  Busy(const Busy&) = delete;
  Busy& operator=(const Busy&) = delete;

 private:
  std::atomic<bool>& flag_;
};

// Each loaded Model's number: a State restores only into the Model it came from.
inline std::atomic<std::uint64_t> g_model_serial{0};

class PyModel {
 public:
  explicit PyModel(std::unique_ptr<ntn::hil::LoadedModel> m) : m_(std::move(m)) {
    const ntn::InitStatus st = m_->init();
    if (!st.ok())
      throw ModelError(m_->description().source_file + ": error: " + ntn::to_string(st.error) +
                       " (at " + std::to_string(st.where) + ")");
    in_.assign(m_->model().sizes.inputs, 0.0);
    reset();
  }

  const ntn::modelc::ModelDescription& d() const { return m_->description(); }
  ntn::hil::LoadedModel& loaded() { return *m_; }

  py::dict sizes() const {
    const ntn::Sizes z = d().sizes();
    py::dict out;
    out["nodes"] = z.nodes, out["elements"] = z.elements, out["hinges"] = z.hinges;
    out["inputs"] = z.inputs, out["outputs"] = z.outputs, out["dofs"] = 6 * z.nodes;
    out["loads"] = z.loads, out["hystereses"] = z.hystereses;
    return out;
  }
  Array nodes() const {
    Array a({static_cast<py::ssize_t>(d().nodes.size()), py::ssize_t{3}});
    auto v = a.mutable_unchecked<2>();
    for (std::size_t n = 0; n < d().nodes.size(); ++n) {
      v(static_cast<py::ssize_t>(n), 0) = d().nodes[n].x;
      v(static_cast<py::ssize_t>(n), 1) = d().nodes[n].y;
      v(static_cast<py::ssize_t>(n), 2) = d().nodes[n].z;
    }
    return a;
  }
  std::vector<std::string> input_names() const { return d().input_names; }
  std::vector<std::string> output_names() const { return d().output_names; }
  std::vector<std::string> output_units() const { return d().output_units; }
  double dt() const { return m_->model().dt; }
  double stable_dt() const { return m_->model().stable.dt_stable; }
  double frame_period() const { return d().settings.frame_period; }
  std::int64_t substeps() const { return m_->model().substeps.count; }
  std::string info() const { return ntn::modelc::info_text(d()); }

  // run(inputs={name: record}, duration=None, sampling="step", threads=1, element_pass="simd",
  // scale={name: factor})
  py::dict run(const py::dict& inputs, py::object duration, const std::string& sampling_name,
               int threads, const std::string& element_pass, const py::dict& scale) {
    const Busy busy(busy_);
    const ntn::Sizes z = m_->model().sizes;
    const auto sampling = ntn::hil::parse_sampling(sampling_name);
    if (!sampling) throw std::invalid_argument("sampling must be 'step', 'hold' or 'interpolate'");
    if (threads < 1 || threads > ntn::kMaxTeam)
      throw std::invalid_argument("threads must be 1.." + std::to_string(ntn::kMaxTeam));
    if (element_pass != "simd" && element_pass != "scalar")
      throw std::invalid_argument("element_pass must be 'simd' or 'scalar'");
    // The factors on the records (the command line's FILE*FACTOR): the rule of a scale factor.
    std::vector<double> factors(z.inputs, 1.0);
    for (const auto& [key, value] : scale) {
      const std::string name = py::str(key);
      const std::size_t k = input_index(name);
      double f = 0;
      try {
        f = value.cast<double>();
      } catch (const py::cast_error&) {
        throw std::invalid_argument("scale['" + name + "'] must be a number, got " +
                                    std::string(py::str(py::type::of(value).attr("__name__"))));
      }
      if (!ntn::io::scale_factor_valid(f))
        throw std::invalid_argument("scale['" + name + "'] must be " + ntn::io::kScaleFactorRule +
                                    ", got " + ntn::cli::num(f));
      factors[k] = f;
    }
    std::vector<ntn::io::Record> records(z.inputs);
    std::vector<char> fed(z.inputs, 0);
    for (const auto& [key, value] : inputs) {
      const std::string name = py::str(key);
      const std::size_t k = input_index(name);
      records[k] = as_record(value, name);
      // As ntn-run reads a record: converted to the input's unit, scaled, every sample finite
      // and in the input's range.
      const ntn::InputSpec& spec = d().inputs[k];
      const ntn::io::Unit unit = ntn::io::input_unit(
          spec.kind == ntn::InputKind::kGroundAcceleration, spec.dof, spec.scale);
      if (const auto e = records[k].to_unit(unit))
        throw std::invalid_argument("input '" + name + "': " + *e);
      records[k].scale(factors[k]);
      for (std::size_t s = 0; s < records[k].values.size(); ++s) {
        const double v = records[k].values[s];
        if (!std::isfinite(v))
          throw std::invalid_argument("input '" + name + "': sample " + std::to_string(s) +
                                      " is not finite");
        if (v < spec.min || v > spec.max)
          throw std::invalid_argument(
              "input '" + name + "': sample " + std::to_string(s) + " = " + ntn::cli::num(v) + " " +
              unit.name +
              (factors[k] != 1 ? " (the record x " + ntn::cli::num(factors[k]) + ")" : "") +
              " is outside the input's range");
      }
      fed[k] = 1;
    }
    double longest = 0;
    for (std::size_t k = 0; k < z.inputs; ++k) {
      if (!fed[k])
        throw std::invalid_argument("no record for input channel '" + d().input_names[k] + "'");
      longest = std::max(longest, records[k].duration());
    }
    double seconds = longest;
    if (!duration.is_none()) {
      if (!py::isinstance<py::float_>(duration) && !py::isinstance<py::int_>(duration))
        throw py::type_error("duration: give a number of seconds, got " +
                             std::string(py::str(py::type::of(duration).attr("__name__"))));
      seconds = duration.cast<double>();
    }
    if (!(seconds > 0) || !std::isfinite(seconds))
      throw std::invalid_argument("give duration, a finite number > 0 (no input record)");
    const double wanted = std::ceil(seconds / dt() - 1e-9);
    if (!(wanted >= 1) || wanted > 1e12)
      throw std::invalid_argument("duration: " + ntn::cli::num(seconds) + " s gives " +
                                  ntn::cli::num(wanted) + " steps of dt = " + ntn::cli::num(dt()) +
                                  " s (at least 1, at most 1e12)");

    m_->model().element_pass =
        element_pass == "scalar" ? ntn::ElementPass::kScalar : ntn::ElementPass::kSimd;
    ntn::run::RunRequest request;
    request.steps = static_cast<std::int64_t>(wanted);
    request.sampling = *sampling;
    request.threads = threads;
    std::vector<double> frames, energy_frames;
    request.frames = &frames;
    request.energy_frames = &energy_frames;
    ntn::run::RunResult r;
    {
      py::gil_scoped_release unlocked;  // the loop runs in C++
      r = ntn::run::simulate(storage(), m_->spec(), m_->info(), records, request);
    }
    if (!r.error.empty()) throw std::runtime_error(r.error);
    started_ = true;  // the state is where the run ended: step() continues from it

    const std::size_t nout = z.outputs;
    // every frame has its energy accounts (a model may have no outputs)
    const std::size_t nframes = energy_frames.size() / ntn::hil::kEnergyChannels.size();
    py::dict out;
    Array time(static_cast<py::ssize_t>(nframes));
    for (std::size_t k = 0; k < nframes; ++k)
      time.mutable_data()[k] = static_cast<double>(k) * frame_period();
    out["time"] = time;
    py::dict channels;
    for (std::size_t c = 0; c < nout; ++c) {
      Array a(static_cast<py::ssize_t>(nframes));
      for (std::size_t k = 0; k < nframes; ++k)
        a.mutable_data()[k] = frames[k * nout + c];
      channels[py::str(d().output_names[c])] = a;
    }
    out["outputs"] = channels;
    py::dict energy;  // the energy books by mechanism, J, every frame after its last step
    const std::size_t na = ntn::hil::kEnergyChannels.size();
    for (std::size_t c = 0; c < na; ++c) {
      Array a(static_cast<py::ssize_t>(nframes));
      for (std::size_t k = 0; k < nframes; ++k)
        a.mutable_data()[k] = energy_frames[k * na + c];
      energy[py::str(std::string(ntn::hil::kEnergyChannels[c]))] = a;
    }
    out["energy"] = energy;
    out["hash"] = std::string(r.hash);
    out["steps"] = r.steps;
    out["diverged"] = r.diverged;
    out["summary"] = summary(r);
    return out;
  }

  void reset() {
    const Busy busy(busy_);
    ntn::initial_state(m_->model(), m_->state());
    started_ = false;
  }
  // One kernel step with these inputs (a sequence in channel order, or {name: value}); the
  // outputs at t_n. The first step after load() / reset() starts the run with its inputs.
  Array step(const py::object& inputs) {
    const Busy busy(busy_);
    read_step_inputs(inputs);
    auto& m = m_->model();
    if (!started_) {
      (void)ntn::start(m, m_->state(), m_->scratch(), std::span<const double>(in_));
      started_ = true;
    }
    const ntn::StepStatus st =
        ntn::step(m, m_->state(), m_->scratch(), std::span<const double>(in_));
    if (st == ntn::StepStatus::kDiverged)
      throw std::runtime_error("the step diverged: the state is no longer finite (reset())");
    const auto& o = m_->scratch().outputs;
    return to_numpy(std::vector<double>(o.begin(), o.end()));
  }
  double time() const { return static_cast<double>(m_->state().tick) * dt(); }
  std::int64_t tick() const { return m_->state().tick; }

  std::shared_ptr<PyState> state() {
    const Busy busy(busy_);
    auto s = std::make_shared<PyState>(m_->model().sizes);
    s->state() = m_->state();  // element by element (Slice)
    s->started = started_;
    s->model = serial_;
    return s;
  }
  void restore(const PyState& s) {
    const Busy busy(busy_);
    if (s.model != serial_ || s.sizes() != m_->model().sizes)
      throw std::invalid_argument(
          "the state is of another model (a State restores into the Model it came from)");
    m_->state() = const_cast<PyState&>(s).state();
    started_ = s.started;
  }
  // The displacements u_n and velocities v_{n-1/2}, one row per node (ux, uy, uz, rx, ry, rz).
  Array displacements() const { return node_rows(m_->state().u); }
  Array velocities() const { return node_rows(m_->state().v); }

  py::dict modes(int n) const {
    if (n < 1)
      throw py::value_error("n: give the number of modes, at least 1, got " + std::to_string(n));
    ntn::modal::ModalOptions options;
    options.modes = n;
    ntn::modal::ModalResult r;
    {
      py::gil_scoped_release unlocked;
      r = ntn::modal::modal_analysis(d().view(), options);
    }
    if (!r.ok()) throw std::runtime_error("modal analysis: " + r.error);
    py::dict out;
    out["frequency"] = eigen_vector(r.frequency);
    out["omega"] = eigen_vector(r.omega);
    out["period"] = eigen_vector(r.period);
    out["damping_ratio"] = eigen_vector(r.damping_ratio);
    out["shapes"] = eigen_matrix(r.shapes);
    out["participation"] = eigen_matrix(r.participation);
    out["effective_mass"] = eigen_matrix(r.effective_mass);
    out["total_mass"] = std::vector<double>(r.total_mass.begin(), r.total_mass.end());
    out["table"] = ntn::modal::mode_table(r);
    return out;
  }

 private:
  ntn::run::RunStorage<ntn::kRunTime> storage() {
    return {m_->model(),   m_->init_work(), m_->state(),
            m_->scratch(), m_->team_work(), &m_->loop_buffers()};
  }
  std::size_t input_index(const std::string& name) const {
    const auto& names = d().input_names;
    for (std::size_t k = 0; k < names.size(); ++k)
      if (names[k] == name) return k;
    std::string known;
    for (const auto& n : names)
      known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("the model has no input channel '" + name +
                                "' (it has: " + (known.empty() ? "none" : known) + ")");
  }
  static ntn::io::Record as_record(const py::handle& value, const std::string& name) {
    if (py::isinstance<PyRecord>(value)) return value.cast<PyRecord>().r;
    if (py::isinstance<py::tuple>(value)) {
      const auto t = value.cast<py::tuple>();
      if (t.size() == 2 || t.size() == 3) {
        const std::string units = t.size() == 3 ? py::str(t[2]).cast<std::string>() : "";
        return make_record(py::reinterpret_borrow<py::object>(t[0]), t[1].cast<double>(), units).r;
      }
    }
    throw std::invalid_argument("input '" + name +
                                "': give an ntnrt.Record or a tuple (values, dt[, units])");
  }
  // The inputs of one step: as run() reads a record's samples, every value finite and inside
  // its input's [min, max] (the kernel would hold a value outside it: step() says so instead).
  void read_step_inputs(const py::object& inputs) {
    std::vector<double> v(in_.size(), 0.0);
    const std::string wanted = "inputs: give " + std::to_string(in_.size()) +
                               " numbers in channel order, or {name: value}";
    if (py::isinstance<py::dict>(inputs)) {
      const auto dict = inputs.cast<py::dict>();
      if (dict.size() != in_.size())
        throw std::invalid_argument("give a value for every input channel (" +
                                    std::to_string(in_.size()) + ")");
      for (const auto& [key, value] : dict) {
        const std::size_t k = input_index(py::str(key));
        if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value) &&
            !py::isinstance(value, py::module_::import("numbers").attr("Real")))
          throw py::type_error("inputs['" + d().input_names[k] + "']: give a number, got " +
                               std::string(py::str(py::type::of(value).attr("__name__"))));
        v[k] = value.cast<double>();
      }
    } else {
      if (inputs.is_none() || py::isinstance<py::str>(inputs)) throw py::type_error(wanted);
      const py::array a = py::array::ensure(inputs);
      if (!a) throw py::type_error(wanted);
      const char kind = a.dtype().kind();
      if (kind != 'f' && kind != 'i' && kind != 'u')
        throw py::type_error(wanted + "; got an array of dtype " + std::string(py::str(a.dtype())));
      if (a.ndim() != 1)
        throw py::value_error(wanted + "; got an array of " + std::to_string(a.ndim()) +
                              " dimensions");
      if (static_cast<std::size_t>(a.size()) != in_.size())
        throw py::value_error("the model has " + std::to_string(in_.size()) +
                              " input channels; got " + std::to_string(a.size()) + " values");
      const Array x = a.cast<Array>();
      std::copy(x.data(), x.data() + x.size(), v.begin());
    }
    for (std::size_t k = 0; k < v.size(); ++k) {
      const ntn::InputSpec& spec = d().inputs[k];
      if (!std::isfinite(v[k]))
        throw std::invalid_argument("input '" + d().input_names[k] + "' is not finite");
      if (v[k] < spec.min || v[k] > spec.max)
        throw std::invalid_argument("input '" + d().input_names[k] + "' = " + ntn::cli::num(v[k]) +
                                    " is outside its range [" + ntn::cli::num(spec.min) + ", " +
                                    ntn::cli::num(spec.max) + "] (the model file's min, max)");
    }
    in_ = v;  // only a good set of inputs reaches the model
  }
  template <class A>
  static Array node_rows(const A& x) {
    const std::size_t nodes = x.size() / 6;
    Array a({static_cast<py::ssize_t>(nodes), py::ssize_t{6}});
    if (x.size() > 0) std::memcpy(a.mutable_data(), x.data(), x.size() * sizeof(double));
    return a;
  }
  static Array eigen_vector(const Eigen::VectorXd& v) {
    Array a(static_cast<py::ssize_t>(v.size()));
    for (Eigen::Index i = 0; i < v.size(); ++i)
      a.mutable_data()[i] = v(i);
    return a;
  }
  static Array eigen_matrix(const Eigen::MatrixXd& m) {
    Array a({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
    auto v = a.mutable_unchecked<2>();
    for (Eigen::Index i = 0; i < m.rows(); ++i)
      for (Eigen::Index j = 0; j < m.cols(); ++j)
        v(i, j) = m(i, j);
    return a;
  }
  py::dict summary(const ntn::run::RunResult& r) const {
    py::dict peaks, end;
    for (std::size_t c = 0; c < r.peaks.size(); ++c) {
      py::dict p;
      p["abs"] = r.peaks[c].value, p["time"] = r.peaks[c].time;
      peaks[py::str(d().output_names[c])] = p;
      end[py::str(d().output_names[c])] = r.last[c];
    }
    py::dict energy;
    const ntn::hil::EnergyAccounts& books = r.accounts;
    energy["external"] = books.external;
    energy["kinetic_change"] = books.kinetic;
    energy["elastic"] = books.elastic;
    energy["viscous"] = books.viscous;
    energy["hysteretic"] = books.hysteretic;
    energy["friction"] = books.friction;
    energy["impacts"] = books.impacts;
    energy["fracture"] = books.fracture;
    energy["residual"] = books.residual;
    py::list yielded;
    for (const auto& y : ntn::hil::yielded_directions(m_->model(), m_->state())) {
      py::dict e;
      e["hinge"] = d().hinge_info[static_cast<std::size_t>(y.hinge)].name;
      e["direction"] = ntn::hil::direction_name(y.direction);
      e["peak"] = y.peak, e["residual"] = y.residual, e["dissipated_J"] = y.dissipated;
      e["level"] = y.level;
      e["level_name"] = ntn::hil::level_name(y.level, y.has_limits);
      if (y.first_slip >= 0) e["first_slip_s"] = y.first_slip, e["failed"] = y.failed;
      yielded.append(e);
    }
    py::dict out;
    out["peaks"] = peaks, out["end"] = end, out["energy_J"] = energy, out["yielded"] = yielded;
    out["plastic_directions"] = ntn::hil::plastic_directions(m_->model());
    out["simulated_s"] = static_cast<double>(r.steps) * dt();
    out["wall_s"] = r.wall;
    // The stable step's bound of second-order geometry and the state's fault bits, as ntn-run's
    // JSON has them (geometry_bound_json, fault_names_json).
    const std::int64_t first = r.loop.geometry_bound_frame;
    py::dict bound;
    bound["elements"] = ntn::hil::bounded_elements(m_->model());
    bound["evaluations"] = r.geometry_bound;
    bound["first_frame"] = first;
    bound["first_time_s"] =
        first >= 0 ? py::cast(static_cast<double>(first) * frame_period()) : py::none();
    out["geometry_bound"] = bound;
    py::list faults;
    for (const ntn::hil::FaultName& f : ntn::hil::kFaultNames)
      if ((m_->state().faults & f.bit) != 0) faults.append(f.name);
    out["faults"] = faults;
    return out;
  }

  std::unique_ptr<ntn::hil::LoadedModel> m_;
  std::vector<double> in_;
  bool started_ = false;
  std::atomic<bool> busy_{false};
  std::uint64_t serial_ = ++g_model_serial;
};

// A path with a NUL in it names another file than the one given (the C library stops at it).
void check_path(const std::string& path) {
  if (path.find('\0') != std::string::npos) throw py::value_error("path: contains a NUL character");
}

std::unique_ptr<PyModel> load(const std::string& path) {
  check_path(path);
  ntn::modelc::LoadResult r = ntn::modelc::load_model(path);
  if (!r.ok()) throw ModelError(trimmed(ntn::modelc::format_all(r.errors)));
  const ntn::RunTimeOptions options{.team = true, .checkpoint = false};
  if (const auto refused = ntn::hil::storage_memory_refusal(*r.model, options))
    throw ModelError(path + ": error: " + *refused);
  return std::make_unique<PyModel>(
      std::make_unique<ntn::hil::LoadedModel>(std::move(*r.model), options));
}

ntn::spectral::Window window_of(const std::string& name) {
  try {
    return ntn::spectral::parse_window(name);
  } catch (const ntn::spectral::Error& e) {
    throw std::invalid_argument(e.what());
  }
}

// The Welch PSD of x (one-sided, u^2/Hz) on lines of `resolution` Hz: (frequencies, psd).
py::tuple psd(const Array& x, double fs, double resolution, double overlap,
              const std::string& window) {
  if (x.ndim() != 1) throw std::invalid_argument("x must be one-dimensional");
  ntn::spectral::WelchOptions o;
  o.resolution_hz = resolution;
  o.overlap = overlap;
  o.window = window_of(window);
  ntn::spectral::Spectrum s;
  try {
    s = ntn::spectral::welch_psd(
        std::span<const double>(x.data(), static_cast<std::size_t>(x.size())), fs, o);
  } catch (const ntn::spectral::Error& e) {
    throw std::invalid_argument(e.what());
  }
  Array f(static_cast<py::ssize_t>(s.values.size()));
  for (std::size_t k = 0; k < s.values.size(); ++k)
    f.mutable_data()[k] = s.grid.frequency(k);
  return py::make_tuple(f, to_numpy(s.values));
}

// ntn-check-modes on arrays: {name: samples} at fs Hz against the model's modes.
py::dict check_modes(const PyModel& model, const py::dict& data, double fs, int modes,
                     double tolerance, double min_mac, double band, double resolution,
                     std::vector<std::string> channels, int direction, double false_alarm) {
  ntn::spectral::Channels ch;
  ch.source = "arrays";
  ch.fs = fs;
  for (const auto& [key, value] : data) {
    const Array a = value.cast<Array>();
    if (a.ndim() != 1) throw std::invalid_argument("each channel is one-dimensional");
    ch.names.push_back(py::str(key));
    ch.units.emplace_back();
    ch.data.emplace_back(a.data(), a.data() + a.size());
  }
  for (const auto& c : ch.data)
    if (c.size() != ch.samples()) throw std::invalid_argument("the channels differ in length");
  ntn::modecheck::Options o;
  o.spelling = ntn::modecheck::Spelling::kLibrary;
  o.modes = modes, o.tolerance = tolerance, o.min_mac = min_mac, o.search_band = band;
  o.resolution_hz = resolution, o.channels = std::move(channels), o.direction = direction;
  o.false_alarm = false_alarm;
  ntn::modecheck::Report rep;
  try {
    rep = ntn::modecheck::check_data(model.d(), ch, o);
  } catch (const ntn::modecheck::InputError& e) {
    throw std::invalid_argument(e.what());
  }
  py::dict out;
  out["pass"] = rep.pass;
  out["summary"] = rep.summary;
  out["table"] = ntn::modecheck::format_table(rep);
  out["json"] = ntn::modecheck::to_json(rep);
  py::list list;
  for (const auto& m : rep.modes) {
    py::dict e;
    e["mode"] = m.number, e["model_hz"] = m.model_hz, e["found"] = m.found;
    e["identified_hz"] = m.identified_hz, e["error"] = m.error, e["pass"] = m.pass;
    e["verdict"] = m.verdict;
    if (m.mac) e["mac"] = *m.mac;
    if (m.above_floor) e["above_floor"] = *m.above_floor;
    if (m.noise_threshold) e["noise_threshold"] = *m.noise_threshold;
    if (m.damping) e["damping"] = *m.damping;
    list.append(e);
  }
  out["modes"] = list;
  return out;
}

}  // namespace

PYBIND11_MODULE(_ntnrt, m) {
  m.doc() = "ntn-rt: real-time structural dynamics kernel (tools/python/README.md)";
  py::register_exception<ModelError>(m, "ModelError", PyExc_ValueError);

  py::class_<PyRecord>(m, "Record")
      .def(py::init(&make_record), py::arg("values"), py::arg("dt"), py::arg("units") = "")
      .def_property_readonly("values", [](const PyRecord& p) { return to_numpy(p.r.values); })
      .def_property_readonly("dt", [](const PyRecord& p) { return p.r.dt; })
      .def_property_readonly("units", [](const PyRecord& p) { return p.r.units; })
      .def_property_readonly("source", [](const PyRecord& p) { return p.r.source; })
      .def_property_readonly("duration", [](const PyRecord& p) { return p.r.duration(); })
      .def("__len__", [](const PyRecord& p) { return p.r.values.size(); });
  m.def("read_record", &read_record, py::arg("path"), py::arg("column") = "",
        "A record file (PEER AT2, or CSV with COLUMN) as ntn-run reads it.");
  m.def(
      "read_at2", [](const std::string& path) { return read_record(path, ""); }, py::arg("path"),
      "A PEER AT2 record (values in g).");

  py::class_<PyState, std::shared_ptr<PyState>>(m, "State")
      .def_property_readonly("tick", [](PyState& s) { return s.state().tick; });

  py::class_<PyModel>(m, "Model")
      .def_property_readonly("name", [](const PyModel& p) { return p.d().name; })
      .def_property_readonly("title", [](const PyModel& p) { return p.d().title; })
      .def_property_readonly("source_file", [](const PyModel& p) { return p.d().source_file; })
      .def_property_readonly("sizes", &PyModel::sizes)
      .def_property_readonly("nodes", &PyModel::nodes)
      .def_property_readonly("node_ids", [](const PyModel& p) { return p.d().node_ids; })
      .def_property_readonly("inputs", &PyModel::input_names)
      .def_property_readonly("outputs", &PyModel::output_names)
      .def_property_readonly("units", &PyModel::output_units)
      .def_property_readonly("dt", &PyModel::dt)
      .def_property_readonly("stable_dt", &PyModel::stable_dt)
      .def_property_readonly("frame_period", &PyModel::frame_period)
      .def_property_readonly("substeps", &PyModel::substeps)
      .def_property_readonly("block_bytes", [](PyModel& p) { return p.loaded().block_bytes(); })
      .def("info", &PyModel::info, "What `ntn-model info` prints.")
      .def("run", &PyModel::run, py::arg("inputs") = py::dict(), py::arg("duration") = py::none(),
           py::arg("sampling") = "step", py::arg("threads") = 1, py::arg("element_pass") = "simd",
           py::arg("scale") = py::dict())
      .def("reset", &PyModel::reset)
      .def("step", &PyModel::step, py::arg("inputs"))
      .def_property_readonly("time", &PyModel::time)
      .def_property_readonly("tick", &PyModel::tick)
      .def("state", &PyModel::state)
      .def("restore", &PyModel::restore, py::arg("state"))
      .def("displacements", &PyModel::displacements)
      .def("velocities", &PyModel::velocities)
      .def("modes", &PyModel::modes, py::arg("n") = 12);
  m.def("load", &load, py::arg("path"), "Loads a model file (TOML); ModelError on errors.");
  m.def("psd", &psd, py::arg("x"), py::arg("fs"), py::arg("resolution"), py::arg("overlap") = 0.5,
        py::arg("window") = "hann");
  m.def("check_modes", &check_modes, py::arg("model"), py::arg("data"), py::arg("fs"),
        py::arg("modes") = 3, py::arg("tolerance") = 0.01, py::arg("min_mac") = 0.9,
        py::arg("band") = 0.10, py::arg("resolution") = 0.0,
        py::arg("channels") = std::vector<std::string>{}, py::arg("direction") = -1,
        py::arg("false_alarm") = 0.01);
  m.attr("element_pass_target") = std::string(ntn::element_pass_target());
}
