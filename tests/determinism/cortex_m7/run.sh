#!/usr/bin/env bash
# run.sh: the kernel and one model on a bare-metal Cortex-M7 with double-precision FPU.
# Compiles MODEL with ntn-modelc, builds main.cpp for the host (g++) and for the Cortex-M7
# (arm-none-eabi-g++, -mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard, -fno-exceptions
# -fno-rtti -ffp-contract=off), reports flash and RAM (arm-none-eabi-size) of the build without
# printf (nosys.specs) and of the one with semihosting (rdimon.specs), runs the latter under
# qemu-system-arm -M mps2-an500 and compares its line (time step bits, status, hash) with the
# host's.
#   run.sh SOURCE_DIR NTN_MODELC MODEL.toml NAME WORK
# Exits 77 (CTest SKIP_RETURN_CODE) when arm-none-eabi-g++ or qemu-system-arm is missing.
set -euo pipefail
src=$1 modelc=$2 model=$3 name=$4 work=$5
for tool in arm-none-eabi-g++ qemu-system-arm; do
  if ! command -v "$tool" >/dev/null; then
    echo "SKIP: $tool not installed (apt-get install gcc-arm-none-eabi libnewlib-arm-none-eabi"
    echo "      libstdc++-arm-none-eabi-newlib qemu-system-arm)"
    exit 77
  fi
done
here=$src/tests/determinism/cortex_m7
mkdir -p "$work"
"$modelc" "$model" -o "$work/${name}_model.hpp" --name "$name"
common=(-std=c++20 -O2 -ffp-contract=off -fno-exceptions -fno-rtti -I"$src/kernel/include"
        -isystem /usr/include/eigen3 -I"$work" "-DNTN_MODEL_HEADER=\"${name}_model.hpp\""
        "-DNTN_MODEL_NS=ntn::models::$name")
# (no NTN_SIMD: the Cortex-M7 build keeps the scalar element and DOF passes)
kernel_src=("$src/kernel/src/time_step.cpp" "$src/kernel/src/constraint_forest.cpp"
            "$src/kernel/src/element_pass.cpp" "$src/kernel/src/dof_pass.cpp")
m7=(-mcpu=cortex-m7 -mfpu=fpv5-d16 -mfloat-abi=hard -mthumb -ffunction-sections -fdata-sections
    -Wno-psabi -T "$here/cortex_m7.ld" -Wl,--gc-sections)

g++ "${common[@]}" "$here/main.cpp" "${kernel_src[@]}" -o "$work/host"
arm-none-eabi-g++ "${common[@]}" "${m7[@]}" -DNTN_NO_PRINT "$here/main.cpp" "$here/startup.cpp" "${kernel_src[@]}" \
  --specs=nosys.specs -o "$work/m7-noprint.elf"
arm-none-eabi-g++ "${common[@]}" "${m7[@]}" "$here/main.cpp" "$here/startup.cpp" "${kernel_src[@]}" \
  --specs=rdimon.specs -o "$work/m7-semihosting.elf"
echo "sizes (flash = text + data, RAM = data + bss; stack and heap not included):"
arm-none-eabi-size "$work/m7-noprint.elf" "$work/m7-semihosting.elf"

host=$("$work/host")
target=$(timeout 300 qemu-system-arm -M mps2-an500 -cpu cortex-m7 -nographic -monitor none \
  -semihosting-config enable=on,target=native -kernel "$work/m7-semihosting.elf")
echo "x86-64:    $host"
echo "cortex-m7: $target"
if [ "$host" = "$target" ]; then
  echo "Cortex-M7 (qemu) and x86-64 give the same bits"
else
  echo "FAIL: Cortex-M7 and x86-64 differ"
  exit 1
fi
