#!/usr/bin/env bash
# All the tests: the Rust workspace, then the Python package (python/) and its MuJoCo
# example under pytest, in a virtual environment .venv/ (made here if missing).
#
#   bash scripts/test.sh              # everything
#   SOFTGRIP_SKIP_CARGO=1 bash ...    # the Python part only
#
# SOFTGRIP_REQUIRE_QEMU and the other variables of `cargo test` pass through.
set -euo pipefail
cd "$(dirname "$0")/.."

# A failing cargo test does not stop the Python tests; the script fails if either does.
cargo_rc=0
if [ "${SOFTGRIP_SKIP_CARGO:-0}" != 1 ]; then
    cargo test --workspace --release || cargo_rc=$?
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
