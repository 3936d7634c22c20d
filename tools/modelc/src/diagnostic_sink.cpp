#include "diagnostic_sink.hpp"

#include <algorithm>
#include <utility>

namespace ntn::modelc::compile {

std::string kind_key(const std::string& key) {
  std::string k;
  for (std::size_t i = 0; i < key.size(); ++i) {
    k += key[i];
    if (key[i] != '[') continue;
    std::size_t j = i + 1;
    while (j < key.size() && key[j] >= '0' && key[j] <= '9')
      ++j;
    if (j > i + 1 && j < key.size() && key[j] == ']') i = j - 1;
  }
  return k;
}

void DiagnosticSink::error(const Where& w, std::string message) {
  add({file_, std::max(1, w.line), std::max(1, w.column), w.key, std::move(message)});
}

void DiagnosticSink::error_at_start(const std::string& key, std::string message) {
  add({file_, 1, 1, key, std::move(message)});
}

void DiagnosticSink::note(const Where& w, std::string message) {
  add({file_, std::max(1, w.line), std::max(1, w.column), w.key, std::move(message),
       Severity::kNote});
}

void DiagnosticSink::add(Diagnostic d) {
  const bool is_error = d.severity == Severity::kError;
  if (is_error) ++error_count_;
  if ((is_error ? errors_ : notes_).size() >= kShownInAll) {
    Overflow& o = overflow_[is_error ? 0 : 1];
    // The earliest in the file, whatever order the tables are read in.
    if (o.count++ == 0 || d.line < o.first.line ||
        (d.line == o.first.line && d.column < o.first.column))
      o.first = std::move(d);
    return;
  }
  Kind& k = kinds_[std::string(is_error ? "e" : "n") + kind_key(d.key)];
  if (k.shown < kShownPerKind) {
    ++k.shown;
    (is_error ? errors_ : notes_).push_back(std::move(d));
  } else if (k.hidden++ == 0) {
    k.first_hidden = std::move(d);
  }
}

std::vector<Diagnostic> DiagnosticSink::take(std::vector<Diagnostic>& v, Severity severity) {
  for (const auto& [name, k] : kinds_) {
    if (k.hidden == 0 || k.first_hidden.severity != severity) continue;
    const std::string what = severity == Severity::kError ? " error" : " note";
    v.push_back({file_, k.first_hidden.line, k.first_hidden.column, kind_key(k.first_hidden.key),
                 "... and " + std::to_string(k.hidden) + " more" + what +
                     (k.hidden == 1 ? "" : "s") +
                     " of this kind (this key, any index), the first of them here: only the "
                     "first " +
                     std::to_string(kShownPerKind) + " of each kind are listed",
                 Severity::kNote});
  }
  if (const Overflow& o = overflow_[severity == Severity::kError ? 0 : 1]; o.count > 0) {
    const std::string what = severity == Severity::kError ? " error" : " note";
    v.push_back({file_, o.first.line, o.first.column, o.first.key,
                 "... and " + std::to_string(o.count) + " more" + what + (o.count == 1 ? "" : "s") +
                     " not listed, the first of them here: only the first " +
                     std::to_string(kShownInAll) + what + "s are listed",
                 Severity::kNote});
  }
  std::stable_sort(v.begin(), v.end(), [](const Diagnostic& a, const Diagnostic& b) {
    return a.line != b.line ? a.line < b.line : a.column < b.column;
  });
  return std::move(v);
}

}  // namespace ntn::modelc::compile
