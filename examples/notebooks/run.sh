#!/usr/bin/env bash
# Executes the notebooks of this folder top to bottom and saves them with their outputs.
# Makes a virtual environment (target/nb-venv) with the ehl package built from this checkout
# and matplotlib, scipy, nbclient, ipykernel, tqdm. Takes a few minutes; not part of ./test.sh.
# Usage: examples/notebooks/run.sh [NOTEBOOK.ipynb ...]   (default: all)
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
cd "$root"
venv=target/nb-venv
if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "./crates/ehl-py[notebooks]"
if [ $# -eq 0 ]; then
    set -- examples/notebooks/*.ipynb
fi
for nb in "$@"; do
    echo "executing $nb"
    start=$(date +%s)
    "$venv/bin/python" - "$nb" <<'PY'
import os, sys
import nbformat
from nbclient import NotebookClient

path = sys.argv[1]
nb = nbformat.read(path, as_version=4)
NotebookClient(nb, timeout=1200, kernel_name="python3",
               resources={"metadata": {"path": os.path.dirname(os.path.abspath(path))}}).execute()
nbformat.write(nb, path)
PY
    echo "  done in $(( $(date +%s) - start )) s"
done
