// ntn-ida MODEL.toml --records DIR|LIST --out DIR: incremental dynamic analysis. Every
// (record, intensity) pair is one run of the model (run-time storage, the run of ntn-run); each
// record is traced by stepping or by hunt and fill (trace.hpp) from its own earlier runs only.
// Under `mpirun -np N` the records are spread over the N processes as they become free (an
// atomic counter in an MPI window: the longest records first); without mpirun one process runs
// them all. Every run is appended to DIR/runs/ as soon as it is done, so a study that was cut
// short is continued with --resume. At the end the first process writes DIR/results.csv (sorted:
// the same bytes whatever the number of processes and the order the runs ended),
// DIR/capacities.csv, DIR/fragility.csv and the plots.
#include <xxhash.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numeric>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "cli.hpp"
#include "ntn/ida/results.hpp"
#include "ntn/ida/study.hpp"

#ifdef NTN_IDA_MPI
#include <mpi.h>
#endif

namespace {

namespace fs = std::filesystem;
using ntn::ida::RunRow;

// Whether this process runs under mpirun (MPI initialized, possibly with others). Without
// mpirun the program runs alone and does not start MPI: a singleton MPI_Init costs ~0.4 s.
bool g_mpi = false;
using ntn::ida::Study;

struct Options {
  std::string model;
  std::string records;
  std::string out;
  std::string im = "sa_t1";
  double period = 0;
  double damping = 0.05;
  std::string scales;
  ntn::ida::TracePlan plan;
  std::vector<std::string> edps;
  std::string input;
  double tail = 10;
  std::string collapse_drift = "0.1";  // a drift ratio, or "none"
  int threads = 1;
  bool resume = false;
  bool no_plots = false;
  bool quiet = false;
};

// "0.1,0.2,0.5" or "START:STEP:STOP" (START + k STEP up to STOP), or the message.
std::vector<double> parse_scales(const std::string& text, std::string& error) {
  std::vector<double> out;
  const auto number = [&](const std::string& s) -> double {
    const auto v = ntn::cli::parse_double(s);
    if (!v) error = "--scales: '" + s + "' is not a number";
    return v.value_or(0);
  };
  if (text.find(':') != std::string::npos) {
    std::vector<std::string> parts;
    std::stringstream in(text);
    for (std::string p; std::getline(in, p, ':');)
      parts.push_back(p);
    if (parts.size() != 3) {
      error = "--scales: START:STEP:STOP has three numbers";
      return out;
    }
    const double start = number(parts[0]), step = number(parts[1]), stop = number(parts[2]);
    if (!error.empty()) return out;
    if (!(step > 0) || !(stop >= start) || (stop - start) / step > 10000) {
      error = "--scales: START:STEP:STOP needs STEP > 0, STOP >= START and at most 10 000 levels";
      return out;
    }
    for (int k = 0;; ++k) {
      const double v = start + k * step;
      if (v > stop * (1 + 1e-12)) break;
      out.push_back(v);
    }
    return out;
  }
  std::stringstream in(text);
  for (std::string p; std::getline(in, p, ',');) {
    out.push_back(number(p));
    if (!error.empty()) return out;
  }
  return out;
}

std::string hex64(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

std::uint64_t file_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  const std::string text = s.str();
  return XXH3_64bits(text.data(), text.size());
}

// What makes two invocations the same study: the model's and records' bytes and every option
// that changes a run or the tracing (not the number of processes, the output folder or the plots).
std::string study_key(const Options& o, const Study& study) {
  std::ostringstream k;
  k << "ntn-ida study\nmodel " << hex64(file_hash(o.model)) << "\n";
  for (const auto& r : study.records())
    k << "record " << r.name << " " << hex64(file_hash(r.path)) << "\n";
  const auto& p = study.config().plan;
  k.precision(17);
  k << "im " << o.im << " period " << study.period() << " damping " << o.damping << "\n"
    << "mode " << (p.mode == ntn::ida::TraceMode::kStepping ? "stepping" : "hunt-fill");
  for (const double v : p.levels)
    k << " " << v;
  k << "\nfirst " << p.first << " increment " << p.increment << " resolution " << p.resolution
    << " max " << p.max << " runs " << p.runs << "\ninput " << o.input << " tail " << o.tail
    << " collapse_drift " << study.config().collapse_drift
    << "\ncollapse: drift above the limit, diverged, past the geometry bound (the run ends there)"
    << "\nedp";
  for (const auto& c : study.columns())
    k << " " << c.name;
  k << "\n";
  return k.str();
}

// A journal line: the results row and the XXH3 of its text (a line cut by a kill is refused).
std::string journal_line(const std::string& row) {
  return row + "," + hex64(XXH3_64bits(row.data(), row.size())) + "\n";
}

// Every complete line of every journal file in `dir`, as rows.
std::vector<RunRow> read_journal(const Study& study, const fs::path& dir, std::size_t& refused) {
  std::vector<RunRow> rows;
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir, ec))
    if (e.path().extension() == ".runs") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    std::ifstream in(f);
    for (std::string line; std::getline(in, line);) {
      const std::size_t comma = line.rfind(',');
      const bool sealed = comma != std::string::npos && in.good() &&
                          line.substr(comma + 1) ==
                              hex64(XXH3_64bits(line.data(), static_cast<std::size_t>(comma)));
      const auto row =
          sealed ? study.parse_row(std::string_view(line).substr(0, comma)) : std::nullopt;
      if (!row) {
        ++refused;
        continue;
      }
      rows.push_back(*row);
    }
  }
  return rows;
}

// The first process's part of the set-up: the output folder and its journal. 0 or an exit code.
int prepare_output(const Options& o, const Study& study, std::vector<std::string>& notes) {
  const fs::path runs = fs::path(o.out) / "runs";
  std::error_code ec;
  fs::create_directories(runs, ec);
  if (ec || !fs::is_directory(runs)) {
    std::fprintf(stderr, "error: --out: cannot create %s (%s)\n", runs.string().c_str(),
                 ec.message().c_str());
    return 2;
  }
  const std::string key = study_key(o, study);
  const fs::path key_file = runs / "study.txt";
  if (fs::exists(key_file)) {
    std::ifstream in(key_file);
    std::stringstream s;
    s << in.rdbuf();
    if (!o.resume) {
      std::fprintf(stderr,
                   "error: --out %s holds the runs of an earlier study (%s): give --resume to "
                   "continue it, or another --out\n",
                   o.out.c_str(), key_file.string().c_str());
      return 2;
    }
    if (s.str() != key) {
      std::fprintf(stderr,
                   "error: --resume: the runs in %s are of another study (model, records or "
                   "options differ; %s says which)\n",
                   runs.string().c_str(), key_file.string().c_str());
      return 2;
    }
    notes.push_back("resuming the study in " + runs.string());
  } else if (const auto e = ntn::cli::write_output_file(key_file.string(), key, "--out")) {
    std::fprintf(stderr, "error: %s\n", e->c_str());
    return 2;
  }
  return 0;
}

// The command line's options, into `o`.
void add_options(ntn::cli::App& app, Options& o) {
  app.add_option("model", o.model, "the model file (TOML)")->required();
  app.add_option("--records", o.records,
                 "the records: a directory (its .AT2 files) or a list file (one path per line)")
      ->required();
  app.add_option("--out", o.out, "the output folder (results, capacities, fragility, plots)")
      ->required();
  app.add_option("--im", o.im, "intensity measure: sa_t1 (5 %-damped Sa at T1) or pga")
      ->check(ntn::cli::IsMember({"sa_t1", "pga"}))
      ->capture_default_str();
  app.add_option("--period", o.period,
                 "T1 [s] for sa_t1 (default: the model's first period "
                 "along the input's direction)")
      ->check(ntn::cli::Positive(1e4));
  app.add_option("--damping", o.damping, "damping ratio of Sa, in [0, 1)")
      ->check(ntn::cli::Validator(
          [](std::string& text) -> std::string {
            const std::optional<double> v = ntn::cli::parse_double(text);
            if (v && *v >= 0 && *v < 1) return {};
            return "wants a damping ratio in [0, 1) (Sa is the peak of an underdamped "
                   "oscillator), got '" +
                   text + "'";
          },
          "[0, 1)"))
      ->capture_default_str();
  app.add_option("--scales", o.scales,
                 "stepping: the intensities [g], '0.1,0.2,0.4' or START:STEP:STOP (default: hunt "
                 "and fill)");
  app.add_option("--first", o.plan.first, "hunt and fill: first intensity and step [g]")
      ->check(ntn::cli::Positive(1e3))
      ->capture_default_str();
  app.add_option("--step-increase", o.plan.increment,
                 "hunt and fill: growth of the step per run [g]")
      ->check(ntn::cli::NonNegative(1e3))
      ->capture_default_str();
  app.add_option("--max", o.plan.max, "hunt and fill: highest intensity [g]")
      ->check(ntn::cli::Positive(1e3))
      ->capture_default_str();
  app.add_option("--runs", o.plan.runs, "hunt and fill: runs per record")
      ->check(ntn::cli::Integer(1, 1000))
      ->capture_default_str();
  app.add_option("--resolution", o.plan.resolution,
                 "hunt and fill: bracket and gaps closed to this [g]")
      ->check(ntn::cli::Positive(1e3))
      ->capture_default_str();
  app.add_option("--edp", o.edps,
                 "demand columns: peak_drift, residual_drift, peak_floor_acceleration, "
                 "hinge_level, or an output channel (its peak)")
      ->delimiter(',');
  app.add_option("--input", o.input,
                 "the input channel the records feed (default: the first "
                 "ground acceleration)");
  app.add_option("--tail", o.tail, "free vibration after each record [s]")
      ->check(ntn::cli::NonNegative(1e4))
      ->capture_default_str();
  app.add_option("--collapse-drift", o.collapse_drift,
                 "a peak storey drift ratio above this is a collapse; none: only a run that "
                 "diverged or passed the stable step's bound of second-order geometry is")
      ->check(ntn::cli::Validator(
          [](std::string& text) -> std::string {
            if (text == "none") return {};
            const std::optional<double> v = ntn::cli::parse_double(text);
            if (v && *v > 0 && *v <= 10) return {};
            return "wants a drift ratio in (0, 10] or none, got '" + text + "'";
          },
          "(0, 10] or none"))
      ->capture_default_str();
  app.add_option("--threads", o.threads, "kernel workers per run")
      ->check(ntn::cli::Integer(1, 64))
      ->capture_default_str();
  app.add_flag("--resume", o.resume, "continue the study whose runs are in --out");
  app.add_flag("--no-plots", o.no_plots, "no PNG/SVG plots");
  app.add_flag("-q,--quiet", o.quiet, "only the summary");
}

// The study's configuration from the options, its intensities and its record files. 0 or an
// exit code (the first process says why).
int make_config(const Options& o, int rank, ntn::ida::StudyConfig& config) {
  config.model_path = o.model;
  config.input = o.input;
  config.measure = o.im == "pga" ? ntn::ida::Measure::kPga : ntn::ida::Measure::kSaT1;
  config.period = o.period;
  config.damping = o.damping;
  config.plan = o.plan;
  config.tail = o.tail;
  config.collapse_drift = o.collapse_drift == "none"
                              ? std::numeric_limits<double>::infinity()
                              : ntn::cli::parse_double(o.collapse_drift).value_or(0.1);
  config.edps = o.edps;
  config.threads = o.threads;
  if (!o.scales.empty()) {
    std::string error;
    config.plan.mode = ntn::ida::TraceMode::kStepping;
    config.plan.levels = parse_scales(o.scales, error);
    if (!error.empty()) {
      if (rank == 0) std::fprintf(stderr, "error: %s\n", error.c_str());
      return 2;
    }
  }
  std::string error;
  config.record_paths = ntn::ida::record_files(o.records, error);
  if (!error.empty()) {
    if (rank == 0) std::fprintf(stderr, "error: %s\n", error.c_str());
    return 2;
  }
  return 0;
}

// The model and the records loaded, or null and the exit code (the first process says why).
std::unique_ptr<Study> open_study(const ntn::ida::StudyConfig& config, int rank,
                                  std::vector<std::string>& notes, int& code) {
  std::vector<std::string> errors;
  std::unique_ptr<Study> study = Study::open(config, errors, notes, code);
  if (!study && rank == 0) {
    for (const std::string& e : errors)
      std::fprintf(
          stderr, "%s%s\n",
          e.rfind("error", 0) == 0 || e.find(": error") != std::string::npos ? "" : "error: ",
          e.c_str());
    std::fprintf(stderr, "ntn-ida: nothing run\n");
  }
  return study;
}

// The output folder and the journal, by the first process; the others wait for its word.
int prepare_output_everywhere(const Options& o, const Study& study, std::vector<std::string>& notes,
                              int rank) {
  int status = rank == 0 ? prepare_output(o, study, notes) : 0;
#ifdef NTN_IDA_MPI
  if (g_mpi) MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
#endif
  return status;
}

// The first process's opening lines: the notes, the study and what a resume takes over.
void print_start(const Options& o, const Study& study, const std::vector<std::string>& notes,
                 std::size_t known, std::size_t refused, int size) {
  for (const std::string& n : notes)
    std::printf("note: %s\n", n.c_str());
  std::printf("ntn-ida: %s, %zu records, %s, %d process%s\n", o.model.c_str(),
              study.records().size(), study.measure_name().c_str(), size, size == 1 ? "" : "es");
  if (o.resume)
    std::printf(
        "resume: %zu runs done earlier%s\n", known,
        refused > 0 ? (", " + std::to_string(refused) + " cut lines left out").c_str() : "");
}

// This process's journal file (one per process and start, never shared). A line that does not
// fit (a full disk) is cut back off, so the journal holds whole lines only, and the journal is
// given up: the runs after it are counted as lost to a resume.
struct Journal {
  std::string path;
  std::FILE* file = nullptr;
  long good = 0;  // the length of its whole lines
  std::string error;
  double lost = 0;  // runs not in it

  // Opens it for appending; false (and the message) when it cannot.
  bool open(const fs::path& runs_dir, int rank) {
    path = (runs_dir / ("p" + std::to_string(rank) + "-" + std::to_string(::getpid()) + ".runs"))
               .string();
    file = std::fopen(path.c_str(), "a");
    if (file == nullptr) {
      std::fprintf(stderr, "error: cannot write %s: %s\n", path.c_str(), std::strerror(errno));
      return false;
    }
    good = std::ftell(file);
    return true;
  }

  void append(const std::string& line) {
    if (!error.empty()) {
      ++lost;
      return;
    }
    errno = 0;
    if (std::fputs(line.c_str(), file) >= 0 && std::fflush(file) == 0) {
      good += static_cast<long>(line.size());
      return;
    }
    error = std::strerror(errno != 0 ? errno : EIO);
    ++lost;
    if (::ftruncate(::fileno(file), good) != 0) error += "; a cut line is left";
  }

  // Closes it and says which of this process's `new_runs` runs it lost.
  void close(std::size_t new_runs) {
    if (std::fclose(file) != 0 && error.empty()) {
      error = std::strerror(errno != 0 ? errno : EIO);
      lost = static_cast<double>(new_runs);  // what the close could not write is unknown
    }
    if (!error.empty()) {
      std::fprintf(stderr,
                   "error: %s: %.0f of this process's %zu runs are not in the journal (%s): "
                   "--resume would make them again\n",
                   path.c_str(), lost, new_runs, error.c_str());
    }
  }
};

// The records, longest first (the longest runs start early: less time waiting at the end).
std::vector<std::size_t> longest_first(const Study& study) {
  const auto& records = study.records();
  std::vector<std::size_t> order(records.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return records[a].record.duration() > records[b].record.duration();
  });
  return order;
}

// The next task of any process: an atomic counter in an MPI window on the first process under
// mpirun, a local one alone.
class TaskCounter {
 public:
  explicit TaskCounter([[maybe_unused]] int rank) {
#ifdef NTN_IDA_MPI
    if (g_mpi) {
      MPI_Win_allocate(rank == 0 ? static_cast<MPI_Aint>(sizeof(std::int64_t)) : 0,
                       sizeof(std::int64_t), MPI_INFO_NULL, MPI_COMM_WORLD, &counter_, &window_);
      if (rank == 0) {
        MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, window_);
        *counter_ = 0;
        MPI_Win_unlock(0, window_);
      }
      MPI_Barrier(MPI_COMM_WORLD);
    }
#endif
  }

  std::int64_t next() {
#ifdef NTN_IDA_MPI
    if (g_mpi) {
      const std::int64_t one = 1;
      std::int64_t task = 0;
      MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, window_);
      MPI_Fetch_and_op(&one, &task, MPI_INT64_T, 0, 0, MPI_SUM, window_);
      MPI_Win_unlock(0, window_);
      return task;
    }
#endif
    return next_local_++;
  }

  // The window freed (after the gathers: every process has taken its last task).
  void release() {
#ifdef NTN_IDA_MPI
    if (g_mpi) MPI_Win_free(&window_);
#endif
  }

 private:
  std::int64_t next_local_ = 0;
#ifdef NTN_IDA_MPI
  std::int64_t* counter_ = nullptr;
  MPI_Win window_ = MPI_WIN_NULL;
#endif
};

// What one process ran: its rows, and its new runs and their time.
struct ProcessRuns {
  std::vector<RunRow> rows;
  double busy = 0;  // s
  std::size_t new_runs = 0;
};

// This process's records, taken from the counter until none is left: each traced, its new runs
// journaled as they end, a line per record unless quiet.
ProcessRuns run_records(const Options& o, Study& study, const std::vector<RunRow>& known,
                        const std::vector<std::size_t>& order, TaskCounter& tasks, Journal& journal,
                        int rank) {
  const auto& records = study.records();
  ProcessRuns mine;
  for (std::int64_t task = tasks.next(); task < static_cast<std::int64_t>(order.size());
       task = tasks.next()) {
    const std::size_t r = order[static_cast<std::size_t>(task)];
    const auto traced = study.trace(r, known, [&](const RunRow& row) {
      journal.append(journal_line(study.csv_row(row)));
      mine.busy += row.seconds;
      ++mine.new_runs;
    });
    if (!o.quiet) {
      const auto cap = ntn::ida::capacities(study, traced);
      std::string c = "no collapse";
      // capacities() indexes by record: this record's entry.
      if (cap[r].collapse.im) c = "collapses from " + ntn::cli::num(*cap[r].collapse.im) + " g";
      std::printf("[%d] %-14s %2zu runs, %s\n", rank, records[r].name.c_str(), traced.size(),
                  c.c_str());
      std::fflush(stdout);
    }
    mine.rows.insert(mine.rows.end(), traced.begin(), traced.end());
  }
  return mine;
}

// Every process's rows (as text), runs, time and lost runs, on the first process.
struct Gathered {
  std::string text;
  std::vector<double> busy_of, runs_of, lost_of;
};

Gathered gather(const Study& study, const ProcessRuns& mine, double journal_lost,
                [[maybe_unused]] int rank, int size) {
  Gathered g;
  for (const RunRow& row : mine.rows)
    g.text += study.csv_row(row) + "\n";
  const double busy = mine.busy;
  g.busy_of.assign(static_cast<std::size_t>(size), busy);
  g.runs_of.assign(static_cast<std::size_t>(size), static_cast<double>(mine.new_runs));
  g.lost_of.assign(static_cast<std::size_t>(size), journal_lost);
#ifdef NTN_IDA_MPI
  if (g_mpi) {
    const int length = static_cast<int>(g.text.size());
    std::vector<int> lengths(static_cast<std::size_t>(size)),
        offsets(static_cast<std::size_t>(size));
    MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, MPI_COMM_WORLD);
    std::string gathered;
    if (rank == 0) {
      for (std::size_t k = 1; k < offsets.size(); ++k)
        offsets[k] = offsets[k - 1] + lengths[k - 1];
      gathered.resize(static_cast<std::size_t>(offsets.back() + lengths.back()));
    }
    MPI_Gatherv(g.text.data(), length, MPI_CHAR, gathered.data(), lengths.data(), offsets.data(),
                MPI_CHAR, 0, MPI_COMM_WORLD);
    MPI_Gather(&busy, 1, MPI_DOUBLE, g.busy_of.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    const double my_runs = static_cast<double>(mine.new_runs);
    MPI_Gather(&my_runs, 1, MPI_DOUBLE, g.runs_of.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    MPI_Gather(&journal_lost, 1, MPI_DOUBLE, g.lost_of.data(), 1, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    g.text = std::move(gathered);
  }
#endif
  return g;
}

// The rows of the gathered text.
std::vector<RunRow> parse_rows(const Study& study, const std::string& text) {
  std::vector<RunRow> all;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (auto row = study.parse_row(line)) all.push_back(*row);
  }
  return all;
}

// The study's time and each process's runs and time; the total of the lost runs.
double print_times(const Gathered& g, double wall, int size) {
  double total_runs = 0, total_lost = 0;
  std::string per_process;
  for (std::size_t k = 0; k < g.busy_of.size(); ++k) {
    total_runs += g.runs_of[k];
    total_lost += g.lost_of[k];
    char part[64];
    std::snprintf(part, sizeof part, "%s p%zu %.0f runs %.1f s", k == 0 ? "" : ",", k, g.runs_of[k],
                  g.busy_of[k]);
    per_process += part;
  }
  std::printf(
      "time %.1f s, %.0f new runs, %.2f runs/s on %d process%s (runs and their time per "
      "process:%s)\n",
      wall, total_runs, total_runs / wall, size, size == 1 ? "" : "es", per_process.c_str());
  return total_lost;
}

// The first process's end: the result files and plots, the summary, the times, what was
// written and lost. The exit code: 2 when a result (a file or journal lines) is lost, 3 when the
// results are whole but a plot is not.
int write_and_report(const Options& o, const Study& study, const std::vector<RunRow>& all,
                     const Gathered& g, double wall, int size) {
  std::vector<std::string> out_notes;
  const ntn::ida::Written written =
      ntn::ida::write_results(study, all, o.out, !o.no_plots, out_notes);
  for (const std::string& n : out_notes)
    std::printf("note: %s\n", n.c_str());
  std::printf("%s", ntn::ida::summary_text(study, all).c_str());
  const double total_lost = print_times(g, wall, size);
  std::string files;
  for (const std::string& f : written.files)
    files += (files.empty() ? "" : ", ") + f;
  std::printf("written: %s\n", files.empty() ? "nothing" : files.c_str());
  for (const std::string& p : written.lost)
    std::fprintf(stderr, "error: %s\n", p.c_str());
  for (const std::string& p : written.plots_lost)
    std::fprintf(stderr, "error: %s\n", p.c_str());
  if (total_lost > 0 && size > 1)
    std::fprintf(stderr, "error: %.0f runs are not in the journal (see above)\n", total_lost);
  if (!written.lost.empty() || total_lost > 0) return 2;
  return written.plots_lost.empty() ? 0 : 3;
}

int ida(int argc, char** argv, int rank, int size) {
  Options o;
  ntn::cli::App app{"Incremental dynamic analysis and fragility of a model over a record suite",
                    "ntn-ida"};
  add_options(app, o);
  // CLI11 prints its messages on every process: only the first one speaks.
  if (rank != 0) {
    app.silence_failures();
  }
  if (const auto code = ntn::cli::parse(app, argc, argv)) return *code;

  ntn::ida::StudyConfig config;
  if (const int code = make_config(o, rank, config); code != 0) return code;
  std::vector<std::string> notes;
  int code = 0;
  std::unique_ptr<Study> study = open_study(config, rank, notes, code);
  if (!study) return code;
  if (const int status = prepare_output_everywhere(o, *study, notes, rank); status != 0)
    return status;

  const fs::path runs_dir = fs::path(o.out) / "runs";
  std::size_t refused = 0;
  const std::vector<RunRow> known = read_journal(*study, runs_dir, refused);
  if (rank == 0 && !o.quiet) print_start(o, *study, notes, known.size(), refused, size);
  Journal journal;
  if (!journal.open(runs_dir, rank)) {
#ifdef NTN_IDA_MPI
    if (g_mpi) MPI_Abort(MPI_COMM_WORLD, 2);
#endif
    return 2;
  }

  const std::vector<std::size_t> order = longest_first(*study);
  TaskCounter tasks(rank);
  const auto t0 = std::chrono::steady_clock::now();
  const ProcessRuns mine = run_records(o, *study, known, order, tasks, journal, rank);
  journal.close(mine.new_runs);
  const Gathered g = gather(*study, mine, journal.lost, rank, size);
  tasks.release();
  // The study's time: after the gathers, so every process has finished its records.
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rank != 0) return 0;
  return write_and_report(o, *study, parse_rows(*study, g.text), g, wall, size);
}

}  // namespace

int main(int argc, char** argv) {
#ifdef NTN_IDA_MPI
  // Launched by mpirun (Open MPI's or another PMI launcher): the environment says so.
  g_mpi = std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMI_SIZE") != nullptr ||
          std::getenv("PMIX_RANK") != nullptr;
  if (g_mpi) MPI_Init(&argc, &argv);
#endif
  const int code = ntn::cli::guarded_main(
      [](int c, char** v) -> int {
        int rank = 0, size = 1;
#ifdef NTN_IDA_MPI
        if (g_mpi) {
          MPI_Comm_rank(MPI_COMM_WORLD, &rank);
          MPI_Comm_size(MPI_COMM_WORLD, &size);
        }
#endif
        return ida(c, v, rank, size);
      },
      argc, argv);
#ifdef NTN_IDA_MPI
  if (g_mpi) MPI_Finalize();
#endif
  return code;
}
