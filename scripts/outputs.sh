#!/usr/bin/env bash
# scripts/outputs.sh BIN OUTDIR: what host-sim writes, for checking that a refactor leaves
# it bit-identical: simulate --all against every controller (direct link), two bench runs,
# the tables in every format, required-force and fls. Timing fields (wall-clock costs,
# real-time factors, cost shares) and a run's provenance (its commit, and whether the
# sources were committed) are stripped, since they differ run to run.
#
#   git worktree add /tmp/base REV && (cd /tmp/base && cargo build --release -p host-sim)
#   scripts/outputs.sh /tmp/base/target/release/host-sim /tmp/out-base
#   cargo build --release -p host-sim && scripts/outputs.sh target/release/host-sim /tmp/out
#   diff -r /tmp/out-base /tmp/out    # prints nothing when the outputs are the same
set -euo pipefail
BIN=$(realpath "$1"); OUT=$2; rm -rf "$OUT"; mkdir -p "$OUT"
S="$(cd "$(dirname "$0")/.." && pwd)/host-sim/scenes"
"$BIN" simulate --all --controller all --link direct --scenes $S --out "$OUT/sim" --quiet > "$OUT/sim.stdout"
"$BIN" bench --trials 12 --seed 17 --out "$OUT/bench" --quiet > "$OUT/bench.stdout"
"$BIN" bench --trials 6 --seed 5 --family twist --controller all --out "$OUT/bench2" --quiet > "$OUT/bench2.stdout"
for f in rust bin csv; do "$BIN" tables --format $f --out "$OUT/tables-$f" > "$OUT/tables-$f.stdout"; done
"$BIN" tables --format rust --finger $S/lift_hold.toml --mode ellipse --out "$OUT/tables-ell" > "$OUT/tables-ell.stdout"
"$BIN" required-force --help > /dev/null
"$BIN" required-force --ft 1.0 --mn 0.01 --mu 0.8 --c 2.5e-3 --gamma 0.5 > "$OUT/rf1.stdout" 2>&1 || true
"$BIN" required-force --ft 1.0 --mn 0.01 --mu 0.8 --c 2.5e-3 --gamma 0.5 --format json > "$OUT/rf2.stdout" 2>&1 || true
"$BIN" fls --format json > "$OUT/fls.stdout" 2>&1 || true
# timing fields differ run to run
find "$OUT" -name '*.json' | while read f; do python3 - "$f" <<'PY'
import json,sys,re
p=sys.argv[1]
def strip(o):
    if isinstance(o,dict): return {k:strip(v) for k,v in o.items() if not re.search(r'(^provenance$|wall|elapsed|_s_per|per_tick_s|seconds|real_time|rtf|speed|_ns$|_step_s$|_link_s$|cost|share)',k)}
    if isinstance(o,list): return [strip(v) for v in o]
    return o
try:
    d=json.load(open(p)); json.dump(strip(d),open(p,'w'),indent=1,sort_keys=True)
except Exception as e: print("nonjson",p,e)
PY
done
sed -i -E '/real-time factor|^wrote /d' "$OUT"/*.stdout
