"""docs/python.md: every ```python example runs, in a folder holding shot.toml and its grid."""
import os
import re
import subprocess
import sys

import pytest

import mirage

DOC = os.path.join(os.environ.get("MIRAGE_SOURCE_DIR", os.path.join(os.path.dirname(__file__),
                                                                      "..", "..")),
                   "docs", "python.md")
EXAMPLES = re.findall(r"```python\n(.*?)```", open(DOC).read(), re.S)


def test_the_page_has_examples():
    assert len(EXAMPLES) >= 3


@pytest.mark.parametrize("index", range(len(EXAMPLES)))
def test_example_runs(fog_dir, index):
    # The package this test imported, wherever the example runs.
    env = dict(os.environ, PYTHONPATH=os.path.dirname(os.path.dirname(mirage.__file__)))
    r = subprocess.run([sys.executable, "-c", EXAMPLES[index]], cwd=fog_dir, env=env,
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, f"example {index}:\n{EXAMPLES[index]}\n{r.stderr}"
