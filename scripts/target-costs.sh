#!/usr/bin/env bash
# Instruction counts, flash and RAM of the firmware variants on the emulated Cortex-M4F
# (QEMU netduinoplus2, -icount shift=0, TIM2): runs two scenes in both modes against each
# variant over the QEMU link and prints the `target` object of each summary.json.
# Needs scripts/firmware-setup.sh and scripts/firmware-build.sh VARIANT... first.
#
# Usage: scripts/target-costs.sh [VARIANT ...]   (default: default soft-sqrt fast-math
#                                                 precompute-f64)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
variants=("$@")
[ ${#variants[@]} -eq 0 ] && variants=(default soft-sqrt fast-math precompute-f64)
cargo build -q --release -p host-sim --manifest-path "$root/Cargo.toml"
for v in "${variants[@]}"; do
    out="$(mktemp -d)"
    "$root/target/release/host-sim" simulate --all --scenes "$root/host-sim/scenes" \
        --controller softgrip,softgrip-table --link qemu \
        --firmware "$root/target/firmware/$v/softgrip-firmware.elf" --out "$out" >/dev/null
    python3 - "$v" "$out/summary.json" <<'PY'
import json, sys
v, path = sys.argv[1], sys.argv[2]
t = json.load(open(path))["target"]
ticks = ", ".join(f"{m} {s['min']:.0f}/{s['median']:.0f}/{s['max']:.0f}"
                  for m, s in t["tick_instructions"].items())
boot = ", ".join(f"{m} {n:.0f}" for m, n in t["startup_instructions_by_mode"].items())
print(f"{v}: start-up [{boot}]; tick min/median/max [{ticks}]; "
      f"flash {t['flash_bytes']} B; RAM {t['static_ram_bytes']} B static + "
      f"{t['stack_peak_bytes']:.0f} B stack peak")
PY
    rm -rf "$out"
done
