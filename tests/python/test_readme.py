# The README's Python example runs as printed, from the repository's root.
import os
import re
import subprocess
import sys

from conftest import DATA


def test_the_readme_s_python_example_runs():
    root = os.path.dirname(DATA)
    readme = open(os.path.join(root, "README.md")).read()
    section = readme.split("## Use it from Python", 1)[1]
    code = re.search(r"```python\n(.*?)```", section, re.S).group(1)
    environment = dict(os.environ, MPLBACKEND="Agg")  # matplotlib, if present, shows nothing
    done = subprocess.run([sys.executable, "-c", code], cwd=root, capture_output=True, text=True, timeout=300,
                          env=environment)
    assert done.returncode == 0, done.stderr
    assert re.search(r"h = 0\.00284: 3\d{4} of 35947 points converged", done.stdout), done.stdout
    assert re.search(r"tooth: \d{6} triangles, closed", done.stdout), done.stdout
