// The mode table (ntn::modal::mode_table).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ntn/modal/modal.hpp"

namespace ntn::modal {
namespace {

void append(std::string& s, const char* format, auto... args) {
  char buf[256];
  const int len = std::snprintf(buf, sizeof buf, format, args...);
  if (len > 0) s.append(buf, static_cast<std::size_t>(std::min<int>(len, sizeof buf - 1)));
}

const char* solver_name(Solver s) {
  switch (s) {
    case Solver::kDense:
      return "dense (Eigen SelfAdjointEigenSolver)";
    case Solver::kSparse:
      return "sparse (Spectra shift-invert Lanczos, sparse LDL^T)";
    case Solver::kAuto:
      break;
  }
  return "auto";
}

}  // namespace

std::string mode_table(const ModalResult& r) {
  std::string s;
  if (!r.ok()) {
    s += "modal analysis failed: " + r.error + "\n";
    return s;
  }
  append(s, "%d DOFs, %d coordinates after supports and rigid hinge directions (%d rigid trees),",
         r.dofs, r.coordinates, r.trees);
  append(s, " %d in the eigenproblem; solver %s\n", r.reduced, solver_name(r.solver));
  append(s, "%5s %11s %10s %8s | %7s %7s %7s | %7s %7s %7s\n", "mode", "f (Hz)", "T (s)", "zeta %",
         "Mx %", "My %", "Mz %", "sum x", "sum y", "sum z");
  double cum[3] = {0, 0, 0};
  for (int i = 0; i < r.modes(); ++i) {
    double frac[3];
    for (int d = 0; d < 3; ++d) {
      frac[d] = 100.0 * r.mass_fraction(i, d);
      cum[d] += frac[d];
    }
    append(s, "%5d %11.5g %10.5g %8.3g | %7.2f %7.2f %7.2f | %7.2f %7.2f %7.2f\n", i + 1,
           r.frequency(i), r.period(i), 100.0 * r.damping_ratio(i), frac[0], frac[1], frac[2],
           cum[0], cum[1], cum[2]);
  }
  append(s, "total mass free to move (kg): x %.6g, y %.6g, z %.6g\n", r.total_mass[0],
         r.total_mass[1], r.total_mass[2]);
  for (const std::string& note : r.notes)
    s += "note: " + note + "\n";
  return s;
}

void print_mode_table(std::FILE* out, const ModalResult& r) {
  const std::string s = mode_table(r);
  std::fwrite(s.data(), 1, s.size(), out);
}

}  // namespace ntn::modal
