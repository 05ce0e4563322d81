# SPDX-License-Identifier: MIT
"""silk_mesh.Batch: many inputs with one model, up to `parallel` meshes decoded together as rows of
one decoder call (C API 1.6, silk_batch_*): add inputs, take each as soon as it ends with its
index. Each input's Result is exactly what Generator.run gives for it with the same params; an
input's error is its own (BatchItem.error) and never stops the others."""

from __future__ import annotations

import ctypes
import os
from typing import NamedTuple

from . import _capi, _checks, _native
from ._library import SilkError, _Owned
from .generation import Model, Result, _generate_input, _generate_params, _progress_dict
from .mesh import Mesh, _Borrowed


class BatchItem(NamedTuple):
    index: int  # the input's index: 0, 1, ... in the order added
    result: Result | None  # None when it failed
    error: SilkError | None  # its error (status SILK_ERR_CANCELLED after a cancel), else None


class Batch(_Owned):
    """Batch(model, parallel=1, rows=None, progress=None, cancel=None). model: a Model, a folder
    path or None (the bundled model). parallel: meshes in flight at most, 1..16 (1: one after
    another; a model folder before decoder contract v4 always runs them so). rows: decoder rows per
    mesh in flight (None: the model's). progress(index, dict) after every id of input `index`;
    cancel() -> truthy stops the batch (the inputs in flight end with SILK_ERR_CANCELLED, and the
    queued ones too without starting: every input added comes back once). An exception in a callback cancels the batch and is raised from next().

    add(input=None, *, points=None, **params) -> index queues an input (copied) with Generator.run's
    params; next() -> BatchItem of the next input to end, or None when none is queued or in flight;
    iterating a batch yields every item until none is left; close() refuses further adds."""

    _h = None

    def __init__(
        self,
        model: Model | str | os.PathLike | None = None,
        parallel: int = 1,
        rows: int | None = None,
        progress=None,
        cancel=None,
    ):
        self._own_model = not isinstance(model, Model)
        self.model = Model(model) if self._own_model else model
        self._error = None
        p = _native.batch_defaults()
        p.parallel = _checks.integer(parallel, ctypes.c_int32, "Batch: parallel")
        if rows is not None:
            p.rows = _checks.integer(rows, ctypes.c_int32, "Batch: rows")
        self._callbacks = []
        if progress is not None:
            self._callbacks.append(
                _capi.BATCH_PROGRESS_FN(lambda i, pr, _u: self._guard(progress, i, _progress_dict(pr)))
            )
            p.progress = self._callbacks[-1]
        if cancel is not None:
            self._callbacks.append(_capi.CANCEL_FN(lambda _u: 1 if self._guard(cancel) else 0))
            p.cancel = self._callbacks[-1]
        try:
            self._h = _native.batch_create(self.model.handle, p)
        except SilkError:
            if self._own_model:
                self.model.close()
            raise

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._h:
            raise ValueError("silk_mesh.Batch: the batch is closed")
        return self._h

    def _guard(self, fn, *args):
        """Runs a callback; an exception is kept for next() and cancels the batch."""
        try:
            return fn(*args)
        except BaseException as e:  # noqa: BLE001 - re-raised by next()
            self._error = self._error or e
            _native.batch_cancel(self._h)
            return True

    def add(self, input=None, *, points=None, **params) -> int:
        """Queues an input (a Mesh, a mesh file path or (positions, triangles); or points=) with
        Generator.run's keyword params; its index. Its params and input are checked when it starts:
        their errors come back from next() as its item's error."""
        for name in ("progress", "cancel", "user_data"):
            if name in params:
                raise TypeError(f"Batch.add: {name} is the batch's (Batch(progress=..., cancel=...))")
        p = _generate_params(params)
        gi, keep = _generate_input(input, points)
        try:
            return _native.batch_add(self.handle, gi, p)  # the input is copied
        finally:
            if isinstance(keep, _Borrowed):
                keep.__exit__()

    def next(self) -> BatchItem | None:
        index, status, mh, th, st = _native.batch_next(self.handle)
        if self._error is not None:
            err, self._error = self._error, None
            if mh:
                Mesh._adopt(mh).close()
            if th:
                _native.tokens_take(th)
            raise err
        if index < 0:
            return None
        if status != _capi.SILK_OK:
            try:
                _native.check(status)
            except SilkError as e:
                return BatchItem(index, None, e)
        return BatchItem(index, Result(Mesh._adopt(mh), _native.tokens_take(th), _native.stats_dict(st)), None)

    def __iter__(self):
        while (item := self.next()) is not None:
            yield item

    def counts(self) -> tuple[int, int]:
        """(inputs in flight, inputs queued)."""
        return _native.batch_counts(self.handle)

    def close_inputs(self) -> None:
        """No more inputs (silk_batch_close): add raises SilkError from now on."""
        _native.batch_close(self.handle)

    def cancel(self) -> None:
        """Thread-safe, any time: cancels the batch."""
        if self._h:
            _native.batch_cancel(self._h)

    def _free(self) -> None:
        if self._h:
            _native.batch_destroy(self._h)
            self._h = None
        self._callbacks = []
        if self._own_model:
            self.model.close()
