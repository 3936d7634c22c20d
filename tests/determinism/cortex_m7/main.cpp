// Bare-metal step loop for the determinism check on a Cortex-M7 (tests/determinism/cortex_m7):
// the kernel and one compiled model, no heap, no exceptions, no RTTI. init(), start(), then
// kSteps steps; the hash (FNV-1a 64 over the bytes of every step's outputs, then the final u and
// v) is printed. The same file is built for the host, so the two hashes can be compared.
// On the target, printing goes through newlib's semihosting (rdimon.specs); with NTN_NO_PRINT
// (and nosys.specs) it only stores the hash in g_hash, which gives the size of kernel + model.
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "ntn/kernel.hpp"
#include NTN_MODEL_HEADER

namespace {

namespace mdl = NTN_MODEL_NS;
constexpr ntn::Sizes kS = mdl::kSizes;
constexpr int kSteps = 20000;

ntn::Model<kS> g_model;
ntn::InitWorkspace<kS> g_init_work;  // init() works in it (static: no heap, little stack)
ntn::State<kS> g_state;
ntn::Scratch<kS> g_scratch;

struct Fnv1a64 {
  std::uint64_t h = 14695981039346656037ull;
  void add(const void* data, std::size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 1099511628211ull;
    }
  }
};

}  // namespace

volatile std::uint64_t g_hash = 0;  // kept for the nosys build, which prints nothing

int main() {
  if (!ntn::init(mdl::kSpec, g_model, g_init_work).ok()) return 1;
  // A fixed input: every channel at 1.0 for the first 100 steps, then 0 (none for a model
  // driven by its own loads, like the cantilever).
  std::array<double, kS.inputs> in{};
  for (auto& x : in)
    x = 1.0;
  Fnv1a64 hash;
  int status = static_cast<int>(ntn::start(g_model, g_state, g_scratch, in));
  for (int n = 0; n < kSteps; ++n) {
    if (n == 100) {
      for (auto& x : in)
        x = 0.0;
    }
    status |= static_cast<int>(ntn::step(g_model, g_state, g_scratch, in));
    hash.add(g_scratch.outputs.data(), sizeof g_scratch.outputs);
  }
  hash.add(g_state.u.data(), sizeof g_state.u);
  hash.add(g_state.v.data(), sizeof g_state.v);
  g_hash = hash.h;
#ifndef NTN_NO_PRINT
  // newlib's printf has no %a: the time step is printed as the bits of the double.
  std::uint64_t dt_bits = 0;
  std::memcpy(&dt_bits, &g_model.dt, sizeof dt_bits);
  std::printf("model %.*s dt-bits %016llx steps %d status %d hash %016llx\n",
              static_cast<int>(mdl::kName.size()), mdl::kName.data(),
              static_cast<unsigned long long>(dt_bits), kSteps, status,
              static_cast<unsigned long long>(hash.h));
#endif
  return status;
}
