# SPDX-License-Identifier: MIT
"""The C declarations of libsilk's API (engine/include/silk/silk.h) for ctypes: status codes,
structs and function signatures, in one place for every Python client (the silk_mesh package,
which export/silk_export uses and the Blender add-on vendors). Pure ctypes, no numpy."""

from __future__ import annotations

import ctypes

_c_int32_p = ctypes.POINTER(ctypes.c_int32)
_c_double_p = ctypes.POINTER(ctypes.c_double)
_c_size_p = ctypes.POINTER(ctypes.c_size_t)

SILK_OK = 0
SILK_ERR_INVALID_ARGUMENT = 1
SILK_ERR_IO = 2
SILK_ERR_REFUSED = 5
SILK_ERR_CANCELLED = 7
SILK_ERR_BUFFER_TOO_SMALL = 9
SILK_ERR_BUSY = 10
MODEL_VALUE = -1  # SILK_MODEL_VALUE: "the model's value" of a sampling field (any other negative is refused)
MODEL_VALUE = -1  # SILK_MODEL_VALUE: "the model's value" of a sampling field (any other negative is refused)
# The silk.h enums libsilk names (C API 1.4: silk_<enum>_name / silk_<enum>_from_name), each with its
# first value; the names themselves come from the library (_native.enum_names), never from here.
ENUM_FIRST = {
    "log_level": 0,
    "mesh_format": 0,
    "window_rule": 0,
    "hole_policy": 0,
    "preprocess_kind": 0,
    "decoder_precision": 0,
    "kv_precision": 0,
    "arch": 0,
    "orientation": 0,
    "face_guidance": 0,
    "advance_until": 0,
    "stop_reason": -1,
    "candidate_state": 0,  # C API 1.5
}


class _Sized(ctypes.Structure):
    """A silk.h struct that starts with uint32_t struct_size (C API 1.0, docs/c_api.md): a
    Python-made one carries its own size; *_default_params() return it set."""

    def __init__(self, *args, **kw):
        super().__init__(*args, **kw)
        self.struct_size = ctypes.sizeof(self)

    def __setattr__(self, name, value):
        # ctypes would quietly keep an unknown attribute (a renamed field would be ignored).
        if not any(name == field for field, _ in type(self)._fields_):
            raise AttributeError(f"{type(self).__name__} has no field '{name}'")
        super().__setattr__(name, value)

    def as_dict(self) -> dict:
        return {name: getattr(self, name) for name, _ in self._fields_ if name != "struct_size"}


_SIZE = [("struct_size", ctypes.c_uint32)]


class VocabInfo(_Sized):
    _fields_ = _SIZE + [
        (n, ctypes.c_int32)
        for n in (
            "token_format_version",
            "format_vocab_size",
            "eos_id",
            "pad_id",
            "model_vocab_size",
            "c_id",
            "u_id",
            "e_id",
            "x_begin",
            "x_end",
            "s_begin",
            "s_end",
            "b_begin",
            "b_end",
            "k_begin",
            "k_end",
            "o_begin",
            "o_end",
            "quant_bins",
            "layer_vertex_limit",
            "layer_count_limit",
            "max_faces",
            "max_seq_length",
        )
    ]


class EncodeParams(_Sized):
    _fields_ = _SIZE + [
        ("normalize", ctypes.c_int32),
        ("normalize_bound", ctypes.c_double),
        ("nonmanifold_processing", ctypes.c_int32),
    ]


class EncodeStats(_Sized):
    _fields_ = (
        _SIZE
        + [
            (n, ctypes.c_int32)
            for n in (
                "input_vertices",
                "input_faces",
                "processed_vertices",
                "processed_faces",
                "emitted_vertices",
                "encodable_faces",
                "components_found",
                "components_encoded",
                "components_dropped_small",
                "layers",
                "max_layer_size",
                "max_layer_count",
            )
        ]
        + [("tokens", ctypes.c_int64), ("seconds", ctypes.c_double)]
        + [
            (n, ctypes.c_int32)
            for n in (
                "merged_vertices",
                "dropped_degenerate_faces",
                "dropped_duplicate_faces",
                "nonmanifold_copies",
                "flipped_faces",
            )
        ]
        + [
            (n, ctypes.c_double)
            for n in (
                "seconds_quantize_cleanup",
                "seconds_nonmanifold",
                "seconds_orientation",
                "seconds_components",
                "seconds_layering",
                "seconds_codecs",
                "seconds_packing",
            )
        ]
    )


class DecodeParams(_Sized):
    _fields_ = _SIZE + [("grid_coordinates", ctypes.c_int32), ("split_nonmanifold_vertices", ctypes.c_int32)]


class DecodeStats(_Sized):
    _fields_ = _SIZE + [(n, ctypes.c_int32) for n in ("vertices", "faces", "components", "vertices_split")]


class LoadParams(_Sized):
    _fields_ = _SIZE + [("point_clouds", ctypes.c_int32)]


class RoundtripReport(_Sized):
    _fields_ = (
        _SIZE
        + [
            (n, ctypes.c_int64)
            for n in (
                "tokens",
                "processed_faces",
                "representable_faces",
                "recovered",
                "reversed",
                "missing",
                "extra",
                "decoded_faces",
            )
        ]
        + [("exact", ctypes.c_int32)]
    )


class CheckParams(_Sized):
    _fields_ = _SIZE + [
        ("max_length", ctypes.c_int32),
        ("window_rule", ctypes.c_int32),
        ("allow_prefix", ctypes.c_int32),
    ]


class CheckResult(_Sized):
    _fields_ = _SIZE + [
        ("accepted", ctypes.c_int32),
        ("reason", ctypes.c_int32),
        ("position", ctypes.c_int64),
        ("id", ctypes.c_int32),
        ("message", ctypes.c_char * 512),
    ]


class RepairParams(_Sized):
    _fields_ = _SIZE + [("holes", ctypes.c_int32), ("max_fill_loop", ctypes.c_int32)]


class RepairStats(_Sized):
    _fields_ = (
        _SIZE
        + [("tokens_accepted", ctypes.c_int64), ("illegal_at", ctypes.c_int64)]
        + [
            (n, ctypes.c_int32)
            for n in (
                "vertices",
                "faces",
                "watertight",
                "window_findings",
                "holes_found",
                "holes_repaired",
                "faces_added",
                "open_edges_before",
                "open_edges_after",
            )
        ]
    )


class RandomWalkParams(_Sized):
    _fields_ = _SIZE + [
        ("seed", ctypes.c_uint64),
        ("max_components", ctypes.c_int32),
        ("max_layers", ctypes.c_int32),
        ("max_layer_size", ctypes.c_int32),
    ]


class PreprocessParams(_Sized):
    _fields_ = _SIZE + [
        ("kind", ctypes.c_int32),
        ("normalize_bound", ctypes.c_double),
        ("merge_distance_fraction", ctypes.c_double),
        ("surface_samples", ctypes.c_int32),
        ("round_float16", ctypes.c_int32),
        ("point_count", ctypes.c_int32),
    ]


class ModelParams(_Sized):
    _fields_ = _SIZE + [
        ("threads", ctypes.c_int32),
        ("decoder", ctypes.c_int32),  # silk_decoder_precision
        ("kv_precision", ctypes.c_int32),
    ]  # silk_kv_precision


class ModelInfo(_Sized):
    _fields_ = (
        _SIZE
        + [("config", ctypes.c_char * 32)]
        + [
            (n, ctypes.c_int32)
            for n in (
                "d_model",
                "n_layers",
                "n_heads",
                "head_dim",
                "n_latents",
                "default_points",
                "max_seq_len",
                "threads",
                "int8",
                "decoder",
                "arch",
                "encoder_points",
                "kv_precision",
            )
        ]
    )


class GenerateProgress(_Sized):
    _fields_ = _SIZE + [
        ("tokens", ctypes.c_int64),
        ("max_tokens", ctypes.c_int64),
        ("components", ctypes.c_int32),
        ("faces", ctypes.c_int32),
        ("seconds", ctypes.c_double),
        ("candidate", ctypes.c_int32),
        ("candidates", ctypes.c_int32),
    ]


PROGRESS_FN = ctypes.CFUNCTYPE(None, ctypes.POINTER(GenerateProgress), ctypes.c_void_p)
CANCEL_FN = ctypes.CFUNCTYPE(ctypes.c_int32, ctypes.c_void_p)


SILK_GENERATE_RECORD_TRACE = 1  # silk_generate_params.report_flags

# C API 1.6: a batch's progress callback (input index, progress, user data).
BATCH_PROGRESS_FN = ctypes.CFUNCTYPE(None, ctypes.c_int32, ctypes.POINTER(GenerateProgress), ctypes.c_void_p)


class BatchParams(_Sized):
    _fields_ = _SIZE + [
        ("parallel", ctypes.c_int32),  # meshes in flight at most, 1..16
        ("rows", ctypes.c_int32),  # decoder rows per mesh in flight (-1: the model's)
        ("progress", BATCH_PROGRESS_FN),
        ("cancel", CANCEL_FN),
        ("user_data", ctypes.c_void_p),
    ]


class GenerateParams(_Sized):
    _fields_ = _SIZE + [
        ("seed", ctypes.c_uint64),
        ("temperature", ctypes.c_double),
        ("top_k", ctypes.c_int32),
        ("top_p", ctypes.c_double),
        ("max_tokens", ctypes.c_int32),
        ("max_faces", ctypes.c_int32),
        ("holes", ctypes.c_int32),
        ("point_count", ctypes.c_int32),
        ("progress", PROGRESS_FN),
        ("cancel", CANCEL_FN),
        ("user_data", ctypes.c_void_p),
        ("top_p_temperature", ctypes.c_double),
        ("preprocessing", ctypes.c_int32),
        ("raw_points", ctypes.c_int32),
        ("report_flags", ctypes.c_int32),
        ("surface_tolerance", ctypes.c_int32),
        ("candidates", ctypes.c_int32),
        ("orient", ctypes.c_int32),
        # reserved, 0 (1.0-1.3: the measurement switches unconstrained, debug_flags; silk.h)
        ("reserved", ctypes.c_int32 * 2),
        # C API 1.3: face guidance (silk_face_guidance or -1: the model's; cells or -1)
        ("face_guidance", ctypes.c_int32),
        ("face_tolerance", ctypes.c_double),
        # C API 1.5: best of N's candidates decoded together, 1..64 (-1: the model's, else 8)
        ("rows", ctypes.c_int32),
    ]


class GenerateStats(_Sized):
    _fields_ = (
        _SIZE
        + [(n, ctypes.c_int64) for n in ("tokens", "forced_tokens", "sampled_tokens", "model_calls")]
        + [
            (n, ctypes.c_int32)
            for n in (
                "stop_reason",
                "faces",
                "vertices",
                "components",
                "holes_found",
                "holes_repaired",
                "faces_added",
                "edge_manifold",
                "watertight",
                "consistently_oriented",
                "open_edges",
            )
        ]
        + [("illegal_at", ctypes.c_int64)]
        + [
            (n, ctypes.c_int32)
            for n in ("vertex_manifold", "nonmanifold_vertices", "fan_gaps_closed", "vertices_split")
        ]
        + [(n, ctypes.c_int64) for n in ("guided_tokens", "guidance_fallbacks")]
        + [(n, ctypes.c_int32) for n in ("candidates", "chosen_candidate")]
        + [("score", ctypes.c_double), ("parts_flipped", ctypes.c_int32)]
        + [
            # timings
            (n, ctypes.c_double)
            for n in (
                "tokens_per_second",
                "seconds_prepare",
                "seconds_encoder",
                "seconds_decoder",
                "seconds_grammar",
                "seconds_sampling",
                "seconds_build_mesh",
                "seconds_guidance",
                "seconds_scoring",
                "seconds_total",
            )
        ]
        + [
            # C API 1.3: face guidance
            (n, ctypes.c_int64)
            for n in ("face_guided_tokens", "face_fallbacks")
        ]
        + [("seconds_face_guidance", ctypes.c_double)]
        # C API 1.5: best of N's rows used (min(rows, candidates))
        + [("rows", ctypes.c_int32)]
    )


class GenerateInput(_Sized):
    _fields_ = _SIZE + [("mesh", ctypes.c_void_p), ("points", _c_double_p), ("point_rows", ctypes.c_size_t)]


class CandidateInfo(_Sized):
    """silk_candidate_info (C API 1.5): one of best of N's candidates of the generation in progress."""

    _fields_ = _SIZE + [
        ("index", ctypes.c_int32),
        ("state", ctypes.c_int32),
        ("faces", ctypes.c_int32),
        ("tokens", ctypes.c_int64),
        ("score", ctypes.c_double),
        ("best", ctypes.c_int32),
    ]


class SaveParams(_Sized):
    _fields_ = _SIZE + [("part_colors", ctypes.c_int32), ("obj_comment", ctypes.c_char_p), ("format", ctypes.c_int32)]


SIGNATURES = {
    "silk_last_error": (ctypes.c_char_p, []),
    "silk_status_name": (ctypes.c_char_p, [ctypes.c_int]),
    "silk_version": (ctypes.c_char_p, []),
    "silk_vocab_get_info": (ctypes.c_int, [ctypes.POINTER(VocabInfo)]),
    "silk_mesh_create": (
        ctypes.c_int,
        [_c_double_p, ctypes.c_size_t, _c_int32_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_void_p)],
    ),
    "silk_mesh_load": (ctypes.c_int, [ctypes.c_char_p, ctypes.POINTER(LoadParams), ctypes.POINTER(ctypes.c_void_p)]),
    "silk_mesh_save": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(SaveParams)]),
    "silk_mesh_destroy": (None, [ctypes.c_void_p]),
    "silk_mesh_copy_positions": (ctypes.c_int, [ctypes.c_void_p, _c_double_p, ctypes.c_size_t, _c_size_p]),
    "silk_mesh_copy_triangles": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, ctypes.c_size_t, _c_size_p]),
    "silk_mesh_copy_triangle_components": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, ctypes.c_size_t, _c_size_p]),
    "silk_mesh_copy_normals": (ctypes.c_int, [ctypes.c_void_p, _c_double_p, ctypes.c_size_t, _c_size_p]),
    "silk_mesh_has_normals": (ctypes.c_int32, [ctypes.c_void_p]),
    "silk_tokens_create": (ctypes.c_int, [_c_int32_p, ctypes.c_size_t, ctypes.POINTER(ctypes.c_void_p)]),
    "silk_tokens_load": (ctypes.c_int, [ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)]),
    "silk_tokens_save": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_char_p]),
    "silk_tokens_destroy": (None, [ctypes.c_void_p]),
    "silk_tokens_copy": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, ctypes.c_size_t, _c_size_p]),
    "silk_encode_default_params": (EncodeParams, []),
    "silk_mesh_encode": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(EncodeParams), ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(EncodeStats)],
    ),
    "silk_preprocess_default_params": (PreprocessParams, [ctypes.c_int32]),
    "silk_points_prepare": (
        ctypes.c_int,
        [
            ctypes.c_void_p,
            _c_double_p,
            ctypes.c_size_t,
            ctypes.POINTER(PreprocessParams),
            ctypes.c_uint64,
            ctypes.POINTER(ctypes.c_float),
            ctypes.c_size_t,
            ctypes.POINTER(ctypes.c_size_t),
            _c_double_p,
        ],
    ),
    "silk_model_get_preprocess_params": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(PreprocessParams)]),
    "silk_decode_default_params": (DecodeParams, []),
    "silk_tokens_decode": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(DecodeParams), ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(DecodeStats)],
    ),
    "silk_load_default_params": (LoadParams, []),
    "silk_mesh_roundtrip": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(EncodeParams), ctypes.POINTER(RoundtripReport)],
    ),
    "silk_report_json": (ctypes.c_char_p, [ctypes.c_void_p]),
    "silk_report_destroy": (None, [ctypes.c_void_p]),
    "silk_check_default_params": (CheckParams, []),
    "silk_tokens_check": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(CheckParams), ctypes.POINTER(CheckResult)]),
    "silk_reject_reason_name": (ctypes.c_char_p, [ctypes.c_int32]),
    "silk_repair_default_params": (RepairParams, []),
    "silk_tokens_repair": (
        ctypes.c_int,
        [
            ctypes.c_void_p,
            ctypes.POINTER(RepairParams),
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(RepairStats),
            ctypes.POINTER(ctypes.c_void_p),
        ],
    ),
    "silk_random_walk_default_params": (RandomWalkParams, []),
    "silk_tokens_random_walk": (
        ctypes.c_int,
        [ctypes.POINTER(RandomWalkParams), ctypes.POINTER(ctypes.c_void_p), ctypes.POINTER(ctypes.c_void_p)],
    ),
    "silk_generation_available": (ctypes.c_int32, []),
    "silk_model_default_params": (ModelParams, []),
    "silk_model_load": (ctypes.c_int, [ctypes.c_char_p, ctypes.POINTER(ModelParams), ctypes.POINTER(ctypes.c_void_p)]),
    "silk_model_destroy": (None, [ctypes.c_void_p]),
    "silk_model_get_info": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(ModelInfo)]),
    "silk_generator_create": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]),
    "silk_generator_destroy": (None, [ctypes.c_void_p]),
    "silk_generate_default_params": (GenerateParams, []),
    "silk_generator_start": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(GenerateInput), ctypes.POINTER(GenerateParams)],
    ),
    "silk_generator_advance": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_int32, ctypes.c_int32, ctypes.POINTER(ctypes.c_int32)],
    ),
    "silk_generator_cancel": (None, [ctypes.c_void_p]),
    "silk_generator_get_tokens": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]),
    "silk_generator_get_mesh": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)]),
    "silk_generator_get_stats": (ctypes.c_int, [ctypes.c_void_p, ctypes.POINTER(GenerateStats)]),
    "silk_generator_finish": (
        ctypes.c_int,
        [
            ctypes.c_void_p,
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(GenerateStats),
        ],
    ),
    "silk_generator_report": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_int32, ctypes.POINTER(ctypes.c_void_p)]),
    "silk_generator_run": (
        ctypes.c_int,
        [
            ctypes.c_void_p,
            ctypes.POINTER(GenerateInput),
            ctypes.POINTER(GenerateParams),
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(GenerateStats),
        ],
    ),
    "silk_save_default_params": (SaveParams, []),
    "silk_generator_copy_points": (ctypes.c_int, [ctypes.c_void_p, _c_double_p, ctypes.c_size_t, _c_size_p]),
    "silk_models_dir": (ctypes.c_int, [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_size_t, _c_size_p]),
    "silk_model_default_dir": (ctypes.c_int, [ctypes.c_char_p, ctypes.c_size_t, _c_size_p]),
    "silk_model_find": (ctypes.c_int, [ctypes.c_char_p, ctypes.c_char_p, ctypes.c_size_t, _c_size_p]),
    "silk_models_list": (ctypes.c_int, [ctypes.POINTER(ctypes.c_void_p)]),
    # C API 1.5: best of N's candidates while they run.
    "silk_generator_candidate_count": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p]),
    "silk_generator_get_candidate": (ctypes.c_int, [ctypes.c_void_p, ctypes.c_int32, ctypes.POINTER(CandidateInfo)]),
    "silk_generator_get_candidate_mesh": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.c_int32, ctypes.POINTER(ctypes.c_void_p)],
    ),
    # C API 1.6: a batch of inputs, several meshes decoded together.
    "silk_batch_default_params": (BatchParams, []),
    "silk_batch_create": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(BatchParams), ctypes.POINTER(ctypes.c_void_p)],
    ),
    "silk_batch_destroy": (None, [ctypes.c_void_p]),
    "silk_batch_add": (
        ctypes.c_int,
        [ctypes.c_void_p, ctypes.POINTER(GenerateInput), ctypes.POINTER(GenerateParams), _c_int32_p],
    ),
    "silk_batch_close": (ctypes.c_int, [ctypes.c_void_p]),
    "silk_batch_next": (
        ctypes.c_int,
        [
            ctypes.c_void_p,
            _c_int32_p,
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(ctypes.c_void_p),
            ctypes.POINTER(GenerateStats),
        ],
    ),
    "silk_batch_counts": (ctypes.c_int, [ctypes.c_void_p, _c_int32_p, _c_int32_p]),
    "silk_batch_cancel": (None, [ctypes.c_void_p]),
}


for _enum in ENUM_FIRST:
    SIGNATURES[f"silk_{_enum}_name"] = (ctypes.c_char_p, [ctypes.c_int32])
    SIGNATURES[f"silk_{_enum}_from_name"] = (ctypes.c_int, [ctypes.c_char_p, _c_int32_p])


def declare(lib: ctypes.CDLL) -> None:
    """Sets restype/argtypes of every function in SIGNATURES on a loaded libsilk."""
    for name, (res, args) in SIGNATURES.items():
        fn = getattr(lib, name)
        fn.restype, fn.argtypes = res, args
