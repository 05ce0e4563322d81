# SPDX-License-Identifier: MIT
"""Finding and loading libsilk, and its one error type: SilkError(status, message) with the
library's own message (silk_last_error), also raised when the library cannot be loaded.

Search order (the first that exists is loaded; a failed load names the file, the OS's reason and
the diagnosis of _platform_libs: missing dependency, wrong architecture, blocked file):
load_library(path) before the first call, else $SILK_LIBRARY, else the package's own folder
(silk_mesh/lib/libsilk.so*, libsilk.dll on Windows: the pip wheel, the add-on), else a build tree
when the package runs from a checkout (<repo>/build/engine/libsilk.so, else the newest
<repo>/build*/engine/libsilk.so), else the system loader ("libsilk.so"). onnxruntime is loaded
first, by full path (never from PATH or a system copy): the copy in libsilk's folder (the add-on,
the Windows zip), else the onnxruntime package's own library (the wheel)."""

from __future__ import annotations

import ctypes
import glob
import importlib.util
import os
import threading

from . import _capi, _platform_libs

PACKAGE_DIR = os.path.dirname(os.path.realpath(__file__))  # realpath: export/silk_mesh is a link to this folder
# bindings/python/silk_mesh -> the repository root, when this is a checkout (silk.h beside it).
_CHECKOUT = os.path.dirname(os.path.dirname(os.path.dirname(PACKAGE_DIR)))


class SilkError(RuntimeError):
    """A libsilk call failed. `status` is the silk_status code (SILK_ERR_* in this module), `name`
    its name ("refused", ...), `message` the library's message. For a refused mesh (status
    SILK_ERR_REFUSED) `reason` is the named refusal ("mobius", ...), else None. A library that
    cannot be loaded raises it too, with status SILK_ERR_IO and name "library"."""

    def __init__(self, status: int, message: str, name: str | None = None):
        super().__init__(f"{name}: {message}" if name else message)
        self.status, self.message, self.name = int(status), message, name

    @property
    def reason(self) -> str | None:
        if self.status != _capi.SILK_ERR_REFUSED:
            return None
        return self.message.split(":", 1)[0].strip()


_lock = threading.Lock()
_loaded: tuple[str, ctypes.CDLL] | None = None
_dependencies: list[ctypes.CDLL] = []  # kept loaded for libsilk's lifetime
_NAME = _platform_libs.library_name()


def library_candidates() -> list[str]:
    """The files tried, in order, when no library is loaded yet (see the module's docstring)."""
    env = os.environ.get("SILK_LIBRARY")
    if env:
        return [env]
    out = sorted(glob.glob(os.path.join(PACKAGE_DIR, "lib", _platform_libs.library_pattern())), key=len)
    if os.path.isfile(os.path.join(_CHECKOUT, "engine", "include", "silk", "silk.h")):
        first = os.path.join(_CHECKOUT, "build", "engine", _NAME)
        others = [p for p in glob.glob(os.path.join(_CHECKOUT, "build*", "engine", _NAME)) if p != first]
        others.sort(key=os.path.getmtime, reverse=True)
        out += ([first] if os.path.exists(first) else []) + others
    return out + [_NAME]


def _first_candidate() -> str:
    """$SILK_LIBRARY as given (a missing file fails naming it), else the first that exists."""
    cands = library_candidates()
    if os.environ.get("SILK_LIBRARY"):
        return cands[0]
    return next(p for p in cands if p == _NAME or os.path.exists(p))


def _load_dependencies(path: str) -> None:
    """onnxruntime from libsilk's own folder, by full path, before libsilk (a missing one is fine:
    the build tree's libsilk finds it through its RPATH)."""
    if os.path.basename(path) == path:
        return
    folder = os.path.dirname(os.path.abspath(path))
    for pattern in _platform_libs.dependency_patterns():
        found = sorted(glob.glob(os.path.join(folder, pattern)), key=len)
        if not found:
            continue
        try:
            _dependencies.append(ctypes.CDLL(found[0]))
        except OSError as e:
            why = _platform_libs.diagnose(found[0], e)
            raise SilkError(
                _capi.SILK_ERR_IO,
                f"cannot load onnxruntime from '{found[0]}' (needed by libsilk): {e}" + (f"; {why}" if why else ""),
                "library",
            ) from e


def _open(path: str) -> ctypes.CDLL:
    _load_dependencies(path)
    try:
        handle = ctypes.CDLL(path)
    except OSError as e:
        hint = (
            f"set SILK_LIBRARY to the path of {_NAME}, or build it (scripts/build.sh)"
            if path == _NAME
            else f"check the file, or set SILK_LIBRARY to another {_NAME}"
        )
        why = _platform_libs.diagnose(path, e) if path != _NAME else ""
        raise SilkError(
            _capi.SILK_ERR_IO,
            f"cannot load libsilk from '{path}': {e}; " + (f"{why}; " if why else "") + hint,
            "library",
        ) from e
    try:
        _capi.declare(handle)
    except AttributeError as e:
        raise SilkError(_capi.SILK_ERR_IO, f"'{path}' is not a matching libsilk: {e}", "library") from e
    return handle


def load_library(path: str | os.PathLike | None = None) -> ctypes.CDLL:
    """Loads libsilk: `path` (a full path), or the first candidate that exists. Once per process:
    a later call with another path raises SilkError (objects would mix two libraries)."""
    global _loaded
    with _lock:
        if _loaded is not None:
            if path is not None and os.path.abspath(os.fspath(path)) != os.path.abspath(_loaded[0]):
                raise SilkError(
                    _capi.SILK_ERR_INVALID_ARGUMENT,
                    f"libsilk is already loaded from '{_loaded[0]}'; "
                    f"load_library('{os.fspath(path)}') must come before the first call",
                    "library",
                )
            return _loaded[1]
        chosen = os.fspath(path) if path is not None else _first_candidate()
        _loaded = (chosen, _open(chosen))
        return _loaded[1]


def lib() -> ctypes.CDLL:
    """The loaded library (loaded on first use)."""
    return _loaded[1] if _loaded is not None else load_library()


def library_path() -> str:
    """The file libsilk was (or would be) loaded from."""
    return _loaded[0] if _loaded is not None else _first_candidate()


def onnxruntime_library() -> str | None:
    """The onnxruntime package's C library (onnxruntime/capi/libonnxruntime.so.<version>), located
    through importlib without importing onnxruntime; None when the package or the file is absent.
    Looked up afresh on every call (import caches dropped): a package installed after a failed
    Model() is found by the next one, as libsilk's own loader retries (issue 35)."""
    importlib.invalidate_caches()
    spec = importlib.util.find_spec("onnxruntime")
    for folder in (spec.submodule_search_locations or []) if spec else []:
        found = sorted(glob.glob(os.path.join(folder, "capi", "libonnxruntime.so.*")), key=len)
        if found:
            return found[-1]
    return None


_onnxruntime: ctypes.CDLL | None = None


def preload_onnxruntime() -> None:
    """Before the first model: the pip wheel's libsilk (silk_mesh/lib/ with no onnxruntime beside it)
    loads onnxruntime itself and takes one already in the process first, so this loads the onnxruntime
    package's library by the full path importlib gives (also when that package lives in another
    site-packages). Elsewhere (a build tree, the add-on) libsilk is linked to its own: nothing done.
    No package found: nothing either; libsilk's own lookup then names the file it tried."""
    global _onnxruntime
    own = os.path.join(PACKAGE_DIR, "lib")
    if (
        _onnxruntime is not None
        or os.path.dirname(os.path.abspath(library_path())) != own
        or glob.glob(os.path.join(own, "libonnxruntime*"))
    ):
        return
    path = onnxruntime_library()
    if path is None:
        return
    try:
        _onnxruntime = ctypes.CDLL(path)
    except OSError as e:
        raise SilkError(
            _capi.SILK_ERR_IO,
            f"cannot load onnxruntime from '{path}' (the onnxruntime package, found by importlib): {e}",
            "library",
        ) from e


def check(status: int) -> None:
    """Raises SilkError with the library's message for a status other than SILK_OK."""
    if status != _capi.SILK_OK:
        L = lib()
        raise SilkError(status, L.silk_last_error().decode(errors="replace"), L.silk_status_name(status).decode())


class _Owned:
    """A libsilk handle this object owns: close() frees it at once (_free), also on leaving a
    `with` block and on garbage collection; subclasses set _h and implement _free."""

    _h = None

    def _free(self) -> None:
        raise NotImplementedError

    def close(self) -> None:
        self._free()

    def __del__(self):
        try:
            self.close()
        except Exception:  # interpreter shutdown
            pass

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()
