// The modal check (DESIGN §9): does a response's spectrum show the model's natural
// frequencies (and, where the channels give a shape, its mode shapes)?
//
//   1. channels: the response file's channels that map to a node DOF of the model (outputs of
//      kind displacement, velocity, acceleration, absolute_acceleration), of one kind;
//   2. model: ntn::modal's modes, optionally only those with effective mass along one direction;
//   3. identification: FDD (first singular value of the cross-spectral matrix, its peaks, their
//      singular vectors as shapes) over two or more channels, the Welch PSD of one channel;
//   4. matching: each model mode to the nearest identified peak within a search band, one peak per
//      mode (closest pairs first); frequency error, half-power damping, MAC;
//   5. verdict: pass when every checked mode is found within the tolerance and, where shapes
//      exist, its MAC reaches the threshold.
// tools/modecheck/README.md gives the rules and their limits.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "ntn/modelc/model_description.hpp"
#include "ntn/spectral/channels.hpp"
#include "ntn/spectral/peaks.hpp"
#include "ntn/spectral/spectrum.hpp"
#include "ntn/spectral/window.hpp"

namespace ntn::modecheck {

// Bad input (exit code 2 of ntn-check-modes): unreadable file, bad model, unknown channel, NaN or
// infinite data, too short a record for the resolution, an impossible request.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// How option errors name an option: as ntn-check-modes takes it ("option --tolerance is 150 %"),
// or as the library and the Python module take it ("tolerance is 1.5", fractions as fractions).
enum class Spelling : std::uint8_t { kCli, kLibrary };

struct Options {
  Spelling spelling = Spelling::kCli;
  int modes = 3;              // N: the first N (selected) model modes are checked
  double tolerance = 0.01;    // |f_identified - f_model| / f_model allowed
  double min_mac = 0.9;       // where the channels give a shape
  double search_band = 0.10;  // a peak is looked for within f_model (1 +- search_band)
  double resolution_hz = 0;   // line spacing; 0: auto (see resolve_resolution)
  double overlap = 0.5;       // Welch segment overlap
  spectral::Window window = spectral::Window::kHann;
  std::vector<std::string> channels;  // empty: every node-DOF channel of the most common kind
  int direction = -1;                 // 0, 1, 2: only modes with effective mass along x, y, z
  double min_mass_fraction = 0.01;    // ... of at least this fraction of the total mass
  double min_prominence = 1.25;  // peaks: value / higher base (1 dB on a power spectrum: the dip
                                 // between close damped modes is shallow)
  double min_level = 1e-4;       // peaks: value / the largest value in the searched range
  double min_visibility = 0.05;  // a mode the channels see less of than this fails (below)
  // A matched peak is a mode only when noise would reach it with at most this probability
  // (compare(): its height over the local floor against the chi-square threshold).
  double false_alarm = 0.01;
};

// Refuses options no check can run with (InputError naming the option as options.spelling
// spells it, its value and the allowed range): NaN or infinite values anywhere, tolerance and
// search band not in (0, 1], min_mac, min_level, min_visibility, min_mass_fraction not in [0, 1],
// min_prominence below 1, overlap not in [0, 1), resolution_hz negative, modes below 1, direction
// not -1..2. check_files, identify and compare call it, so programmatic use is covered too.
void validate(const Options& options);

// How a response channel maps to the model.
enum class Kind : std::uint8_t { kDisplacement, kVelocity, kAcceleration, kOther };
const char* to_string(Kind kind);

struct ChannelInfo {
  std::string name;
  std::size_t column = 0;  // index in Channels::data
  Kind kind = Kind::kOther;
  int node = -1;         // model node index (kOther: -1)
  int dof = -1;          // 0..5
  std::string location;  // "node 201 ux" (empty for kOther)
  std::string unit;      // the file's unit of the channel ("m"), may be empty
};

struct Selection {
  std::vector<ChannelInfo> channels;
  bool shapes = false;  // all channels map to node DOFs of one kind, and there are two or more
  std::vector<std::string> notes;
};

// The channels to use. `names` empty: the channels that map to a node DOF, of the most common
// kind (ties: displacement, velocity, acceleration); none mapping: every channel of the file.
// Throws InputError on an unknown name (listing the file's channels) or a repeated one.
Selection select_channels(const modelc::ModelDescription* model, const spectral::Channels& data,
                          const std::vector<std::string>& names);

// The model's modes to check, and their shapes at the selected channels.
struct ModelModes {
  std::vector<int> number;           // 1-based mode number in the model's full list
  std::vector<double> frequency;     // Hz
  std::vector<double> damping;       // the model's modal damping ratio (alpha / 2 omega)
  std::vector<double> mass_percent;  // effective mass along options.direction (or the largest)
  Eigen::MatrixXd shapes;            // channels x modes; empty without shapes
  // How much of each mode the channels see: the largest |phi| at the channels' node DOFs over
  // the largest |phi| of the same sort (translation or rotation) anywhere in the model. Empty
  // when a channel does not map to a node DOF.
  std::vector<double> visibility;
  std::vector<std::string> notes;
};

// Modal analysis (ntn::modal) and the first options.modes modes, those with effective mass along
// options.direction >= min_mass_fraction when a direction is given. Throws InputError when the
// analysis fails or fewer modes qualify.
ModelModes model_modes(const modelc::ModelDescription& model, const Selection& selection,
                       const Options& options);

struct IdentifiedPeak {
  spectral::Peak peak;
  std::optional<spectral::HalfPower> half_power;
  Eigen::VectorXd shape;  // FDD: real operational shape at the selected channels; PSD: empty
  int singular = 0;       // FDD: the peak is on s1 (1) or s2 (2); PSD: 0
};

struct Identification {
  std::string method;  // "FDD" or "PSD"
  spectral::Grid grid;
  std::vector<std::string> channels;
  spectral::Spectrum spectrum;               // what the peaks come from: s1 (FDD) or the PSD
  std::vector<spectral::Spectrum> auto_psd;  // per channel (FDD: the diagonal of G)
  std::vector<spectral::Spectrum> singular;  // FDD: s1 ... sn
  std::vector<IdentifiedPeak> peaks;         // inside [f_min, f_max], frequency order
  double f_min = 0, f_max = 0;               // Hz: the range searched
  // The numerical floor of the spectrum (u^2/Hz): a local maximum below it is rounding noise, not
  // a peak (README, "Dead channels and the numerical floor"); the maxima left out for it are
  // counted.
  double floor = 0;
  int below_floor = 0;
  std::vector<std::string> notes;
};

// The line spacing to use: options.resolution_hz when given (InputError, naming the needed
// duration, when the record is shorter than one segment), else tolerance x f_lowest / 2 when the
// record holds a segment that long, else the whole record as one segment (with a note).
double resolve_resolution(const spectral::Channels& data, double lowest_model_hz,
                          const Options& options, std::vector<std::string>* notes);

// Spectrum and peaks of the selected channels in [f_min, f_max] (InputError on bad data, bad
// options, and a constant channel: "channel 'X' is constant (a dead sensor?) ..."). Peaks below
// the numerical floor are left out (Identification::floor).
Identification identify(const spectral::Channels& data, const Selection& selection,
                        double resolution_hz, double f_min, double f_max, const Options& options);

// One model mode against the spectrum.
struct ModeCheck {
  int number = 0;  // model mode number (1-based)
  double model_hz = 0;
  double model_damping = 0;
  double mass_percent = 0;
  bool found = false;
  double identified_hz = 0;
  double error = 0;                        // (identified - model) / model
  std::optional<double> damping;           // half power
  std::optional<double> resolution_ratio;  // B_e / half-power band; > 0.25: damping biased high
  std::optional<double> mac;
  bool frequency_ok = false;
  bool mac_ok = true;
  bool pass = false;
  // The peak over its local floor (the PSD, or the trace of the spectral matrix for FDD) and
  // the ratio noise reaches with probability options.false_alarm in the search band.
  std::optional<double> above_floor, noise_threshold;
  std::string verdict;  // "ok" or what failed
};

// A mode whose visibility (ModelModes) is below options.min_visibility fails as "not seen by the
// channels": a peak near its frequency would belong to something else, and its MAC is noise.
//
// A matched peak must stand out of noise: its line's value over the local floor (the median of
// the lines within f / 1.5 .. 1.5 f outside the peak's half-power band, ntn::spectral::
// local_floor) must reach the ratio that the largest of the search band's lines of noise
// reaches with probability options.false_alarm (ntn::spectral::noise_threshold, with the
// average's degrees of freedom, welch_dof). For FDD the test is on the trace of the spectral
// matrix with one channel's degrees of freedom (conservative: correlated channels average no
// further).
//
// Matching: every (mode, peak) pair with |f_peak - f_model| <= search_band f_model, taken in
// order of increasing relative distance; a mode and a peak are matched once each. Returns, per
// model frequency, the index of its peak or -1.
std::vector<int> match_peaks(const std::vector<double>& model_hz,
                             const std::vector<double>& peak_hz, double search_band);

struct Report {
  std::string model_name, model_file, response_file;
  double fs = 0, duration = 0;
  Kind kind = Kind::kOther;
  Selection selection;
  Identification identification;
  ModelModes model;
  Options options;
  std::vector<ModeCheck> modes;
  std::vector<std::string> notes;
  bool pass = false;
  std::string summary;  // "PASS ..." or "FAIL: mode 2 (frequency +4.88 % > 1 %), ..."
};

// Matching, errors, MAC, verdicts.
Report compare(const ModelModes& model, const Identification& identification,
               const Selection& selection, const Options& options);

// Everything from files: model (TOML), response (CSV or AT2). Throws InputError.
Report check_files(const std::string& model_path, const std::string& response_path,
                   const Options& options);
// The same from a loaded model and channels in memory (the Python module's check_modes): the
// report names model.source_file and data.source. Throws InputError.
Report check_data(const modelc::ModelDescription& model, const spectral::Channels& data,
                  const Options& options);

std::string format_table(const Report& report);
std::string to_json(const Report& report);
// The spectrum used, as a table ntn-plot reads: frequency[Hz], s1..sn (FDD) and each channel's
// PSD ("name[unit^2/Hz]"), one row per line; and beside it, at modes_csv_path(path), the checked
// modes: mode, model_hz, identified_hz, error_percent, mac, pass. Throws InputError when it
// cannot write.
void write_spectrum_csv(const std::string& path, const Report& report);
std::string modes_csv_path(const std::string& spectrum_path);  // "x.csv" -> "x_modes.csv"

// BASE.png and BASE.svg (ntn::plot, gnuplot): the singular values (FDD) or the PSD, and below them
// each channel's PSD, log scale, with the model's frequencies marked ("mode 1 1.6046 Hz"), from
// 0 to 1.5 times the top of the searched range. Returns the two paths; throws PlotError.
class PlotError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
std::vector<std::string> write_plot(const std::string& base, const Report& report);

}  // namespace ntn::modecheck
