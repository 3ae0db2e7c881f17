"""The example in docs/python.md runs as written, from the repository root (its own asserts check J against
finite differences and the dynamics round trip)."""
import os
import re
import subprocess
import sys

from conftest import SOURCE_DIR


def test_docs_example_runs():
    text = (SOURCE_DIR / "docs" / "python.md").read_text()
    blocks = re.findall(r"```python\n(.*?)```", text, re.S)
    assert len(blocks) == 1
    # the module's folder made absolute, since the example runs from the repository root
    path = os.pathsep.join(os.path.abspath(p) for p in os.environ.get("PYTHONPATH", "").split(os.pathsep) if p)
    done = subprocess.run([sys.executable, "-c", blocks[0]], cwd=SOURCE_DIR, capture_output=True, text=True,
                          env={**os.environ, "PYTHONPATH": path})
    assert done.returncode == 0, done.stdout + done.stderr
    assert "sinew.Error:" in done.stdout and "no_such_model.yaml" in done.stdout
