// Minimal Cortex-M7 start-up for tests/determinism/cortex_m7: the vector table (initial stack
// pointer and reset handler) and a reset handler that turns the FPU on (CPACR: full access to
// CP10 and CP11) before newlib's _start (crt0) sets up .data/.bss and calls main.
#include <cstdint>

extern "C" {
extern std::uint32_t __stack_top;  // linker script
void _start();                     // newlib crt0
[[noreturn]] void ntn_reset();
[[noreturn]] void ntn_fault() {
  for (;;) {
  }
}
}

[[noreturn]] void ntn_reset() {
  volatile std::uint32_t& cpacr = *reinterpret_cast<volatile std::uint32_t*>(0xE000ED88u);
  cpacr = cpacr | (0xFu << 20);
  asm volatile("dsb\n\tisb" ::: "memory");
  _start();
  for (;;) {
  }
}

using Handler = void (*)();
__attribute__((section(".isr_vector"), used))
const Handler g_vectors[16] = {reinterpret_cast<Handler>(&__stack_top),
                               ntn_reset,
                               ntn_fault,
                               ntn_fault,
                               ntn_fault,
                               ntn_fault,
                               ntn_fault,
                               nullptr,
                               nullptr,
                               nullptr,
                               nullptr,
                               ntn_fault,
                               ntn_fault,
                               nullptr,
                               ntn_fault,
                               ntn_fault};
