"""Shared fixtures: the `radchain` executable built beside the module is the independent reference (its JSON and
CSV output, its error lines), and the bundled sensors are the inputs. ctest sets RADCHAIN_CLI and
RADCHAIN_SOURCE_DIR (python/CMakeLists.txt); run by hand:
    PYTHONPATH=<build>/python RADCHAIN_CLI=<build>/radchain /usr/bin/python3 -m pytest python/tests
"""
import json
import os
import subprocess
from pathlib import Path

import pytest

SOURCE_DIR = Path(os.environ.get("RADCHAIN_SOURCE_DIR", Path(__file__).resolve().parents[2]))
CLI = os.environ.get("RADCHAIN_CLI")


@pytest.fixture(scope="session")
def source_dir() -> Path:
    return SOURCE_DIR


@pytest.fixture(scope="session")
def sbv() -> str:
    return str(SOURCE_DIR / "sensors" / "msx-sbv.toml")


class Cli:
    def __init__(self, path):
        self.path = path

    def __call__(self, *args, check=True):
        done = subprocess.run([self.path, *map(str, args)], capture_output=True, text=True)
        if check and done.returncode not in (0, 1):
            raise AssertionError(f"radchain {' '.join(map(str, args))} exited {done.returncode}: {done.stderr}")
        return done

    def json(self, *args):
        return json.loads(self(*args).stdout)


@pytest.fixture(scope="session")
def cli() -> Cli:
    if not CLI or not Path(CLI).is_file():
        pytest.fail("RADCHAIN_CLI must name the radchain executable built with the module")
    return Cli(CLI)
