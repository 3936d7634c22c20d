// ntn-check-modes: does a response's spectrum show the model's natural frequencies (and shapes)?
//   ntn-check-modes MODEL.toml RESPONSE.csv [options]
// Exit 0: the first N (selected) modes are found within the tolerance (and MAC >= the threshold
// where the channels give shapes); 1: they are not (the table and the last line say which mode
// and why); 2: bad input (a message on stderr). tools/modecheck/README.md.
#include <cstdio>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "cli.hpp"  // tools/io: validators that print numbers with %g and refuse NaN and inf
#include "ntn/modecheck/modecheck.hpp"
#include "ntn/spectral/error.hpp"

int main(int argc, char** argv) {
  namespace mc = ntn::modecheck;
  ntn::cli::App app{
      "Check a response's spectrum against a model's natural frequencies and mode shapes "
      "(exit 0 pass, 1 fail, 2 bad input)"};
  std::string model_path, response_path, json_path, psd_path, plot_base, window = "hann", direction;
  mc::Options o;
  double tolerance_pct = 100 * o.tolerance, band_pct = 100 * o.search_band,
         min_mass_pct = 100 * o.min_mass_fraction, min_visibility_pct = 100 * o.min_visibility,
         false_alarm_pct = 100 * o.false_alarm;
  app.add_option("model", model_path, "model file (.toml)")->required();
  app.add_option("response", response_path,
                 "response: the CSV of ntn-run / ntn-hil (time column, then channels), a plain "
                 "CSV of the same shape, or a PEER .AT2 record")
      ->required();
  app.add_option("-n,--modes", o.modes, "number of (selected) model modes to check")
      ->check(ntn::cli::Integer(1, std::numeric_limits<int>::max()))
      ->capture_default_str();
  app.add_option("-t,--tolerance", tolerance_pct, "allowed frequency error, %")
      ->check(ntn::cli::Positive())
      ->capture_default_str();
  app.add_option("--min-mac", o.min_mac, "MAC needed where the channels give a shape")
      ->check(ntn::cli::Number(0.0, 1.0))
      ->capture_default_str();
  app.add_option("-c,--channels", o.channels,
                 "channels to use (comma-separated; default: every channel that maps to a node "
                 "DOF, of the most common kind)")
      ->delimiter(',');
  app.add_option("-r,--resolution", o.resolution_hz,
                 "line spacing in Hz (default: tolerance x lowest checked frequency / 2 if the "
                 "record is long enough, else the whole record as one segment)")
      ->check(ntn::cli::Positive());
  app.add_option("-d,--direction", direction,
                 "check only modes with effective mass along x, y or z (base excitation in that "
                 "direction)")
      ->check(ntn::cli::IsMember({"x", "y", "z"}));
  app.add_option("--min-mass", min_mass_pct,
                 "with --direction: effective mass a mode needs, % of the total")
      ->check(ntn::cli::Number(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--band", band_pct, "search band around each model frequency, +-%")
      ->check(ntn::cli::Number(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--min-visibility", min_visibility_pct,
                 "a mode fails as not seen when the channels move less than this % of its "
                 "largest motion")
      ->check(ntn::cli::Number(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--false-alarm", false_alarm_pct,
                 "a matched peak must stand out of the noise: the probability, %, that noise "
                 "reaches it in the search band")
      ->check(ntn::cli::Number(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--window", window, "hann, hamming, blackman, flattop, rectangular")
      ->capture_default_str();
  app.add_option("--overlap", o.overlap, "Welch segment overlap, fraction")
      ->check(ntn::cli::Number(0.0, 0.95))
      ->capture_default_str();
  app.add_option("--min-prominence", o.min_prominence,
                 "a peak's value over its higher base (power ratio)")
      ->check(ntn::cli::Number(1.0, 1e12))
      ->capture_default_str();
  app.add_option("--min-level", o.min_level,
                 "a peak's value over the largest in the searched range")
      ->check(ntn::cli::Number(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--json", json_path, "write the summary as JSON to FILE ('-': stdout, no table)");
  app.add_option("--psd-out", psd_path,
                 "write the spectrum used (frequency, singular values or PSD, each channel's "
                 "PSD) as CSV, and the checked modes beside it as FILE_modes.csv");
  app.add_option("--plot", plot_base,
                 "draw the spectrum with the model frequencies marked to BASE.png and BASE.svg "
                 "(gnuplot)");
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;
  o.tolerance = tolerance_pct / 100;
  o.search_band = band_pct / 100;
  o.min_mass_fraction = min_mass_pct / 100;
  o.min_visibility = min_visibility_pct / 100;
  o.false_alarm = false_alarm_pct / 100;
  if (!direction.empty()) o.direction = direction[0] - 'x';

  try {
    o.window = ntn::spectral::parse_window(window);
    const mc::Report report = mc::check_files(model_path, response_path, o);
    if (json_path == "-") {
      std::fputs(mc::to_json(report).c_str(), stdout);
    } else {
      std::fputs(mc::format_table(report).c_str(), stdout);
      if (!json_path.empty()) {
        std::ofstream js(json_path, std::ios::binary);
        js << mc::to_json(report);
        if (!js) throw mc::InputError("cannot write the JSON file '" + json_path + "'");
      }
    }
    if (!psd_path.empty()) mc::write_spectrum_csv(psd_path, report);
    if (!plot_base.empty()) {
      const auto files = mc::write_plot(plot_base, report);
      if (json_path != "-") {
        for (const std::string& f : files)
          std::printf("  plot: %s\n", f.c_str());
      }
    }
    if (!report.pass) std::fprintf(stderr, "ntn-check-modes: %s\n", report.summary.c_str());
    return report.pass ? 0 : 1;
  } catch (const mc::InputError& e) {
    std::fprintf(stderr, "ntn-check-modes: error: %s\n", e.what());
    return 2;
  } catch (const ntn::spectral::Error& e) {
    std::fprintf(stderr, "ntn-check-modes: error: %s\n", e.what());
    return 2;
  } catch (const mc::PlotError& e) {
    std::fprintf(stderr, "ntn-check-modes: error: the plot: %s\n", e.what());
    return 2;
  }
}
