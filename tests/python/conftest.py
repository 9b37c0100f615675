"""Shared fixtures of the Python module's tests (run by ctest: PYTHONPATH is the build tree's
package, TERRASTUDIO_EXE the built command line)."""

import os
import subprocess

import pytest


@pytest.fixture(scope="session")
def cli():
    """Runs the built terrastudio executable: cli(*args) -> CompletedProcess (text)."""
    exe = os.environ.get("TERRASTUDIO_EXE")
    if not exe:
        pytest.fail("TERRASTUDIO_EXE is not set (run the tests through ctest)")

    def run(*args):
        return subprocess.run([exe, *map(str, args)], capture_output=True, text=True,
                              env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})

    return run


@pytest.fixture(scope="session")
def resources():
    """The source tree's resources/ (presets, examples)."""
    return os.environ["TERRA_RESOURCE_DIR"]
