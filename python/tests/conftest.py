"""Shared fixtures: the repository root and the Rust tools the tests compare against."""

import os
import subprocess
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]


def cargo(*args: str) -> None:
    """Runs cargo in the repository root (honours CARGO_TARGET_DIR)."""
    subprocess.run(["cargo", *args], cwd=ROOT, check=True)


def target_dir() -> Path:
    return Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))


@pytest.fixture(scope="session")
def cli() -> Path:
    """The release `scratchwave` CLI, built if needed."""
    cargo("build", "--release", "--quiet", "-p", "scratchwave-conformance", "--bin", "scratchwave")
    return target_dir() / "release" / "scratchwave"


@pytest.fixture(scope="session")
def c_example(tmp_path_factory) -> Path:
    """capi/examples/eval.c linked against the release static library."""
    cargo("build", "--release", "--quiet", "--lib", "-p", "scratchwave-capi")
    exe = tmp_path_factory.mktemp("c") / "eval"
    subprocess.run(
        [
            os.environ.get("CC", "cc"),
            "-O2",
            "-I",
            str(ROOT / "capi/include"),
            str(ROOT / "capi/examples/eval.c"),
            str(target_dir() / "release/libscratchwave_capi.a"),
            "-lpthread",
            "-ldl",
            "-lm",
            "-o",
            str(exe),
        ],
        check=True,
    )
    return exe
