// Where a problem is in the model file, and the sink that collects every error and note of one
// load. The reader records places as it reads (Where); the compile stages report through the same
// sink, so every message of the compiler leaves through DiagnosticSink::take_errors / take_notes.
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "ntn/modelc/diagnostic.hpp"

namespace ntn::modelc::compile {

// A place in the file and the key it belongs to, kept for checks made after reading: line and
// column as the TOML parser gave them (1-based; 0 where there is no place, reported at 1:1).
struct Where {
  int line = 0;
  int column = 0;
  std::string key;
};

// The diagnostics sink: every error and note goes through add(), which keeps the first
// kShownPerKind of each kind (severity and key with the array indices taken out: every
// "nodes[i].id" error is one kind) and counts the rest; take_errors() / take_notes() end each
// capped kind with one summary note. A million unconnected nodes give 50 errors and one line
// "999950 more ...", not 238 MB.
constexpr std::size_t kShownPerKind = 50;
// At most this many errors (and notes) are kept in all, whatever their kinds: 300 000 unknown
// keys are 300 000 kinds, and each kept message costs about 800 bytes. The rest are counted.
constexpr std::size_t kShownInAll = 500;

// "nodes[12].id" -> "nodes[].id": the kind of a key.
std::string kind_key(const std::string& key);

class DiagnosticSink {
 public:
  explicit DiagnosticSink(std::string file) : file_(std::move(file)) {}

  void error(const Where& w, std::string message);
  void error_at_start(const std::string& key, std::string message);
  void note(const Where& w, std::string message);
  // A diagnostic made elsewhere (the size and nesting limits, limits.cpp), counted and capped
  // like the others.
  void add(Diagnostic d);

  std::vector<Diagnostic> take_notes() { return take(notes_, Severity::kNote); }
  bool failed() const { return error_count_ > 0; }
  std::size_t error_count() const { return error_count_; }
  std::vector<Diagnostic> take_errors() { return take(errors_, Severity::kError); }

 private:
  struct Kind {
    std::size_t shown = 0, hidden = 0;
    Diagnostic first_hidden;
  };
  // Sorted by place, each capped kind summarized at its first diagnostic left out.
  std::vector<Diagnostic> take(std::vector<Diagnostic>& v, Severity severity);

  std::string file_;
  std::vector<Diagnostic> errors_;
  std::vector<Diagnostic> notes_;
  std::map<std::string, Kind> kinds_;
  std::size_t error_count_ = 0;
  struct Overflow {
    std::size_t count = 0;
    Diagnostic first;
  };
  Overflow overflow_[2];  // errors, notes past kShownInAll
};

}  // namespace ntn::modelc::compile
