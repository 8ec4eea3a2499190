#!/usr/bin/env bash
# Runs every fuzz target (fuzz/, cargo-fuzz with libFuzzer on the nightly toolchain) for a
# set time each, from its committed seeds, and prints per target: executions, seconds,
# executions per second, corpus size and findings (crash, leak or timeout artifacts).
#
#   bash scripts/fuzz.sh [SECONDS_PER_TARGET] [TARGET ...]     # default 300 s, every target
#
# Installs what it needs when it is missing: rustup's nightly toolchain (libFuzzer needs
# -Zsanitizer) and cargo-fuzz (from crates.io). Targets run one after the other, each on
# one core (libFuzzer's default), so the times add up. The corpus grows in fuzz/corpus/
# (ignored by git) and is reused by the next run; findings land in fuzz/artifacts/TARGET/.
# Exit status 1 when any target has a finding, 0 otherwise.
#
# FUZZ_SANITIZER chooses cargo-fuzz's sanitizer: `none` (the default) or `address`. The
# targets call safe Rust only (the core's one `unsafe`, the VSQRT instruction, is built for
# ARM alone), so AddressSanitizer finds nothing Rust's own checks would miss; without it
# the targets run about twice as fast (`config`: 365 against 186 executions per second).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
seconds="${1:-300}"
sanitizer="${FUZZ_SANITIZER:-none}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(frame_decoder config device device_loop scene)

if ! rustup toolchain list | grep -q '^nightly'; then
    rustup toolchain install nightly --profile minimal
fi
if ! cargo +nightly fuzz --version >/dev/null 2>&1; then
    cargo install cargo-fuzz
fi

seeds_of() {
    case "$1" in
        scene) echo "$root/host-sim/scenes" ;;
        device_loop) echo "$root/fuzz/seeds/device" ;;
        *) echo "$root/fuzz/seeds/$1" ;;
    esac
}

cd "$root/fuzz"
found=0
printf '%-14s %12s %8s %10s %8s %s\n' target executions seconds "exec/s" corpus findings
for t in "${targets[@]}"; do
    mkdir -p "corpus/$t" "artifacts/$t"
    before="$(find "artifacts/$t" -type f | wc -l)"
    log="$(mktemp)"
    set +e
    cargo +nightly fuzz run -O --sanitizer "$sanitizer" "$t" "corpus/$t" "$(seeds_of "$t")" -- \
        -max_total_time="$seconds" -print_final_stats=1 \
        -artifact_prefix="artifacts/$t/" >"$log" 2>&1
    rc=$?
    set -e
    # A run that ends early (a crash, an interrupt) has no "Done" line: `|| true` keeps
    # `set -e` from ending the script before it prints the row.
    runs="$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' | tail -n 1 || true)"
    secs="$(grep -o 'Done [0-9]* runs in [0-9]* second' "$log" | grep -o 'in [0-9]*' | grep -o '[0-9]*' | tail -n 1 || true)"
    corpus="$(find "corpus/$t" -type f | wc -l)"
    after="$(find "artifacts/$t" -type f | wc -l)"
    new=$((after - before))
    if [ "$rc" -ne 0 ] || [ "$new" -gt 0 ]; then
        found=1
        tail -n 30 "$log" >&2
    fi
    runs="${runs:-0}"
    secs="${secs:-$seconds}"
    rate=$((runs / (secs > 0 ? secs : 1)))
    printf '%-14s %12s %8s %10s %8s %s\n' "$t" "$runs" "$secs" "$rate" "$corpus" \
        "$new (exit $rc)"
    rm -f "$log"
done
exit "$found"
