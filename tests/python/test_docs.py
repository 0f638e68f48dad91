"""The Python in the docs runs as printed: every ```python block of README.md and docs/python.md
(one namespace per file, run from the checkout; interactive >>> blocks are shown output, not run),
examples/python/drape.py writes its PNG, and examples/python/hanging_cloth.py runs."""

import os
import re
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR


def blocks(name):
    with open(os.path.join(SOURCE_DIR, name)) as handle:
        text = handle.read()
    return [b for b in re.findall(r"```python\n(.*?)```", text, re.S)
            if not b.lstrip().startswith(">>>")]


@pytest.mark.parametrize("name", ["README.md", "docs/python.md"])
def test_python_blocks_run(name, monkeypatch, capsys):
    found = blocks(name)
    assert found, f"no python block in {name}"
    monkeypatch.chdir(SOURCE_DIR)
    namespace = {}
    for code in found:
        exec(compile(code, name, "exec"), namespace)  # noqa: S102: our own documentation


def test_drape_example_writes_a_png(tmp_path):
    pytest.importorskip("matplotlib")
    png = tmp_path / "drape.png"
    drape = os.path.join(SOURCE_DIR, "examples", "python", "drape.py")
    run = subprocess.run([sys.executable, drape, "--frames", "40", "--iterations", "5", "--png",
                          str(png)],
                         capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stderr
    assert "961 points" in run.stdout
    with open(png, "rb") as handle:
        assert handle.read(8) == b"\x89PNG\r\n\x1a\n"


def test_hanging_cloth_example_runs():
    script = os.path.join(SOURCE_DIR, "examples", "python", "hanging_cloth.py")
    run = subprocess.run([sys.executable, script], capture_output=True, text=True, timeout=600)
    assert run.returncode == 0, run.stdout + run.stderr
    assert "600 points; lowest after 2 s:" in run.stdout
