# SPDX-License-Identifier: MIT
"""silk_mesh's library loading per platform (_platform_libs, _library): onnxruntime loaded first,
by full path from libsilk's folder, and a failed load that names the file and the reason. Windows
Python is not available here, so the Windows cases run the same (pure Python) diagnosis on Linux
with real or crafted PE files; the real Windows load is checked under Wine by
scripts/test_windows.sh (silkgen.exe without onnxruntime.dll)."""

from __future__ import annotations

import os
import shutil
import struct
import subprocess
import sys
from pathlib import Path

import pytest

from silk_mesh import _platform_libs

ROOT = Path(__file__).resolve().parents[2]
WINDOWS_ORT = ROOT / ".deps" / "onnxruntime-windows" / "onnxruntime.dll"
LOAD = (
    "import silk_mesh\ntry:\n    silk_mesh.encode([])\nexcept silk_mesh.SilkError as e:\n"
    "    print(e.status, e.name, e.message)\n"
)


def fake_pe(path: Path, machine: int = 0x8664) -> Path:
    """The headers of a Windows DLL (MZ stub, "PE\\0\\0", the machine field) and nothing else."""
    data = bytearray(256)
    data[0:2] = b"MZ"
    struct.pack_into("<I", data, 0x3C, 0x80)
    data[0x80:0x84] = b"PE\0\0"
    struct.pack_into("<H", data, 0x84, machine)
    path.write_bytes(bytes(data))
    return path


def load_in_subprocess(library: Path) -> str:
    env = {**os.environ, "SILK_LIBRARY": str(library), "PYTHONPATH": str(ROOT / "bindings" / "python")}
    return subprocess.run([sys.executable, "-c", LOAD], env=env, capture_output=True, text=True, check=True).stdout


def test_a_windows_dll_given_to_linux_is_named_as_such(tmp_path):
    out = load_in_subprocess(fake_pe(tmp_path / "libsilk.dll"))
    assert out.startswith(f"2 library cannot load libsilk from '{tmp_path / 'libsilk.dll'}'"), out
    assert "wrong architecture: not a Linux library (a Windows PE file for x86-64)" in out, out


@pytest.mark.skipif(not WINDOWS_ORT.is_file(), reason="no .deps/onnxruntime-windows (scripts/setup_windows.sh)")
def test_the_real_onnxruntime_dll_is_a_windows_x64_library():
    assert _platform_libs.binary_kind(str(WINDOWS_ORT)) == ("PE", "x86-64")
    assert "wrong architecture: not a Linux library" in _platform_libs.diagnose(str(WINDOWS_ORT), plat="linux")
    assert _platform_libs.diagnose(str(WINDOWS_ORT), plat="win32", machine="x86-64") == ""


def test_a_library_for_another_machine_names_both_machines(tmp_path, lib_path):
    arm = tmp_path / "libsilk.so"
    data = bytearray(lib_path.read_bytes())
    struct.pack_into("<H", data, 18, 0xB7)  # e_machine: AArch64
    arm.write_bytes(bytes(data))
    out = load_in_subprocess(arm)
    assert f"wrong architecture: built for arm64, this Python is {_platform_libs.this_machine()}" in out, out
    arm_dll = fake_pe(tmp_path / "arm64.dll", machine=0xAA64)
    assert (
        _platform_libs.diagnose(str(arm_dll), plat="win32", machine="x86-64")
        == "wrong architecture: built for arm64, this Python is x86-64"
    )
    elf_on_windows = _platform_libs.diagnose(str(lib_path), plat="win32", machine="x86-64")
    assert elf_on_windows.startswith("wrong architecture: not a Windows library (a Linux ELF file"), elf_on_windows


def test_missing_and_non_library_files(tmp_path):
    assert _platform_libs.diagnose(str(tmp_path / "absent.dll"), plat="win32") == "file not found"
    text = tmp_path / "libsilk.so"
    text.write_text("not a library")
    assert _platform_libs.diagnose(str(text), plat="linux").startswith("not a library (no ELF, PE or Mach-O header)")


def test_a_missing_linux_dependency_is_named(tmp_path):
    cc = shutil.which("cc") or shutil.which("gcc")
    if not cc:
        pytest.skip("no C compiler")
    (tmp_path / "dep.c").write_text("int dep(void) { return 1; }\n")
    (tmp_path / "top.c").write_text("int dep(void);\nint top(void) { return dep(); }\n")
    subprocess.run([cc, "-shared", "-fPIC", "-o", str(tmp_path / "libsilkdep.so"), str(tmp_path / "dep.c")], check=True)
    subprocess.run(
        [
            cc,
            "-shared",
            "-fPIC",
            "-o",
            str(tmp_path / "libsilk.so"),
            str(tmp_path / "top.c"),
            f"-L{tmp_path}",
            "-lsilkdep",
        ],
        check=True,
    )
    (tmp_path / "libsilkdep.so").unlink()
    out = load_in_subprocess(tmp_path / "libsilk.so")
    assert "missing dependency: libsilkdep.so" in out, out


class _WinError(OSError):
    def __init__(self, winerror: int):
        super().__init__(f"[WinError {winerror}]")
        self.winerror = winerror


@pytest.mark.skipif(not WINDOWS_ORT.is_file(), reason="no .deps/onnxruntime-windows (scripts/setup_windows.sh)")
def test_windows_missing_dependency_names_the_dlls_from_the_import_table(tmp_path, monkeypatch):
    imports = _platform_libs.pe_imports(str(WINDOWS_ORT))
    assert {"KERNEL32.dll", "MSVCP140.dll", "VCRUNTIME140.dll"} <= set(imports), imports
    system = tmp_path / "Windows" / "System32"  # a Windows without the Visual C++ runtime
    system.mkdir(parents=True)
    for dll in imports:
        if not dll.upper().startswith(("MSVCP140", "VCRUNTIME140")):
            (system / dll).write_bytes(b"")
    monkeypatch.setenv("SystemRoot", str(tmp_path / "Windows"))
    why = _platform_libs.diagnose(str(WINDOWS_ORT), _WinError(126), plat="win32", machine="x86-64")
    assert why.startswith("missing dependency: MSVCP140.dll, VCRUNTIME140.dll"), why
    assert "vc_redist.x64.exe" in why and "KERNEL32" not in why


def test_windows_blocked_files(tmp_path):
    dll = fake_pe(tmp_path / "libsilk.dll")
    assert (
        _platform_libs.diagnose(str(dll), _WinError(4551), plat="win32", machine="x86-64")
        == "blocked: blocked by an application control policy"
    )
    assert _platform_libs.diagnose(str(dll), _WinError(5), plat="win32", machine="x86-64") == "blocked: access denied"


def test_platform_file_names():
    assert _platform_libs.library_pattern("win32") == "libsilk.dll"
    assert _platform_libs.dependency_patterns("win32") == ("onnxruntime.dll",)
    assert _platform_libs.library_pattern("linux") == "libsilk.so*"
    assert _platform_libs.dependency_patterns("linux") == ("libonnxruntime.so*",)


def test_onnxruntime_is_loaded_first_from_libsilks_own_folder(tmp_path, lib_path):
    """A folder like the add-on's silk_mesh/lib: onnxruntime there is the one loaded (by full
    path, before libsilk), and a broken one there is named, not silently replaced by another."""
    ort = next((p for p in sorted(lib_path.resolve().parent.glob("libonnxruntime.so*"))), None) or next(
        iter(sorted((ROOT / ".deps" / "onnxruntime").rglob("libonnxruntime.so.1*"))), None
    )
    if ort is None:
        pytest.skip("no libonnxruntime.so to copy")
    folder = tmp_path / "lib"
    folder.mkdir()
    shutil.copy(lib_path.resolve(), folder / "libsilk.so")
    shutil.copy(ort.resolve(), folder / "libonnxruntime.so.1")
    code = (
        "import silk_mesh\nsilk_mesh.load_library()\n"
        "print([l.split()[-1] for l in open('/proc/self/maps') if 'libonnxruntime' in l][0])\n"
    )
    env = {**os.environ, "SILK_LIBRARY": str(folder / "libsilk.so"), "PYTHONPATH": str(ROOT / "bindings" / "python")}
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True, check=True).stdout
    assert out.strip() == str(folder / "libonnxruntime.so.1")
    (folder / "libonnxruntime.so.1").write_text("broken")
    out = load_in_subprocess(folder / "libsilk.so")
    assert f"cannot load onnxruntime from '{folder / 'libonnxruntime.so.1'}' (needed by libsilk)" in out, out
    assert "not a library" in out, out
