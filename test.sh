#!/usr/bin/env bash
# The whole test suite, what CI runs (.ci/run): the Rust tests, then the Python package's
# tests (crates/ehl-py/tests) in a virtual environment made here, target/py-venv, with the
# package built from this checkout by `pip install ./crates/ehl-py` (maturin, release build
# into crates/ehl-py/target). Needs python3 (3.9 or later) with venv, and PyPI for numpy,
# pytest, tqdm and maturin.
set -euo pipefail
cd "$(dirname "$0")"
cargo test --workspace
venv=target/py-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "./crates/ehl-py[test]"
# the program the parity tests compare with: the one `cargo test --workspace` just built
EHL_CLI="$PWD/target/debug/ehl" "$venv/bin/python" -m pytest -q -rs crates/ehl-py/tests
