"""What the package's tests share: the repository, the CLI built from it, and ../shared."""

import os
import subprocess
import sys
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SHARED = REPO.parent / "shared"

sys.path.insert(0, str(Path(__file__).parent))


def binary() -> Path:
    """The CLI the package is compared with: GLTFMAT_BIN, or the newest cargo build."""
    if "GLTFMAT_BIN" in os.environ:
        return Path(os.environ["GLTFMAT_BIN"])
    built = [REPO / "target" / kind / "gltfmat" for kind in ("release", "debug")]
    built = [b for b in built if b.exists()]
    if not built:
        pytest.fail("no gltfmat binary: run `cargo build` first, or set GLTFMAT_BIN")
    return max(built, key=lambda b: b.stat().st_mtime)


def cli(*args: str) -> str:
    """The CLI's standard output (any exit status: findings exit 1)."""
    result = subprocess.run([str(binary()), *args], capture_output=True, text=True, cwd=REPO)
    assert result.returncode in (0, 1), result.stderr
    return result.stdout


def shared(*parts: str) -> Path:
    """A path under ../shared: skipped loudly without it, a failure when CI is set."""
    path = SHARED.joinpath(*parts)
    if not path.exists():
        message = f"{path} is missing: the test needs ../shared beside the checkout"
        if os.environ.get("CI"):
            pytest.fail(message)
        print(f"SKIPPED LOUDLY: {message}", file=sys.stderr)
        pytest.skip(message)
    return path
