#!/usr/bin/env bash
# Builds the firmware for the Cortex-M4F with Debian's rustc and build-std (run
# scripts/firmware-setup.sh once first). Prints the path of each ELF it builds.
#
# Usage: scripts/firmware-build.sh [VARIANT ...]
#   VARIANT: default (FPU sqrt in the tick, f32 precomputation), soft-sqrt (libm's
#   software sqrt), fast-math (micromath's sqrt), precompute-f64, prebuilt-tables (the
#   default finger's table-mode tables, made by host-sim, linked in), defmt
#   (the defmt build is compiled and linked only to show it builds; it has no logger).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
lld="$(rustc --print sysroot)/lib/rustlib/x86_64-unknown-linux-gnu/bin/rust-lld"
host_path="$PATH"
host_rustc="$(command -v rustc)"
export PATH="/usr/bin:$PATH" RUSTC=/usr/bin/rustc RUSTC_BOOTSTRAP=1
export CARGO_TARGET_THUMBV7EM_NONE_EABIHF_LINKER="$lld"
variants=("$@")
[ ${#variants[@]} -eq 0 ] && variants=(default)
for v in "${variants[@]}"; do
    case "$v" in
        default) features="firmware" ;;
        fast-math) features="firmware,fast-math" ;;
        soft-sqrt) features="firmware,soft-sqrt" ;;
        prebuilt-tables)
            features="firmware,prebuilt-tables"
            # Host tools with rustup's toolchain, before PATH puts Debian's first.
            (cd "$root" && PATH="$host_path" RUSTC="$host_rustc" cargo run -q --release -p host-sim -- \
                tables --format rust --mode table --out "$root/target/firmware/tables" >&2)
            export SOFTGRIP_TABLES_RS="$root/target/firmware/tables/softgrip_tables.rs"
            ;;
        precompute-f64) features="firmware,precompute-f64" ;;
        defmt) features="defmt" ;;
        *) echo "unknown variant $v" >&2; exit 2 ;;
    esac
    # One target dir for every variant, so core is built once; each variant's result is
    # copied to target/firmware/VARIANT/.
    dir="$root/target/firmware/build"
    out="$root/target/firmware/$v"
    mkdir -p "$out"
    # The defmt variant builds the library only: linking a binary with defmt needs a
    # global logger (a transport such as defmt-rtt), which the emulator setup has none of.
    what=(-p softgrip-firmware --bin softgrip-firmware)
    [ "$v" = defmt ] && what=(-p softgrip --lib)
    (cd "$root" && /usr/bin/cargo build -q --profile firmware "${what[@]}" \
        --target thumbv7em-none-eabihf -Zbuild-std=core --features "$features" \
        --target-dir "$dir" >&2)
    if [ "$v" = defmt ]; then
        cp "$dir/thumbv7em-none-eabihf/firmware/libsoftgrip.rlib" "$out/"
        echo "$out/libsoftgrip.rlib"
    else
        cp "$dir/thumbv7em-none-eabihf/firmware/softgrip-firmware" "$out/softgrip-firmware.elf"
        echo "$out/softgrip-firmware.elf"
    fi
done
