// SIGINT and SIGTERM during a run: the handler only records the signal; a run loop given
// &g_stop_signal (LoopConfig::stop) ends after the frame it is in, and the program finishes its
// files, prints its summary and exits 4. Shared by ntn-hil and ntn-run.
#pragma once

#include <csignal>

namespace ntn::hil {

inline volatile std::sig_atomic_t g_stop_signal = 0;  // the signal that asked to stop, or 0

}  // namespace ntn::hil

extern "C" inline void ntn_on_stop_signal(int signal) {
  ntn::hil::g_stop_signal = signal;
}

namespace ntn::hil {

// From here on SIGINT and SIGTERM set g_stop_signal instead of ending the program.
inline void catch_stop_signals() {
  struct sigaction action {};
  action.sa_handler = ntn_on_stop_signal;
  sigemptyset(&action.sa_mask);
  (void)sigaction(SIGINT, &action, nullptr);
  (void)sigaction(SIGTERM, &action, nullptr);
}

// "SIGINT", "SIGTERM", or "" when no signal asked to stop.
inline const char* stop_signal_name() {
  return g_stop_signal == SIGINT ? "SIGINT" : g_stop_signal == SIGTERM ? "SIGTERM" : "";
}

}  // namespace ntn::hil
