#!/usr/bin/env bash
# Times the README's main command on a fresh clone: a clone of COMMIT (default HEAD) into
# a temporary folder with an empty target/, then
#   cargo run --release -p host-sim -- simulate host-sim/scenes/lift_hold.toml
# from the clone, build included. Crates already in cargo's registry cache are not
# downloaded again (`cargo fetch` first, untimed, so the figure is the build and the run,
# not the network). Prints one line: the commit, the seconds, the machine's cores.
#
#   bash scripts/first-run.sh            # this commit
#   bash scripts/first-run.sh 1815a73    # an older one, for comparison
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
commit="${1:-HEAD}"
dir="$(mktemp -d)"
trap 'rm -rf "$dir"' EXIT
git clone -q "$root" "$dir/clone"
git -C "$dir/clone" checkout -q "$commit"
cd "$dir/clone"
cargo fetch -q
start=$(date +%s.%N)
cargo run -q --release -p host-sim -- simulate host-sim/scenes/lift_hold.toml \
    --out "$dir/out" --quiet >/dev/null
end=$(date +%s.%N)
printf 'first run of %s: %.1f s on %s cores (%s)\n' \
    "$(git rev-parse --short HEAD)" "$(echo "$end - $start" | bc)" "$(nproc)" "$(uname -m)"
