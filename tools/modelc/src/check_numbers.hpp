// The check of a quantity the kernel derives from the input numbers, shared by the stages of
// check_numbers.cpp.
#pragma once

#include <string>
#include <vector>

#include "diagnostic_sink.hpp"

namespace ntn::modelc::compile {

// --- Numbers beyond double ---
//
// Every input number is finite, but what the kernel derives from them (E A / l, 12 E I / l^3,
// rho A l / 2, k / m, ...) can still overflow to inf or underflow to zero or a subnormal, and
// then fail far from its cause ("a spring acts on a DOF without mass" for E = 1e308). A derived
// quantity is checked as the kernel computes it, and refused naming the input that drives it
// out of range the most: the factor with the largest power x log10(value), towards overflow or
// underflow.
struct Factor {
  std::string name;  // "E", "A", "l"
  double value = 0;
  int power = 1;
  Where at;
  std::string unit;
};

// True when v is finite (and, with `normal`, at least the smallest normal double); otherwise one
// error at the factor that drives v out of range the most, naming every factor.
bool check_derived(DiagnosticSink& L, double v, const std::string& what,
                   const std::vector<Factor>& f, bool normal);

}  // namespace ntn::modelc::compile
