"""``.ci/run`` leaves no virtual environment behind, whether it succeeds or fails."""

import os
import shutil
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

# A stand-in for python3: `-m venv DIR` makes a venv whose `python` records its arguments and
# exits with $FAKE_EXIT, so the script runs its steps without installing anything.
FAKE_PYTHON3 = """#!/bin/sh
if [ "$1" = "-m" ] && [ "$2" = "venv" ]; then
    mkdir -p "$3/bin"
    printf 'PATH="%s/bin:$PATH"\\n' "$3" > "$3/bin/activate"
    printf '#!/bin/sh\\necho "$@" >> "$CALLS"\\nexit ${FAKE_EXIT:-0}\\n' > "$3/bin/python"
    chmod +x "$3/bin/python"
    head -c 1000000 /dev/zero > "$3/bin/ballast"
    exit 0
fi
exit 99
"""


@pytest.mark.skipif(shutil.which("bash") is None, reason="needs bash")
@pytest.mark.parametrize("exit_code", [0, 1])
def test_ci_removes_its_virtual_environment(exit_code, tmp_path):
    bin_dir, temp = tmp_path / "bin", tmp_path / "tmp"
    bin_dir.mkdir()
    temp.mkdir()
    fake = bin_dir / "python3"
    fake.write_text(FAKE_PYTHON3)
    fake.chmod(0o755)
    calls = tmp_path / "calls"
    env = {**os.environ, "PATH": f"{bin_dir}:{os.environ['PATH']}", "TMPDIR": str(temp),
           "CALLS": str(calls), "FAKE_EXIT": str(exit_code)}
    done = subprocess.run(["bash", str(ROOT / ".ci" / "run")], env=env, capture_output=True,
                          text=True, check=False)
    assert done.returncode == exit_code, done.stderr
    assert list(temp.iterdir()) == []
    steps = calls.read_text().splitlines()
    if exit_code == 0:
        assert steps[-3:] == ["-m pip install --quiet .[dev]",
                              "-m ruff check continuation groove_model", "-m mypy"]
        assert "-m pytest" in steps
