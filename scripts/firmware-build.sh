#!/usr/bin/env bash
# Builds the firmware (firmware/) for the Cortex-M4F on plain stable: the toolchain pinned
# in firmware/rust-toolchain.toml and rustup's prebuilt `thumbv7em-none-eabihf` standard
# library (run scripts/firmware-setup.sh once first). Prints the path of each ELF it builds.
#
# Usage: scripts/firmware-build.sh [VARIANT ...]
#   VARIANT: default (FPU sqrt in the tick, f32 precomputation), soft-sqrt (libm's
#   software sqrt), fast-math (micromath's sqrt), precompute-f64, prebuilt-tables (the
#   default finger's table-mode tables, made by host-sim, linked in), sqrt-check (the
#   FPU square root against libm's over a sweep of inputs, then exit; see
#   host-sim/tests/qemu_sqrt.rs), defmt (the core's defmt logging with a sink logger,
#   to measure its flash cost; DEFMT_LOG sets the level compiled in, defmt's default is
#   error only), board (a real STM32F405/F407: clocks, USART1 pins and baud rate set at
#   start-up, TIM2 at the 16 MHz reset clock, the actuator's PWM on TIM3 channel 1, reset
#   instead of the emulator's exit; host-sim/tests/qemu_board.rs, qemu_pwm.rs),
#   solve-to-cap (the default with every Illinois solve run to its iteration cap: the
#   worst tick, measured by host-sim/tests/firmware_costs.rs).
#
# Fallback, only where rustup cannot install the target (firmware-setup.sh then installs
# Debian's rustc-web and its library source): `core` is built from source with
# `-Zbuild-std=core`, which needs RUSTC_BOOTSTRAP=1 for that sysroot build (the firmware's
# own code uses no unstable feature). SOFTGRIP_REQUIRE_STABLE=1 (as .ci/run sets it) makes
# that fallback an error instead.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
target=thumbv7em-none-eabihf
toolchain="$(sed -n 's/^channel *= *"\(.*\)"/\1/p' "$root/firmware/rust-toolchain.toml")"
variants=("$@")
[ ${#variants[@]} -eq 0 ] && variants=(default)

libdir="$(rustup run "$toolchain" rustc --print target-libdir --target "$target" 2>/dev/null || true)"
if [ -n "$libdir" ] && ls "$libdir"/libcore-*.rlib >/dev/null 2>&1; then
    how=stable
    cargo=(rustup run "$toolchain" cargo)
    dir="$root/target/firmware/build"
    echo "firmware-build: $(rustup run "$toolchain" rustc --version), prebuilt core for" \
        "$target (plain stable)" >&2
else
    if [ "${SOFTGRIP_REQUIRE_STABLE:-0}" = 1 ]; then
        echo "firmware-build: rustup has no $toolchain for $target (run scripts/firmware-setup.sh);" \
            "SOFTGRIP_REQUIRE_STABLE=1 refuses the build-std fallback" >&2
        exit 1
    fi
    how=build-std
    lld="$(rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin/rust-lld"
    cargo=(env PATH="/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1
        CARGO_TARGET_THUMBV7EM_NONE_EABIHF_LINKER="$lld" /usr/bin/cargo)
    dir="$root/target/firmware/build-std"
    echo "firmware-build: WARNING: no rustup target $target; building core with" \
        "Debian's $(/usr/bin/rustc --version) and -Zbuild-std (RUSTC_BOOTSTRAP=1)" >&2
fi

for v in "${variants[@]}"; do
    case "$v" in
        default) features="firmware" ;;
        fast-math) features="firmware,fast-math" ;;
        soft-sqrt) features="firmware,soft-sqrt" ;;
        sqrt-check) features="firmware,sqrt-check" ;;
        prebuilt-tables)
            features="firmware,prebuilt-tables"
            (cd "$root" && cargo run -q --release -p host-sim -- \
                tables --format rust --mode table --out "$root/target/firmware/tables" >&2)
            export SOFTGRIP_TABLES_RS="$root/target/firmware/tables/softgrip_tables.rs"
            ;;
        precompute-f64) features="firmware,precompute-f64" ;;
        board) features="firmware,board" ;;
        solve-to-cap) features="firmware,solve-to-cap" ;;
        defmt) features="firmware,defmt" ;;
        *) echo "unknown variant $v" >&2; exit 2 ;;
    esac
    # One target dir for every variant, so the dependencies are built once; each
    # variant's result is copied to target/firmware/VARIANT/.
    out="$root/target/firmware/$v"
    mkdir -p "$out"
    what=(-p softgrip-firmware --bin softgrip-firmware)
    std=()
    [ "$how" = build-std ] && std=(-Zbuild-std=core)
    (cd "$root" && "${cargo[@]}" build -q --profile firmware "${what[@]}" \
        --target "$target" "${std[@]}" --features "$features" --target-dir "$dir" >&2)
    cp "$dir/$target/firmware/softgrip-firmware" "$out/softgrip-firmware.elf"
    echo "$out/softgrip-firmware.elf"
done
