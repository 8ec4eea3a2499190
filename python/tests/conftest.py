"""Shared fixtures: the host-sim binary (built once, release) for the CLI comparisons."""

import os
import pathlib
import subprocess

import pytest

REPO = pathlib.Path(__file__).resolve().parents[2]


@pytest.fixture(scope="session")
def host_sim() -> pathlib.Path:
    """``target/release/host-sim``, built with cargo if missing or if SOFTGRIP_BUILD_HOST_SIM=1."""
    exe = REPO / "target" / "release" / "host-sim"
    if not exe.exists() or os.environ.get("SOFTGRIP_BUILD_HOST_SIM") == "1":
        subprocess.run(
            ["cargo", "build", "--release", "-p", "host-sim"], cwd=REPO, check=True
        )
    return exe
