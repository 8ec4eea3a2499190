#!/usr/bin/env bash
# The README's test command: every set-up step, then every test.
#
#   bash scripts/test.sh                  # set-up (idempotent), then the whole suite
#   SOFTGRIP_QUICK=1 bash scripts/test.sh # no firmware: its QEMU tests show as ignored
#   SOFTGRIP_SKIP_CARGO=1 bash ...        # the Python part only
#
# Set-up, each step skipped when already done (so a second run costs only the tests):
# 1. the firmware's pinned toolchain with the Cortex-M4F target, and QEMU unpacked into
#    .firmware/qemu (scripts/firmware-setup.sh);
# 2. the font of bench's PNG plots (scripts/fonts-setup.sh);
# 3. the firmware builds the QEMU tests boot (scripts/firmware-build.sh; cargo builds
#    incrementally, so an up-to-date ELF costs a few seconds);
# 4. the MSRV check: the core and host-sim build with the declared `rust-version`
#    (rustup installs that toolchain once, minimal profile);
# 5. the Python virtual environment .venv/ with the package built from python/.
# Then `cargo test --workspace --release` with SOFTGRIP_REQUIRE_QEMU=1 (a missing QEMU
# or ELF fails its tests instead of ignoring them), then pytest.
set -euo pipefail
cd "$(dirname "$0")/.."

quick="${SOFTGRIP_QUICK:-0}"
if [ "${SOFTGRIP_SKIP_CARGO:-0}" != 1 ]; then
    bash scripts/fonts-setup.sh
    if [ "$quick" != 1 ]; then
        bash scripts/firmware-setup.sh
        # The variants the QEMU tests boot (host-sim/build.rs lists them).
        SOFTGRIP_REQUIRE_STABLE=1 bash scripts/firmware-build.sh \
            default prebuilt-tables sqrt-check board solve-to-cap >/dev/null
        export SOFTGRIP_REQUIRE_QEMU=1
    else
        echo "SOFTGRIP_QUICK=1: no firmware set-up; the QEMU tests are ignored" >&2
        unset SOFTGRIP_REQUIRE_QEMU
    fi
    msrv="$(sed -n 's/^rust-version *= *"\(.*\)"/\1/p' Cargo.toml)"
    if [ "$quick" != 1 ]; then
        rustup toolchain list | grep -q "^$msrv" \
            || rustup toolchain install "$msrv" --profile minimal >&2
        echo "MSRV $msrv: cargo check of the core and host-sim" >&2
        cargo "+$msrv" check -q --locked -p softgrip -p host-sim --target-dir target/msrv
    fi
fi

# A failing cargo test does not stop the Python tests; the script fails if either does.
cargo_rc=0
if [ "${SOFTGRIP_SKIP_CARGO:-0}" != 1 ]; then
    cargo test --workspace --release || cargo_rc=$?
fi

if [ "${SOFTGRIP_SKIP_CARGO:-0}" != 1 ]; then
    # The defmt logging feature compiles (linking it needs a target logger: the firmware's).
    cargo check -q -p softgrip --lib --features defmt || cargo_rc=$?
    if [ "$quick" != 1 ]; then
        # The firmware's own lints, on its target (host builds of the workspace skip the
        # binary), and the defmt build, which links with a sink logger.
        SOFTGRIP_REQUIRE_STABLE=1 bash scripts/firmware-build.sh defmt >/dev/null
        toolchain="$(sed -n 's/^channel *= *"\(.*\)"/\1/p' firmware/rust-toolchain.toml)"
        for features in firmware firmware,soft-sqrt firmware,fast-math sqrt-check defmt \
            board solve-to-cap; do
            rustup run "$toolchain" cargo clippy -q -p softgrip-firmware \
                --target thumbv7em-none-eabihf --features "$features" \
                --target-dir target/firmware/build -- -D warnings || cargo_rc=$?
        done
        # Mutually exclusive variants refuse to build together (firmware/build.rs).
        for features in firmware,fast-math,soft-sqrt firmware,precompute-f64,prebuilt-tables \
            board,sqrt-check; do
            refusal="$(rustup run "$toolchain" cargo check -q -p softgrip-firmware \
                --target thumbv7em-none-eabihf --features "$features" \
                --target-dir target/firmware/build 2>&1 || true)"
            if grep -q "each pick" <<<"$refusal"; then
                echo "firmware: $features refused together, as it should be" >&2
            else
                echo "error: the firmware's features $features were not refused" >&2
                cargo_rc=1
            fi
        done
    fi
    # The README's tour, run as written: a simulated grasp on the default in-process link,
    # a limit-surface sweep, one required force, and a small benchmark over the pty.
    out="$(mktemp -d)"
    if cargo run -q --release -p host-sim -- simulate host-sim/scenes/lift_hold.toml \
        --out "$out" --quiet >/dev/null \
        && test -s "$out/summary.json" \
        && cargo run -q --release -p host-sim -- fls --format json --samples 16 >/dev/null \
        && cargo run -q --release -p host-sim -- required-force --ft 1 --mn 0.004 --mu 0.8 \
            --c 2.5e-3 --gamma 0.5 --mode table --format json >/dev/null \
        && cargo run -q --release -p host-sim -- bench --trials 5 --link pty --quiet \
            --out "$out/bench" >/dev/null \
        && test -s "$out/bench/bench.json" && test -s "$out/bench/pareto-shake.png"; then
        echo "README tour: ok" >&2
    else
        echo "error: a README tour command failed" >&2
        cargo_rc=1
    fi
    rm -rf "$out"
fi

# The Python tests compare with the CLI's JSON: build it (incremental, release).
cargo build --release -p host-sim

py_start=$(date +%s)
PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet maturin numpy pytest mujoco matplotlib
.venv/bin/python -m pip install --quiet ./python
set +e
.venv/bin/python -m pytest python/tests -q -p no:cacheprovider
rc=$?
set -e
echo "python tests: $(( $(date +%s) - py_start )) s"
if [ "$rc" -eq 5 ]; then
    echo "error: pytest collected no tests" >&2
    rc=1
fi
if [ "$cargo_rc" -ne 0 ]; then
    echo "error: cargo test --workspace --release failed (exit $cargo_rc)" >&2
    exit "$cargo_rc"
fi
exit "$rc"
