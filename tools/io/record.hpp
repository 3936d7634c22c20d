// Reading sampled records (ground motions, measured channels): PEER AT2 and CSV, with the rules
// every tool shares: the sample interval's accepted range, uniform sampling of a CSV time column,
// and the units of the values (parsed, and converted to a model input's unit in one place).
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace ntn::io {

// The sample interval (AT2 DT, a CSV's time step) a record may have, in s. 1 us (1 MHz) is
// beyond any accelerograph or laboratory data acquisition used on structures (tens of kHz at
// most); 1 s (Nyquist 0.5 Hz) is below the modes of any structure a record could drive. A value
// outside is a corrupt header or a unit slip (DT in ms: "DT= 20"), and a record of 1e-300 s
// steps (zero run steps) or 1e308 s steps (an infinite duration) is refused by its key.
inline constexpr double kMinSampleInterval = 1e-6;
inline constexpr double kMaxSampleInterval = 1.0;
// Values an AT2 header may claim (NPTS): at most 1e8 (800 MB of doubles).
inline constexpr double kMaxPoints = 1e8;
// Uniform sampling of a CSV time column: strictly increasing, and every time t_k within this
// fraction of a step of the least-squares grid through all rows. Relative to the step, not to
// |t|: a time column counted from an epoch (t ~ 1.7e9 s) is held to the same 1 % of a step as one
// starting at 0. (1 % of a step is a phase error of 0.003 rad at a tenth of the sample rate; a
// time column printed with 9 significant digits, as ntn-run and ntn-hil write it, meets it at
// 1 kHz up to t = 10 000 s.)
inline constexpr double kTimeGridTolerance = 0.01;

// What a record's values measure: the model's inputs are ground accelerations, forces and
// moments.
enum class Quantity : std::uint8_t { kAcceleration, kForce, kMoment };

// A unit of a record's values: a value in this unit times `si` is the SI value.
struct Unit {
  std::string name;  // canonical spelling: "g", "mg", "gal", "cm/s2", "m/s2", "mm/s2", "in/s2",
                     // "ft/s2", "N", "kN", "N m", "kN m"
  Quantity quantity = Quantity::kAcceleration;
  double si = 1;
};

// The unit a text names, in any case and common spelling ("m/s^2", "m/s²", "m/s/s", "cm/sec**2",
// "Gal", "G"); nothing when it names none of the units above.
std::optional<Unit> parse_unit(std::string_view text);
// "g, mg, gal, cm/s2, m/s2, mm/s2, in/s2, ft/s2, N, kN, N m, kN m": for messages.
std::string known_units();
// The raw unit of a model input ([[inputs]] of config/README.md): a ground acceleration in "g"
// (scale 9.80665) or "m/s2" (scale 1); a nodal force (dof 0..2) or moment (dof 3..5) whose raw
// value times `scale` is N or N m. The unit's `si` is the input's scale.
Unit input_unit(bool ground_acceleration, int dof, double scale);

// A factor on a ground motion: a ground acceleration's `scale` in a model file, the FACTOR of
// `--input NAME=FILE*FACTOR`, ntnrt's run(scale=). Any finite number but 0: a negative factor
// reverses the motion (a record is run in both senses), while 0 would turn the record into no
// motion and the run into a success that computed nothing. The caller names the key or option:
// "must be " + kScaleFactorRule + ", got ...".
inline constexpr const char* kScaleFactorRule = "a finite number other than 0";
bool scale_factor_valid(double factor);

// One uniformly sampled channel.
struct Record {
  std::string source;          // file path
  std::string description;     // header text (AT2) or column name (CSV)
  std::string units;           // the unit as the file states it ("g", "m/s2", ...); empty if none;
                               // after to_unit, the target's name
  std::optional<Unit> unit;    // `units` understood by parse_unit (nothing: none, or unknown)
  std::string converted_from;  // after to_unit: the stated unit converted from; empty if the
                               // values were already in the target unit or stated none
  bool unit_assumed = false;   // after to_unit: the file stated no unit; taken as the target's
  double scaled_by = 1;        // after scale: the factor the values were multiplied by
  double dt = 0;               // s, in [kMinSampleInterval, kMaxSampleInterval]
  double t0 = 0;  // s, the time of the first sample as the file gives it (a CSV's first row; 0 for
                  // AT2). The record's time origin is its first sample: at(t) and every run
                  // play sample k at t = k dt.
  std::vector<double> values;  // in `units`

  double duration() const { return dt * static_cast<double>(values.size()); }
  // Linear interpolation at time t (from the first sample); 0 before the start and after the
  // end (ground at rest).
  double at(double t) const;
  double peak_abs() const;
  // Converts the values to `target` (a model input's unit, input_unit): a stated unit of the
  // same quantity is converted (values x unit.si / target.si; exactly unchanged when the two
  // are the same unit), a record that states no unit is taken to be in `target` already, and a
  // stated unit that is unknown or of another quantity is refused. Returns the message (naming
  // the stated unit and the wanted one), or nothing when the values are now in `target`.
  std::optional<std::string> to_unit(const Unit& target);
  // Multiplies every value by `f` (FILE*FACTOR, run(scale=)), after to_unit: the values stay in
  // their unit, `scaled_by` says by how much they were scaled. f = 1 leaves them as they are.
  void scale(double f);
};

struct ReadError {
  std::string file;
  int line = 0;  // 0: the file as a whole (it cannot be opened): no position
  int column = 0;
  std::string message;
  std::string format() const;  // "file:line:column: error: message" ("file: error: message")
};

struct ReadResult {
  std::optional<Record> record;
  std::optional<ReadError> error;
};

// The whole file as text, or the error "cannot open: <reason>" (no such file, a directory, no
// permission) without a position. Every reader of tools/io opens files through it.
std::optional<ReadError> read_text_file(const std::string& path, std::string& text);

// PEER AT2: three free-text header lines, a fourth with NPTS and DT in either style
// ("NPTS=  2000, DT= .02000 SEC" or "2000  0.0200  NPTS, DT"), then NPTS values in free or
// Fortran fixed format. CR/LF line endings of any mix are accepted. The unit comes from the
// header lines ("UNITS OF G", "The units are (g)", "IN GAL (CM/S/S)", "IN CM/SEC/SEC"); a header
// that names two different units, or speaks of units and names none that parse_unit knows, is
// refused; one that says nothing of units leaves `units` empty.
ReadResult read_at2(const std::string& path);
// The same from text in memory; `source` stands for the file name in the record and errors.
ReadResult read_at2_text(std::string_view text, const std::string& source);

// CSV with a header row; `column` names the channel (or is empty for the second column). The
// first column is time in s (a header "time[ms]" is refused), strictly increasing and uniformly
// spaced (kTimeGridTolerance); the channel's unit is the "[unit]" of its header.
ReadResult read_csv(const std::string& path, const std::string& column);
ReadResult read_csv_text(std::string_view text, const std::string& column,
                         const std::string& source);

// The uniform-sampling rule for a time column (read_csv and ntn::spectral's CSV channels): at
// least 2 times, strictly increasing, each within kTimeGridTolerance of a step of the line
// t_k = a + k dt fitted to all times by least squares (computed on t_k - t_0). On success `dt` is
// set; on failure the index of the first bad time and the message.
struct TimeGridError {
  std::size_t index = 0;
  std::string message;
};
std::optional<TimeGridError> check_time_grid(const std::vector<double>& times, double& dt);

// By extension: .AT2/.at2 -> read_at2, anything else -> read_csv.
ReadResult read_record(const std::string& path, const std::string& column = {});
// True when `path` ends in ".at2" in any case: read_record and the channel readers of
// ntn::spectral and ntn::plot choose the AT2 reader by it.
bool is_at2_path(const std::string& path);

}  // namespace ntn::io
