# SPDX-License-Identifier: MIT
"""The one shared-folder rule, written once per language (scripts/shared_dir.sh, cmake/SilkSharedDir.cmake,
export/silk_export/paths.py; the C++ tests get CMake's finding), gives the same answer in all three:
$SILK_SHARED_DIR when set, refused naming it when it is not a folder, else ../shared beside the
checkout, else beside the checkout it was cloned from, else an error naming the places looked in."""

from __future__ import annotations

import os
import shutil
import subprocess
from pathlib import Path

import pytest

from silk_export import paths

ROOT = Path(__file__).resolve().parents[2]


def env_with(shared: str | None) -> dict:
    env = {k: v for k, v in os.environ.items() if k != "SILK_SHARED_DIR"}
    if shared is not None:
        env["SILK_SHARED_DIR"] = shared
    return env


def by_shell(root: Path, shared: str | None) -> tuple[int, str]:
    p = subprocess.run(
        ["bash", "-c", "source scripts/shared_dir.sh && silk_shared_dir"],
        cwd=root,
        env=env_with(shared),
        capture_output=True,
        text=True,
    )
    return p.returncode, (p.stdout if p.returncode == 0 else p.stderr).strip()


def by_cmake(root: Path, shared: str | None, tmp_path: Path) -> tuple[bool, str]:
    """(warned, folder) of cmake/SilkSharedDir.cmake run as a script."""
    script = tmp_path / "find_shared.cmake"
    script.write_text(
        f'set(PROJECT_SOURCE_DIR "{root}")\ninclude("{root}/cmake/SilkSharedDir.cmake")\n'
        'silk_shared_dir(found)\nmessage(STATUS "FOUND=${found}")\n'
    )
    p = subprocess.run(["cmake", "-P", str(script)], env=env_with(shared), capture_output=True, text=True)
    found = next(line.split("FOUND=", 1)[1] for line in p.stdout.splitlines() if "FOUND=" in line)
    return "CMake Warning" in p.stderr, found


def by_python(root: Path, shared: str | None, monkeypatch) -> Path | None:
    monkeypatch.setattr(paths, "_checkout", lambda: root)
    if shared is None:
        monkeypatch.delenv("SILK_SHARED_DIR", raising=False)
    else:
        monkeypatch.setenv("SILK_SHARED_DIR", shared)
    return paths.shared_dir(required=True)


need_cmake = pytest.mark.skipif(shutil.which("cmake") is None, reason="cmake not installed")


@need_cmake
def test_the_variable_wins_in_every_language(tmp_path, monkeypatch):
    given = tmp_path / "elsewhere"
    given.mkdir()
    assert by_shell(ROOT, str(given)) == (0, str(given.resolve()))
    assert by_cmake(ROOT, str(given), tmp_path) == (False, str(given))
    assert by_python(ROOT, str(given), monkeypatch) == given.resolve()


@need_cmake
def test_a_variable_naming_no_folder_is_refused_naming_it(tmp_path, monkeypatch):
    missing = str(tmp_path / "missing")
    rc, message = by_shell(ROOT, missing)
    assert rc == 1 and f"SILK_SHARED_DIR={missing} is not a folder" in message
    assert by_cmake(ROOT, missing, tmp_path)[0]
    with pytest.raises(ValueError, match="is not a folder"):
        by_python(ROOT, missing, monkeypatch)


def fake_checkout(at: Path, origin: Path | None) -> Path:
    """A checkout holding the three copies of the rule (and git's remote.origin.url = origin)."""
    for rel in ("scripts/shared_dir.sh", "cmake/SilkSharedDir.cmake"):
        (at / rel).parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(ROOT / rel, at / rel)
    subprocess.run(["git", "init", "-q", str(at)], check=True)
    if origin is not None:
        subprocess.run(["git", "-C", str(at), "remote", "add", "origin", str(origin)], check=True)
    return at


@need_cmake
def test_beside_the_checkout_then_beside_its_origin_then_an_error(tmp_path, monkeypatch):
    if shutil.which("git") is None:
        pytest.skip("git not installed")
    # origin/ has ../shared with spec/ (tmp/a/shared); the clone (tmp/b/clone) has none beside it.
    origin = tmp_path / "a" / "origin"
    origin.mkdir(parents=True)
    (tmp_path / "a" / "shared" / "spec").mkdir(parents=True)
    clone = fake_checkout(tmp_path / "b" / "clone", origin)
    want = (tmp_path / "a" / "shared").resolve()
    assert by_shell(clone, None) == (0, str(want))
    warned, found = by_cmake(clone, None, tmp_path)
    assert not warned and Path(found).resolve() == want
    assert by_python(clone, None, monkeypatch) == want
    # A ../shared beside the checkout itself comes first.
    (tmp_path / "b" / "shared" / "spec").mkdir(parents=True)
    want = (tmp_path / "b" / "shared").resolve()
    assert by_shell(clone, None) == (0, str(want))
    assert Path(by_cmake(clone, None, tmp_path)[1]).resolve() == want
    assert by_python(clone, None, monkeypatch) == want
    # Neither: an error naming where it looked.
    lone = fake_checkout(tmp_path / "c" / "lone", None)
    rc, message = by_shell(lone, None)
    assert rc == 1 and "SILK_SHARED_DIR is not set" in message and str(lone) in message
    assert by_cmake(lone, None, tmp_path)[0]
    with pytest.raises(ValueError, match="SILK_SHARED_DIR is not set"):
        by_python(lone, None, monkeypatch)
