"""Shared fixtures: the shipped models, the CLI (the independent reference most tests compare with), and
OpenSim's example data in ../shared/data/opensim where it is present (tests needing it skip otherwise).
ctest sets SINEW_CLI, SINEW_SOURCE_DIR and SINEW_SHARED_DIR, and PYTHONPATH to the module in the build tree."""
import os
import pathlib
import subprocess

import pytest

import sinew

SOURCE_DIR = pathlib.Path(os.environ.get("SINEW_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
SHARED_DIR = pathlib.Path(os.environ.get("SINEW_SHARED_DIR", SOURCE_DIR.parent / "shared"))
ARM26_YAML = SOURCE_DIR / "models" / "arm26.yaml"
WHOLE_BODY_YAML = SOURCE_DIR / "models" / "whole_body" / "whole_body.yaml"
OPENSIM_ARM26 = SHARED_DIR / "data" / "opensim" / "arm26"
OPENSIM_GAIT2354 = SHARED_DIR / "data" / "opensim" / "gait2354"


def run_cli(*args):
    """Runs the sinew command-line tool; returns its standard output, failing the test on a non-zero exit."""
    cli = os.environ.get("SINEW_CLI")
    if not cli:
        pytest.fail("SINEW_CLI is not set (ctest sets it to build/bin/sinew)")
    done = subprocess.run([cli, *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, f"sinew {' '.join(map(str, args))} failed:\n{done.stdout}\n{done.stderr}"
    return done.stdout


@pytest.fixture(scope="session")
def arm26():
    return sinew.load_model(str(ARM26_YAML))


@pytest.fixture(scope="session")
def whole_body():
    return sinew.load_model(str(WHOLE_BODY_YAML))


@pytest.fixture(scope="session")
def opensim_arm26():
    if not (OPENSIM_ARM26 / "arm26.osim").exists():
        pytest.skip("../shared/data/opensim/arm26 is absent (sinew's developer data)")
    return OPENSIM_ARM26
