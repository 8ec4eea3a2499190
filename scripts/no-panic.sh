#!/usr/bin/env bash
# Machine check that no panic is reachable from the paths that face the world.
#
# 1. Builds nopanic/ (its own workspace) in release with fat LTO and one codegen unit. Every
#    wrapper in nopanic/src/main.rs is marked #[no_panic] (the `no-panic` crate): the link
#    fails, naming the wrapper, unless the optimiser proved that no panic can unwind out of
#    it. The wrappers cover the controller's tick (f32 with libm and micromath, f64), the
#    pure rule, Controller::new, the frame decoder (requests and replies), the encoder,
#    table-blob parsing with the controller built from it, and the device loop (handle,
#    poll).
# 2. For the wrappers that fail, builds the same binary without the attributes
#    (`--features scan`) and prints, with scripts/panic-paths.py, every panic entry point
#    their call graph reaches and its source location.
#
# Exit status: 0 when every wrapper that must be proven is (all but KNOWN, which is empty
# today: every wrapper, the device loop's included, is proven), 1 otherwise.
# Wrappers in KNOWN are expected to fail (see docs/testing.md, "No panic on the
# paths that face the world"): they are reported, and a KNOWN wrapper that starts passing
# is pointed out so it can be promoted.
#
# Limits: the proof holds for this x86-64 host build with the release profile (overflow
# checks off, as in the firmware profile); it is not a proof for thumbv7em (same source,
# other optimiser decisions), nor for debug builds, where integer overflow checks add panic
# paths (index arithmetic in src/controller/capacity.rs). Run with
# CARGO_PROFILE_RELEASE_OVERFLOW_CHECKS=true to see those.
#
#   bash scripts/no-panic.sh
set -euo pipefail
cd "$(dirname "$0")/.."
KNOWN=""
base="${CARGO_TARGET_DIR:-target}"
log="$(mktemp)"
trap 'rm -f "$log"' EXIT

failed=""
if cargo build --release --manifest-path nopanic/Cargo.toml --target-dir "$base/nopanic" \
    2>"$log"; then
    "$base/nopanic/release/softgrip-nopanic" >/dev/null
else
    failed="$(grep -o 'detected panic in function `[^`]*`' "$log" | sed 's/.*`\(.*\)`/\1/' | sort -u || true)"
    if [ -z "$failed" ]; then
        cat "$log" >&2
        echo "no-panic: the build failed for another reason" >&2
        exit 1
    fi
fi

wrappers="$(grep -A4 'no_panic)\]' nopanic/src/main.rs | grep -o 'fn [a-z0-9_]*' | sed 's/fn //' | sort -u)"
status=0
for w in $wrappers; do
    if echo "$failed" | grep -qx "$w"; then
        if echo " $KNOWN " | grep -q " $w "; then
            echo "not proven (known): $w"
        else
            echo "NOT PROVEN: $w" >&2
            status=1
        fi
    else
        echo "proven panic-free: $w"
        if echo " $KNOWN " | grep -q " $w "; then
            echo "  ($w is in KNOWN but now passes: remove it from KNOWN)"
        fi
    fi
done

if [ -n "$failed" ]; then
    echo
    echo "Remaining panic paths (build without the attributes, walk the call graph):"
    cargo build --release --features scan --manifest-path nopanic/Cargo.toml \
        --target-dir "$base/nopanic-scan" 2>/dev/null
    roots=""
    for w in $failed; do roots="$roots softgrip_nopanic::$w"; done
    # shellcheck disable=SC2086
    python3 scripts/panic-paths.py "$base/nopanic-scan/release/softgrip-nopanic" $roots |
        sed -e 's/::h[0-9a-f]\{16\}//g' -e 's/\[[0-9a-f]\{16\}\]//g' \
            -e 's#/[^ ]*/registry/src/[^/]*/##' || true
fi
exit $status
