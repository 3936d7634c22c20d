// The command line of every ntn tool: the parser, and the checks the tools share (numbers must be
// finite and in range, counts must be whole numbers within bounds, output paths must be writable
// before a run starts, and NAME=FILE[:COLUMN][*FACTOR] input arguments are read one way
// everywhere). Messages print numbers with %g (never DBL_MAX in 300 digits) and name the option:
// CLI11 puts the option's name in front of a validator's message.
//
// The parser is CLI11's (Debian libcli11-dev), behind the few classes below, which cli.cpp alone
// implements: CLI11 2.1 is header-only (its precompiled mode came with 2.3), and a file that builds
// a CLI::App compiles ~16 s of CLI11's code at -O3 (~19 s under the sanitizers), once per program
// and per compiled runner. Through this header a program compiles none of it. The names are
// CLI11's: App, Option, Validator, add_option, check, required, ...
#pragma once

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "record.hpp"  // the rule of a scale factor

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace ntn::cli {

// A check of one argument's text (CLI11's Validator): it returns the message, or "" when the
// text is fine; it may rewrite the text. `description` is what --help shows for it.
class Validator {
 public:
  Validator(std::function<std::string(std::string&)> check, std::string description)
      : check_(std::move(check)), description_(std::move(description)) {}
  std::string operator()(std::string& text) const { return check_(text); }
  std::string operator()(const std::string& text) const {
    std::string copy = text;
    return check_(copy);
  }
  const std::string& description() const { return description_; }

 private:
  std::function<std::string(std::string&)> check_;
  std::string description_;
};

// One of the text's values, exactly (CLI::IsMember).
Validator IsMember(std::vector<std::string> values);

// An option or positional argument of an App (CLI::Option); every call returns the option, so
// that calls chain as in CLI11.
class Option {
 public:
  Option* check(const Validator& v);
  Option* required();
  Option* capture_default_str();           // --help shows the variable's value before parsing
  Option* needs(const std::string& name);  // given only with that option
  Option* excludes(Option* other);         // never with that option
  Option* delimiter(char c);               // one argument may hold several values: a,b,c
  std::size_t count() const;               // how often it was given

 private:
  friend class App;
  explicit Option(CLI::Option* o) : o_(o) {}
  CLI::Option* o_;
};

// A command line or one of its subcommands (CLI::App). The top App owns everything made through
// it; the pointers it hands out live as long as it does.
class App {
 public:
  explicit App(std::string description = "", std::string name = "");
  ~App();
  App(const App&) = delete;
  App& operator=(const App&) = delete;

  Option* add_option(std::string name, std::string& value, std::string description = "");
  Option* add_option(std::string name, std::vector<std::string>& value,
                     std::string description = "");
  Option* add_option(std::string name, std::vector<double>& value, std::string description = "");
  Option* add_option(std::string name, double& value, std::string description = "");
  Option* add_option(std::string name, int& value, std::string description = "");
  Option* add_option(std::string name, long& value, std::string description = "");
  Option* add_option(std::string name, unsigned& value, std::string description = "");
  Option* add_option(std::string name, unsigned long& value, std::string description = "");
  Option* add_flag(std::string name, bool& value, std::string description = "");
  App* add_subcommand(std::string name, std::string description);
  App* require_subcommand(int count);
  // No message of a failed parse (ntn-ida's processes but the first: one speaks for all).
  void silence_failures();
  bool parsed() const;                               // this subcommand was given
  std::size_t count(const std::string& name) const;  // how often option `name` was given
  // Parses argv: nothing when the program goes on, else its exit code after CLI11 printed the
  // help (0) or the message (2: every ntn tool's code for bad input; CLI11's own are 100+).
  std::optional<int> parse(int argc, const char* const* argv);

 private:
  struct Parts;  // everything the top App owns
  App(CLI::App* app, Parts* parts);
  CLI::App* app_;
  Parts* parts_;
  std::unique_ptr<Parts> owned_;  // the top App's
};

// %g with 6 significant digits: how every message prints a number.
inline std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// The whole text as a double, or nothing (empty text, trailing characters, out of range of a
// double: strtod's ERANGE for 1e400).
inline std::optional<double> parse_double(const std::string& text) {
  if (text.empty()) return std::nullopt;
  errno = 0;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size() || errno == ERANGE) return std::nullopt;
  return v;
}

// A finite number within [lo, hi] (either bound may be infinite). `open_lo` excludes lo itself,
// for "positive" (> 0). The message says what was wanted and what was given.
inline Validator Number(double lo, double hi, bool open_lo = false) {
  std::string wanted;
  if (std::isinf(lo) && std::isinf(hi)) {
    wanted = "a finite number";
  } else if (std::isinf(hi)) {
    wanted = std::string("a finite number ") + (open_lo ? "> " : ">= ") + num(lo);
  } else {
    wanted = std::string("a number in ") + (open_lo ? "(" : "[") + num(lo) + ", " + num(hi) + "]";
  }
  return Validator(
      [lo, hi, open_lo, wanted](std::string& text) -> std::string {
        const std::optional<double> v = parse_double(text);
        if (!v || !std::isfinite(*v) || *v < lo || *v > hi || (open_lo && *v == lo)) {
          return "wants " + wanted + ", got '" + text + "'";
        }
        return {};
      },
      wanted);
}
inline Validator Finite() {
  return Number(-INFINITY, INFINITY);
}
inline Validator Positive(double hi = INFINITY) {
  return Number(0.0, hi, true);
}
inline Validator NonNegative(double hi = INFINITY) {
  return Number(0.0, hi);
}

// A whole number in [lo, hi] written as digits (an optional sign): refuses 1.5, 1e3, nan and
// 99999999999999999999 with the bounds in the message, before CLI11's conversion sees them.
inline Validator Integer(std::int64_t lo, std::int64_t hi) {
  const std::string wanted =
      "a whole number in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  return Validator(
      [lo, hi, wanted](std::string& text) -> std::string {
        bool digits = !text.empty();
        for (std::size_t i = 0; i < text.size(); ++i) {
          const char c = text[i];
          const bool sign = i == 0 && (c == '-' || c == '+') && text.size() > 1;
          if (!sign && (c < '0' || c > '9')) digits = false;
        }
        if (!digits) return "wants " + wanted + ", got '" + text + "'";
        errno = 0;
        const long long v = std::strtoll(text.c_str(), nullptr, 10);
        if (errno == ERANGE || v < lo || v > hi) return "wants " + wanted + ", got '" + text + "'";
        return {};
      },
      wanted);
}

// Whether a file can be written at `path`, checked before a run so that its result is not lost
// at the end: the path is not a directory, its parent is a directory (created first when
// `create_parents`, as a build step writing into a build tree wants), and the file opens for
// writing (an existing file is left as it is; one created by this check is removed again).
// Returns the message naming the option and the path, or nothing when the path is fine.
inline std::optional<std::string> output_path_problem(const std::string& path,
                                                      std::string_view option,
                                                      bool create_parents = false) {
  namespace fs = std::filesystem;
  const std::string where = std::string(option) + ": cannot write '" + path + "': ";
  if (path.empty()) return std::string(option) + ": the file name is empty";
  std::error_code ec;
  const fs::path p(path);
  if (fs::is_directory(p, ec)) return where + "it is a directory";
  fs::path parent = p.parent_path();
  if (parent.empty()) parent = ".";
  if (create_parents && !fs::exists(parent, ec)) {
    // The nearest existing ancestor must be a directory; create_directories says why not.
    fs::create_directories(parent, ec);
    if (ec)
      return where + "cannot create the directory '" + parent.string() + "' (" + ec.message() + ")";
  }
  if (!fs::exists(parent, ec))
    return where + "the directory '" + parent.string() + "' does not exist";
  if (!fs::is_directory(parent, ec)) return where + "'" + parent.string() + "' is not a directory";
  const bool existed = fs::exists(p, ec);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) return where + std::strerror(errno);
  ::close(fd);
  if (!existed) ::unlink(path.c_str());
  return std::nullopt;
}

// Writes `text` to the output file `path` so that a reader never sees half of it and nothing
// but a regular file is ever replaced: a regular file (or a new one) is written beside itself
// and renamed over (through a symbolic link, its target's place, so the link stays); anything
// else that exists there (a device such as /dev/null, a FIFO, a socket) is written into, as
// the shell's `>` would. Returns the message naming the option and the path, or nothing.
inline std::optional<std::string> write_output_file(const std::string& path, std::string_view text,
                                                    std::string_view option) {
  namespace fs = std::filesystem;
  const std::string where = std::string(option) + ": cannot write '" + path + "': ";
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows links
  if (fs::exists(st) && !fs::is_regular_file(st)) {
    if (fs::is_directory(st)) return where + "it is a directory";
    std::FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) return where + std::strerror(errno);
    const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const int err = errno;
    if (std::fclose(f) != 0 || !written) return where + std::strerror(written ? errno : err);
    return std::nullopt;
  }
  fs::path target(path);
  if (fs::is_symlink(fs::symlink_status(target, ec))) {
    target = fs::read_symlink(target, ec);
    if (ec) return where + ec.message();
    if (target.is_relative()) target = fs::path(path).parent_path() / target;
  }
  const fs::path tmp = target.string() + ".tmp";
  {
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (f == nullptr) return where + "cannot create " + tmp.string() + ": " + std::strerror(errno);
    const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const int err = errno;
    if (std::fclose(f) != 0 || !written) {
      const int e = written ? errno : err;
      fs::remove(tmp, ec);
      return where + std::strerror(e != 0 ? e : EIO);
    }
  }
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    return where + why;
  }
  return std::nullopt;
}

// Closes an output stream written during a run; a failed write or close (disk full) is an error
// of the run: the message names the option and the file.
inline std::optional<std::string> close_output(std::ofstream& out, std::string_view option,
                                               const std::string& path) {
  out.close();
  if (out) return std::nullopt;
  return std::string(option) + ": write error in " + path + ": " +
         std::strerror(errno != 0 ? errno : EIO);
}

// Parses the command line (App::parse): nothing when the program goes on, else its exit code.
inline std::optional<int> parse(App& app, int argc, const char* const* argv) {
  return app.parse(argc, argv);
}

// main()'s backstop: no exception may end a program unreported. Whatever is left after the
// program's own checks (a std::bad_alloc, a filesystem error) is an error with exit 2.
inline int guarded_main(int (*program)(int, char**), int argc, char** argv) {
  try {
    return program(argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
}

// One NAME=FILE[:COLUMN][*FACTOR] argument of --input. FACTOR is what follows the last '*' when
// all of it reads as a number (strtod: 1.5, -1, 2e-1, and nan, inf, 1e999, which the rule of a
// scale factor then refuses); otherwise the '*' belongs to the file name (a file named
// "run*2.AT2" is read as it is; one named "a.AT2*2" is given as "a.AT2*2*1"). COLUMN is what
// follows the last ':' of the file part, when that ':' is not the second character (a drive
// letter).
struct InputArg {
  std::string name;
  std::string file;
  std::string column;  // empty: the record's first data column
  double factor = 1;   // the record's values are multiplied by it (io::Record::scale)
};

struct InputArgs {
  std::vector<InputArg> args;
  std::optional<std::string> error;  // the message naming the option and the argument
};

namespace detail {
// FILE[:COLUMN] into a.file and a.column.
inline void split_column(std::string text, InputArg& a) {
  a.column.clear();
  if (const auto c = text.rfind(':'); c != std::string::npos && c > 1) {
    a.column = text.substr(c + 1);
    text.resize(c);
  }
  a.file = std::move(text);
}
// The whole text as a number in strtod's syntax, whatever its value (nan, inf, 1e999 included:
// those are factors that the rule refuses, not parts of a file name).
inline std::optional<double> number_syntax(const std::string& text) {
  if (text.empty() || std::isspace(static_cast<unsigned char>(text[0]))) return std::nullopt;
  char* end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (end != text.c_str() + text.size()) return std::nullopt;
  return v;
}
}  // namespace detail

// Reads every --input argument; an argument without NAME=, with an empty name or file, a bad
// FACTOR, or a NAME given twice is an error (the last one silently winning would hide a typo).
// What follows a last '*' that is not a number is refused too when the file with it does not
// exist and the file before it does: FILE*1,5 or FILE*x2 is a mistyped factor, not a file.
inline InputArgs parse_input_args(const std::vector<std::string>& raw,
                                  std::string_view option = "--input") {
  namespace fs = std::filesystem;
  InputArgs out;
  for (const std::string& arg : raw) {
    const auto eq = arg.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == arg.size()) {
      out.error = std::string(option) + " wants NAME=FILE[:COLUMN][*FACTOR], got '" + arg + "'";
      return out;
    }
    InputArg a{arg.substr(0, eq), {}, {}, 1};
    std::string rest = arg.substr(eq + 1);
    const auto star = rest.rfind('*');
    const std::string tail = star == std::string::npos ? "" : rest.substr(star + 1);
    if (const auto f = star == std::string::npos ? std::nullopt : detail::number_syntax(tail)) {
      if (!io::scale_factor_valid(*f)) {
        out.error = std::string(option) + " " + arg + ": the scale factor after '*' must be " +
                    io::kScaleFactorRule + ", got '" + tail + "'";
        return out;
      }
      a.factor = *f;
      rest.resize(star);
      if (rest.empty()) {
        out.error = std::string(option) + " wants NAME=FILE[:COLUMN][*FACTOR], got '" + arg + "'";
        return out;
      }
    } else if (star != std::string::npos) {
      InputArg before;
      detail::split_column(rest.substr(0, star), before);
      detail::split_column(rest, a);
      std::error_code ec;
      if (!before.file.empty() && !fs::exists(a.file, ec) && fs::exists(before.file, ec)) {
        out.error = std::string(option) + " " + arg + ": '" + tail +
                    "' after the last '*' is not a number, and there is no file '" + a.file +
                    "' (FILE*FACTOR scales the record by FACTOR)";
        return out;
      }
    }
    detail::split_column(std::move(rest), a);
    for (const InputArg& earlier : out.args) {
      if (earlier.name == a.name) {
        out.error = std::string(option) + ": channel '" + a.name + "' is given twice ('" + a.name +
                    "=" + earlier.file + "' and '" + arg + "')";
        return out;
      }
    }
    out.args.push_back(std::move(a));
  }
  return out;
}

}  // namespace ntn::cli
