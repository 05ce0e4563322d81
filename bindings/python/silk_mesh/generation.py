# SPDX-License-Identifier: MIT
"""Generation: silk_mesh.Model (a loaded model folder), silk_mesh.Generator (one generation at a
time, in one call or step by step: start / advance / preview / finish / cancel, with a progress
callback) and silk_mesh.generate (one call with a fresh generator). Results are Result(mesh, ids,
stats); the mesh is in the input's frame, its `parts` give each triangle's part."""

from __future__ import annotations

import ctypes
import os
from typing import NamedTuple

from . import _arrays, _capi, _checks, _native, _params
from ._library import SilkError, _Owned, preload_onnxruntime
from .mesh import Mesh, _Borrowed
from .models import find_model

# silk_generate_params' enum fields: the enum libsilk names each one's values with.
_ENUM_FIELDS = {
    "holes": "hole_policy",
    "orient": "orientation",
    "preprocessing": "preprocess_kind",
    "face_guidance": "face_guidance",
}
_HIDDEN = ("progress", "cancel", "user_data", "reserved")  # callables (set from Python ones); reserved: 0


class Model(_Owned):
    """A loaded model folder (model.json, encoder.onnx, decoder.onnx). dir: a folder, or the name of a
    model in the user's models folder (models.find_model; a path always wins); None: the bundled
    model (bundled_model_dir()), else SilkError naming where libsilk looked. threads: the process's shared
    pool (0 = physical cores; the first load decides); decoder: "default", "int8", "fp32", "int4";
    kv_precision: "default" (the model's), "fp32", "fp16", "int8" (the self-attention cache; docs/runtime.md).
    Generators keep the model alive: close() may come first."""

    _h = None

    def __init__(
        self,
        dir: str | os.PathLike | None = None,
        threads: int = 0,
        decoder: str = "default",
        kv_precision: str = "default",
    ):
        dir = find_model(dir)  # libsilk's rule: bundled, a folder, or a name
        decoders, kv_precisions = _native.enum_names("decoder_precision"), _native.enum_names("kv_precision")
        if decoder not in decoders:
            raise ValueError(f"Model: decoder must be one of {sorted(decoders)}, not {decoder!r}")
        if kv_precision not in kv_precisions:
            raise ValueError(f"Model: kv_precision must be one of {sorted(kv_precisions)}, not {kv_precision!r}")
        self.dir = os.fspath(dir)
        preload_onnxruntime()  # the pip wheel's libsilk: the onnxruntime package's library
        threads = _checks.integer(threads, ctypes.c_int32, "Model: threads")
        self._h = _native.model_load(os.fsencode(self.dir), threads, decoders[decoder], kv_precisions[kv_precision])

    def info(self) -> dict:
        """model.json figures and the options in use (d_model, default_points, decoder, ...)."""
        return _params.as_dict(_native.model_info(self.handle))

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._h:
            raise ValueError("silk_mesh.Model: the model is closed")
        return self._h

    def _free(self) -> None:
        if self._h:
            _native.model_destroy(self._h)
            self._h = None


class Result(NamedTuple):
    mesh: Mesh  # the generated mesh (input frame); Mesh.parts: each triangle's part
    ids: list  # the generated token ids (format ids, EOS included when generated)
    stats: dict  # silk_generate_stats by field name; stop_reason as libsilk's name ("eos", ...)


def _progress_dict(p) -> dict:
    return p[0].as_dict()


def _generate_params(params: dict) -> _capi.GenerateParams:
    """silk_generate_params from keywords (Generator's params; the callbacks are set apart)."""
    enums = {field: _native.enum_names(enum) for field, enum in _ENUM_FIELDS.items()}
    return _params.fill(_native.generate_defaults(), params, "generate", enums, _HIDDEN)


def _generate_input(source, points):
    """(silk_generate_input, what must outlive its use: the points array or a _Borrowed mesh,
    whose __exit__ the caller calls)."""
    gi = _capi.GenerateInput()
    if (source is None) == (points is None):
        raise TypeError("generate: give exactly one of an input mesh and points=")
    if points is not None:
        ptr, rows, keep = _arrays.to_c(points, ctypes.c_double, 6, "points")
        gi.points, gi.point_rows = ptr, rows
        return gi, keep
    borrowed = _Borrowed(source, "generate")
    gi.mesh = borrowed.mesh.handle
    return gi, borrowed


class Generator(_Owned):
    """One generation at a time on a Model (a Model, a folder path, or None: the bundled model).
    One call: run(input, **params) -> Result. Step-wise: start(input, **params), advance(...) until
    it returns True (also `done`), preview() / ids() / stats() at any point (best of N: every
    candidate with candidates() / candidate_preview(i)), finish() -> Result;
    cancel() from anywhere (a callback, another thread). Use one generator per thread.

    input: a Mesh, a mesh file path or (positions, triangles); or points= rows x y z nx ny nz.
    params: fields of silk_generate_params by name: seed, temperature, top_k, top_p, max_tokens,
    max_faces, holes ("off", "report", "repair"), point_count,
    surface_tolerance, candidates, rows (best of N's candidates decoded together, 1..64; 1: one
    after another; the result does not depend on it, only the time), orient ("input", "tokens"),
    face_guidance ("off", "hard", "soft"), face_tolerance (cells), report_flags (1: record the trace for
    report_json(trace=True)), ...; None keeps libsilk's default (sampling: the model's values).
    progress(dict) is called after every id (tokens, max_tokens, components, faces, seconds);
    cancel() -> truthy stops the run (SilkError with status SILK_ERR_CANCELLED). An exception in
    either callback cancels the run and is raised from the call."""

    _h = None

    def __init__(self, model: Model | str | os.PathLike | None = None):
        self._own_model = not isinstance(model, Model)
        self.model = Model(model) if self._own_model else model
        self._h = _native.generator_create(self.model.handle)
        self._keep, self._error, self.done = (), None, False

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._h:
            raise ValueError("silk_mesh.Generator: the generator is closed")
        return self._h

    def _prepare(self, source, points, progress, cancel, params: dict):
        """(GenerateInput, GenerateParams); their Python-side objects stay in self._keep."""
        p = _generate_params(params)
        callbacks = []
        if progress is not None:
            callbacks.append(_capi.PROGRESS_FN(lambda pr, _u: self._guard(progress, _progress_dict(pr))))
            p.progress = callbacks[-1]
        if cancel is not None:
            callbacks.append(_capi.CANCEL_FN(lambda _u: 1 if self._guard(cancel) else 0))
            p.cancel = callbacks[-1]
        gi, keep = _generate_input(source, points)
        self._keep, self._error = (callbacks, keep, p), None
        return gi, p

    def _guard(self, fn, *args):
        """Runs a callback; an exception is kept for the caller and cancels the run."""
        try:
            return fn(*args)
        except BaseException as e:  # noqa: BLE001 - re-raised by _release
            self._error = self._error or e
            _native.generator_cancel(self._h)
            return True

    def _release(self, keep_callbacks: bool = False) -> None:
        callbacks, keep, _ = self._keep or ((), None, None)
        if isinstance(keep, _Borrowed):
            keep.__exit__()
        self._keep = (callbacks, None, None) if keep_callbacks else ()
        if self._error is not None:
            err, self._error = self._error, None
            raise err

    def run(self, input=None, *, points=None, progress=None, cancel=None, **params) -> Result:
        """One call (best of `candidates` runs): the Result."""
        gi, p = self._prepare(input, points, progress, cancel, params)
        try:
            mh, th, st = _native.generator_run(self.handle, gi, p)
        except SilkError:
            self._release()
            raise
        self._release()
        return Result(Mesh._adopt(mh), _native.tokens_take(th), _native.stats_dict(st))

    def start(self, input=None, *, points=None, progress=None, cancel=None, **params) -> None:
        """Prepares the points and runs the encoder; then advance() adds ids."""
        gi, p = self._prepare(input, points, progress, cancel, params)
        self.done = False
        try:
            _native.generator_start(self.handle, gi, p)
        except SilkError:
            self._release()
            raise
        self._release(keep_callbacks=True)  # the input is copied by start; callbacks run on

    def advance(self, max_ids: int = 64, until_layer: bool = False) -> bool:
        """Adds up to max_ids ids (until_layer: stops at the next completed layer); True once done.
        A cancel raises SilkError(SILK_ERR_CANCELLED); finish() still gives the completed layers."""
        try:
            max_ids = _checks.integer(max_ids, ctypes.c_int32, "advance: max_ids")
            self.done = _native.generator_advance(self.handle, max_ids, until_layer)
        finally:
            if self._error is not None:
                err, self._error = self._error, None
                raise err
        return self.done

    def preview(self) -> Mesh:
        """The faces of the layers completed so far (input frame)."""
        return Mesh._adopt(_native.generator_mesh(self.handle))

    def ids(self) -> list[int]:
        return _native.tokens_take(_native.generator_tokens(self.handle))

    def candidates(self) -> list[dict]:
        """Every one of best of N's candidates of the generation in progress (C API 1.5), in seed
        order: {"index", "state" ("waiting", "running", "ended", "scored"), "tokens" (ids so far),
        "faces" (its mesh's, None until built), "score" (None unless scored; lower is better),
        "best" (True: the best of those scored so far)}. The candidates may run one after another
        or together as rows; one run one after another stays "running" until its mesh is built.
        Between start() and finish() only (SilkError otherwise)."""
        out = []
        for c in _native.generator_candidates(self.handle):
            out.append(
                {
                    "index": c.index,
                    "state": _native.enum_name("candidate_state", c.state),
                    "tokens": c.tokens,
                    "faces": None if c.faces < 0 else c.faces,
                    "score": c.score if c.score == c.score else None,  # NaN: not scored
                    "best": bool(c.best),
                }
            )
        return out

    def candidate_preview(self, index: int) -> Mesh:
        """Candidate `index`'s mesh (input frame): its completed layers while it runs, its whole mesh
        once built, no faces while it waits. SilkError (invalid argument) for an index outside
        [0, N) or with no generation in progress."""
        index = _checks.integer(index, ctypes.c_int32, "candidate_preview: index")
        return Mesh._adopt(_native.generator_candidate_mesh(self.handle, index))

    def stats(self) -> dict:
        return _native.stats_dict(_native.generator_stats(self.handle))

    def finish(self) -> Result:
        """Ends the generation (cancelling it first when not done): the final mesh, ids, stats."""
        try:
            mh, th, st = _native.generator_finish(self.handle)
        finally:
            self._keep = ()
        self.done = True
        return Result(Mesh._adopt(mh), _native.tokens_take(th), _native.stats_dict(st))

    def cancel(self) -> None:
        """Thread-safe, any time: cancels the run in progress (nothing when none is)."""
        if self._h:
            _native.generator_cancel(self._h)

    def report_json(self, trace: bool = False) -> str:
        """The last finished generation as JSON (settings, input, figures; trace: per-id legal sets
        when started with report_flags=1, SILK_GENERATE_RECORD_TRACE)."""
        return _native.generator_report_json(self.handle, trace)

    def _free(self) -> None:
        if self._h:
            _native.generator_destroy(self._h)
            self._h = None
        self._keep = ()
        if self._own_model:
            self.model.close()


def generate(
    input=None, model: Model | str | os.PathLike | None = None, *, points=None, progress=None, cancel=None, **params
) -> Result:
    """One generation with a fresh Generator (see Generator for input and params); model: a
    Model, a model folder, or None for the bundled model."""
    with Generator(model) as gen:  # closes the model too when it made it
        return gen.run(input, points=points, progress=progress, cancel=cancel, **params)
