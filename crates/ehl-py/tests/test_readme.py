"""The Python examples of the READMEs run as written (output folders moved to a temporary
folder)."""

import re
import subprocess
import sys

import pytest

from conftest import REPO


def python_blocks(path):
    text = path.read_text()
    return re.findall(r"```python\n(.*?)```", text, flags=re.S)


@pytest.mark.parametrize("readme", ["README.md", "crates/ehl-py/README.md"])
def test_readme_python_examples_run(readme, tmp_path):
    blocks = python_blocks(REPO / readme)
    assert blocks, f"{readme} has no python example"
    for code in blocks:
        code = code.replace('"out/', f'"{tmp_path}/')
        r = subprocess.run(
            [sys.executable, "-c", code], cwd=REPO, capture_output=True, text=True, timeout=300
        )
        assert r.returncode == 0, f"{readme}:\n{code}\n{r.stderr}"
    if readme == "README.md":
        assert len(python_blocks(REPO / readme)[0].strip().splitlines()) <= 10
        assert (tmp_path / "roller" / "summary.json").is_file()
