# SPDX-License-Identifier: MIT
"""Which native libraries this platform loads (libsilk and its onnxruntime dependency, by file
name) and, when one will not load, why: the file is missing, is not a library of this system (an
ELF library given to Windows, a DLL given to Linux), was built for another architecture (the ELF /
PE / Mach-O machine field against this Python's), is blocked (Windows' application control or
antivirus, a file marked as downloaded, no read permission), or a library it needs is missing
(named from the loader's message, or from the DLL's import table). Pure Python: the checks run
on any platform, so tests on Linux cover the Windows diagnosis with fake files."""

from __future__ import annotations

import os
import platform
import struct
import sys

# sys.platform prefix -> (libsilk file name pattern, onnxruntime file name patterns, format,
# the name the system loader is asked for when no file is found).
_PLATFORMS = {
    "win32": ("libsilk.dll", ("onnxruntime.dll",), "PE", "libsilk.dll"),
    "linux": ("libsilk.so*", ("libonnxruntime.so*",), "ELF", "libsilk.so"),
    "darwin": ("libsilk*.dylib", ("libonnxruntime*.dylib",), "Mach-O", "libsilk.dylib"),
}
_SYSTEM_NAMES = {"PE": "Windows", "ELF": "Linux", "Mach-O": "macOS"}
_ELF_MACHINES = {0x3E: "x86-64", 0xB7: "arm64", 0x03: "x86", 0x28: "arm"}
_PE_MACHINES = {0x8664: "x86-64", 0xAA64: "arm64", 0x014C: "x86", 0x01C4: "arm"}
_MACHO_CPUS = {0x01000007: "x86-64", 0x0100000C: "arm64", 7: "x86", 12: "arm"}
# Windows LoadLibrary errors that mean "not allowed" rather than "broken": access denied, blocked
# by group policy, virus detected / potentially unwanted, application control (WDAC, Smart App Control).
_WIN_BLOCKED = {
    5: "access denied",
    1260: "blocked by group policy",
    225: "flagged by antivirus",
    226: "flagged by antivirus",
    4551: "blocked by an application control policy",
    4556: "blocked by an application control policy",
}
_WIN_MOD_NOT_FOUND, _WIN_BAD_FORMAT = 126, 193


def _key(plat: str | None = None) -> str:
    plat = plat or sys.platform
    return next((k for k in _PLATFORMS if plat.startswith(k)), "linux")


def library_pattern(plat: str | None = None) -> str:
    """libsilk's file name (glob pattern) on `plat` (default: this one)."""
    return _PLATFORMS[_key(plat)][0]


def library_name(plat: str | None = None) -> str:
    """libsilk's plain file name on `plat`: what the system loader is asked for as a last resort."""
    return _PLATFORMS[_key(plat)][3]


# libsilk_ops, onnxruntime's custom-op library of the ai.silk kernels (engine/kernels), as CMake
# names it on each platform; it lies beside libsilk.
_OPS_NAMES = {"win32": "libsilk_ops.dll", "linux": "libsilk_ops.so", "darwin": "libsilk_ops.dylib"}


def ops_library_name(plat: str | None = None) -> str:
    """libsilk_ops' file name on `plat` (default: this one)."""
    return _OPS_NAMES[_key(plat)]


def dependency_patterns(plat: str | None = None) -> tuple[str, ...]:
    """onnxruntime's file names (glob patterns), loaded first from libsilk's folder."""
    return _PLATFORMS[_key(plat)][1]


def this_machine() -> str:
    """This Python's architecture as the machine fields name it ("x86-64", "arm64", ...)."""
    m = platform.machine().lower()
    bits64 = struct.calcsize("P") == 8
    if m in ("x86_64", "amd64", "x64", "i386", "i686", "x86"):
        return "x86-64" if bits64 else "x86"
    if m in ("aarch64", "arm64", "armv8l"):
        return "arm64" if bits64 else "arm"
    return m


def binary_kind(path: str) -> tuple[str, str] | None:
    """(format, machine) from a file's header: ("ELF", "x86-64"), ("PE", "arm64"), ("Mach-O",
    "universal"), ...; None for a file that is none of them."""
    with open(path, "rb") as f:
        head = f.read(64)
        if head[:4] == b"\x7fELF" and len(head) >= 20:
            endian = "<" if head[5] == 1 else ">"
            m = struct.unpack_from(endian + "H", head, 18)[0]
            return "ELF", _ELF_MACHINES.get(m, f"machine 0x{m:x}")
        if head[:2] == b"MZ" and len(head) >= 64:
            f.seek(struct.unpack_from("<I", head, 0x3C)[0])
            pe = f.read(6)
            if pe[:4] == b"PE\0\0" and len(pe) == 6:
                m = struct.unpack_from("<H", pe, 4)[0]
                return "PE", _PE_MACHINES.get(m, f"machine 0x{m:x}")
            return "PE", "unknown (no PE header)"
        if head[:4] in (b"\xca\xfe\xba\xbe", b"\xbe\xba\xfe\xca"):
            return "Mach-O", "universal"
        if head[:4] in (b"\xcf\xfa\xed\xfe", b"\xce\xfa\xed\xfe"):
            cpu = struct.unpack_from("<I", head, 4)[0]
            return "Mach-O", _MACHO_CPUS.get(cpu, f"cpu 0x{cpu:x}")
    return None


def pe_imports(path: str) -> list[str]:
    """The DLL names a PE file imports (its import directory); [] when it cannot be read."""
    try:
        with open(path, "rb") as f:
            data = f.read()
        pe = struct.unpack_from("<I", data, 0x3C)[0]
        n_sections, opt_size = struct.unpack_from("<H", data, pe + 6)[0], struct.unpack_from("<H", data, pe + 20)[0]
        opt = pe + 24
        magic = struct.unpack_from("<H", data, opt)[0]
        import_rva = struct.unpack_from("<I", data, opt + (120 if magic == 0x20B else 104))[0]
        sections = [struct.unpack_from("<II4xI", data, opt + opt_size + 40 * i + 8) for i in range(n_sections)]

        def offset(rva: int) -> int:
            for size, va, raw in sections:
                if va <= rva < va + max(size, 1):
                    return rva - va + raw
            raise ValueError("rva outside the sections")

        names, at = [], offset(import_rva)
        while True:
            name_rva = struct.unpack_from("<I", data, at + 12)[0]
            if name_rva == 0:
                return names
            start = offset(name_rva)
            names.append(data[start : data.index(b"\0", start)].decode("ascii", "replace"))
            at += 20
    except (OSError, ValueError, struct.error, IndexError):
        return []


def _missing_windows_imports(path: str) -> list[str]:
    """Imported DLLs found neither beside `path` nor in the system folder (API sets excepted)."""
    folder = os.path.dirname(os.path.abspath(path))
    system = os.path.join(os.environ.get("SystemRoot", r"C:\Windows"), "System32")
    return [
        d
        for d in pe_imports(path)
        if not d.lower().startswith(("api-ms-", "ext-ms-"))
        and not any(os.path.isfile(os.path.join(p, d)) for p in (folder, system))
    ]


def _blocked_mark(path: str) -> str:
    """Windows: ' (marked as downloaded from the internet: unblock it in its Properties or with
    PowerShell Unblock-File)' when the file carries a Zone.Identifier stream, else ''."""
    if not sys.platform.startswith("win"):
        return ""
    try:
        with open(path + ":Zone.Identifier", "rb"):
            return " (marked as downloaded from the internet: unblock it in its Properties or with PowerShell Unblock-File)"
    except OSError:
        return ""


def diagnose(path: str, error: OSError | None = None, plat: str | None = None, machine: str | None = None) -> str:
    """Why `path` does not load here (or on `plat`/`machine`), in words; `error` is the loader's."""
    fmt = _PLATFORMS[_key(plat)][2]
    machine = machine or this_machine()
    if not os.path.exists(path):
        return "file not found"
    if os.path.isdir(path):
        return "is a folder, not a library"
    try:
        kind = binary_kind(path)
    except PermissionError:
        return "blocked: no permission to read the file"
    except OSError as e:
        return f"cannot read the file ({e.strerror or e})"
    if kind is None:
        return f"not a library (no ELF, PE or Mach-O header): not a {_SYSTEM_NAMES[fmt]} library"
    if kind[0] != fmt:
        return (
            f"wrong architecture: not a {_SYSTEM_NAMES[fmt]} library (a {_SYSTEM_NAMES[kind[0]]} "
            f"{kind[0]} file for {kind[1]}); use the {_SYSTEM_NAMES[fmt].lower()} build"
        )
    if kind[1] not in (machine, "universal"):
        return f"wrong architecture: built for {kind[1]}, this Python is {machine}"
    winerror = getattr(error, "winerror", None)
    if winerror in _WIN_BLOCKED:
        return f"blocked: {_WIN_BLOCKED[winerror]}{_blocked_mark(path)}"
    if winerror == _WIN_MOD_NOT_FOUND:
        missing = _missing_windows_imports(path)
        hint = (
            " (the Microsoft Visual C++ 2015-2022 runtime: install vc_redist.x64.exe)"
            if any(d.lower().startswith(("msvcp140", "vcruntime140")) for d in missing)
            else ""
        )
        return (
            ("missing dependency: " + ", ".join(missing) + hint)
            if missing
            else "missing dependency (a library it needs was not found)"
        )
    text = str(error or "")
    base = os.path.basename(path)
    if ": cannot open shared object file" in text:
        dep = text.split(": cannot open shared object file")[0].rsplit(": ", 1)[-1].strip()
        if dep and os.path.basename(dep) != base:
            return f"missing dependency: {dep}"
    if isinstance(error, PermissionError) or "Permission denied" in text:
        return "blocked: no permission to load the file" + _blocked_mark(path)
    return ""
