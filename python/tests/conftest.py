"""Shared paths and functions: the repository's test data and the `vericad` command line.

The command line is taken from ``VERICAD_CLI`` or, failing that, from the repository's
``target/{debug,release}/vericad``; tests that compare with it are skipped without it unless
``VERICAD_REQUIRE_CLI`` is set (as ``.ci/run`` does).
"""

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "tests" / "data"
PUBLIC = DATA / "public"
FAULTY = DATA / "faulty"
MALFORMED = DATA / "malformed"
YANG = REPO / "src" / "models" / "yang-table2.json"
SPHERE = PUBLIC / "gmsh-sphere_Rhino3D_default.igs"
PLANE = FAULTY / "plane-z0.step"


def _find_cli():
    env = os.environ.get("VERICAD_CLI")
    if env:
        return Path(env)
    for p in (REPO / "target" / "debug" / "vericad", REPO / "target" / "release" / "vericad"):
        if p.exists():
            return p
    return None


@pytest.fixture(scope="module")
def cli():
    """A function running the command line: cli(*args) -> CompletedProcess (text)."""
    exe = _find_cli()
    if exe is None or not exe.exists():
        if os.environ.get("VERICAD_REQUIRE_CLI"):
            pytest.fail(f"the vericad command line is required but not found ({exe})")
        pytest.skip("the vericad command line is not built")

    def run(*args, check=True):
        p = subprocess.run(
            [str(exe), *map(str, args)], cwd=REPO, capture_output=True, text=True
        )
        if check and p.returncode not in (0, 3):
            raise AssertionError(f"vericad {args}: exit {p.returncode}: {p.stderr}")
        return p

    return run


def cli_json(cli, *args):
    """The command's `--json` output, parsed."""
    return json.loads(cli(*args, "--json").stdout)


def plain(x):
    """Numpy arrays as lists, recursively (to compare with parsed JSON)."""
    if hasattr(x, "tolist"):
        return x.tolist()
    if isinstance(x, dict):
        return {k: plain(v) for k, v in x.items()}
    if isinstance(x, list):
        return [plain(v) for v in x]
    return x


def without(d, keys):
    """`d` without the given keys at any depth (time-dependent fields)."""
    if isinstance(d, dict):
        return {k: without(v, keys) for k, v in d.items() if k not in keys}
    if isinstance(d, list):
        return [without(v, keys) for v in d]
    return d
