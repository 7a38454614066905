"""Shared fixtures: the repository's examples and the `ehl` program to compare with."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[3]
EXAMPLES = REPO / "examples"


def example(name: str) -> Path:
    return EXAMPLES / name


def cli_binary() -> Path:
    """The `ehl` program: $EHL_CLI, else the newest of target/{debug,release}/ehl (`cargo test
    --workspace` builds target/debug/ehl), else built with `cargo build --release`."""
    env = os.environ.get("EHL_CLI")
    if env:
        return Path(env)
    found = [p for p in (REPO / "target/debug/ehl", REPO / "target/release/ehl") if p.is_file()]
    if found:
        return max(found, key=lambda p: p.stat().st_mtime)
    cargo = shutil.which("cargo")
    if cargo is None:
        pytest.skip("no ehl program and no cargo to build it")
    subprocess.run([cargo, "build", "--release", "-p", "ehl-cli"], cwd=REPO, check=True)
    return REPO / "target/release/ehl"


@pytest.fixture(scope="session")
def cli() -> Path:
    return cli_binary()
