"""Shared fixtures: the `twoball` command line the Python results are compared with."""

import os
import shutil
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs the twoball command line (TWOBALL_BIN, else `twoball` on PATH) and returns
    (exit code, stdout, stderr)."""
    exe = os.environ.get("TWOBALL_BIN") or shutil.which("twoball")
    if not exe:
        pytest.skip("no twoball command line (set TWOBALL_BIN)")

    def run(*args, cwd=None):
        p = subprocess.run([exe, *args], capture_output=True, text=True, cwd=cwd)
        return p.returncode, p.stdout, p.stderr

    return run
