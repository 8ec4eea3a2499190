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

if [ "${SOFTGRIP_SKIP_CARGO:-0}" != 1 ]; then
    cargo test --workspace --release
fi

# The Python tests compare with the CLI's JSON: build it (incremental, release).
cargo build --release -p host-sim

py_start=$(date +%s)
PYTHON="${PYTHON:-python3}"
if [ ! -x .venv/bin/python ]; then
    "$PYTHON" -m venv .venv
fi
.venv/bin/python -m pip install --quiet --upgrade pip
.venv/bin/python -m pip install --quiet maturin numpy pytest mujoco matplotlib
.venv/bin/python -m pip install --quiet ./python
set +e
.venv/bin/python -m pytest python/tests -q -p no:cacheprovider
rc=$?
set -e
echo "python tests: $(( $(date +%s) - py_start )) s"
if [ "$rc" -eq 5 ]; then
    echo "error: pytest collected no tests" >&2
    exit 1
fi
exit "$rc"
