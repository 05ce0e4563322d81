/* SPDX-License-Identifier: MIT */
/* silk.h — the one public C API of libsilk (Mesh Silksong engine); its version: SILK_VERSION_* below.
 * Opaque handles, create/destroy pairs, one silk_<x>_default_params() per params struct, status
 * codes plus a per-thread error message, one size-query rule for every copy, one way to return
 * JSON (silk_report); no exception ever crosses this boundary. The rules: docs/c_api.md. */
#ifndef SILK_SILK_H_
#define SILK_SILK_H_

#include <stddef.h>
#include <stdint.h>

/* SILK_API: on Windows, libsilk's own build (SILK_BUILDING_LIBRARY) exports the functions, a
 * client of libsilk.dll imports them, and a client of the static library (SILK_STATIC, set by the
 * silk_static target) does neither. Elsewhere only SILK_API symbols leave libsilk.so. */
#if defined(_WIN32)
#if defined(SILK_BUILDING_LIBRARY)
#define SILK_API __declspec(dllexport)
#elif defined(SILK_STATIC)
#define SILK_API
#else
#define SILK_API __declspec(dllimport)
#endif
#else
#define SILK_API __attribute__((visibility("default")))
#endif

/* SILK_DEPRECATED(why): marks what is removed in 2.0 (a compiler warning where supported; never
 * inside libsilk, which still fills those fields). */
#if defined(SILK_BUILDING_LIBRARY) || defined(SILK_NO_DEPRECATION_WARNINGS)
#define SILK_DEPRECATED(why)
#elif defined(__GNUC__) || defined(__clang__)
#define SILK_DEPRECATED(why) __attribute__((deprecated(why)))
#else
#define SILK_DEPRECATED(why)
#endif

/* ---- version (the one source: CMake reads these three lines) ------------------------------
 * MAJOR changes only with an incompatible change; MINOR adds functions or appends struct fields;
 * PATCH fixes. silk_version() is the library's own string (compare it with SILK_VERSION_STRING
 * to detect a header/library mismatch). */
#define SILK_VERSION_MAJOR 1
#define SILK_VERSION_MINOR 6
#define SILK_VERSION_PATCH 0
#define SILK_STR_(x) #x
#define SILK_STR(x) SILK_STR_(x)
#define SILK_VERSION_STRING \
  SILK_STR(SILK_VERSION_MAJOR) "." SILK_STR(SILK_VERSION_MINOR) "." SILK_STR(SILK_VERSION_PATCH)
/* 10000 * MAJOR + 100 * MINOR + PATCH (1.0.0 = 10000), for #if comparisons. */
#define SILK_VERSION_NUMBER (SILK_VERSION_MAJOR * 10000 + SILK_VERSION_MINOR * 100 + SILK_VERSION_PATCH)

#ifdef __cplusplus
extern "C" {
#endif

/* ---- the rules every function below follows (docs/c_api.md) -----------------------------
 * Size query: a function that copies into a caller's buffer takes (T* out, size_t capacity,
 *   size_t* out_count) with capacity in elements of T. *out_count (may be NULL) always receives
 *   the number of elements needed. out == NULL with capacity == 0 is the size query: SILK_OK,
 *   nothing copied. A non-NULL out with capacity below the need is SILK_ERR_BUFFER_TOO_SMALL and
 *   nothing is written to out.
 * JSON: returned as a silk_report* out-handle (silk_report_json gives its text).
 * Struct growth: every params struct and every struct the library fills for the caller (stats,
 *   info, results) starts with uint32_t struct_size. Params: take them from their
 *   silk_<x>_default_params() (which sets struct_size). Out structs: set struct_size = sizeof
 *   before the call (C: silk_encode_stats st = {sizeof st}; or {.struct_size = sizeof st}).
 *   A size this library has not shipped is SILK_ERR_INVALID_ARGUMENT naming the struct. Fields
 *   are only ever appended; the library reads and fills only struct_size bytes.
 * Params: a NULL params pointer means the defaults; int32_t flags take 0 or 1 and enum fields
 *   their listed values, anything else is SILK_ERR_INVALID_ARGUMENT naming the field.
 * Ownership: every silk_<object>** out receives a new handle the caller owns and frees with
 *   silk_<object>_destroy (NULL is ignored); on failure *out is NULL. const char* results are
 *   borrowed: their lifetime is stated at each function. Inputs are borrowed for the call only. */

/* ---- status and errors ------------------------------------------------------------- */
typedef enum silk_status {
  SILK_OK = 0,
  SILK_ERR_INVALID_ARGUMENT = 1,
  SILK_ERR_IO = 2,
  SILK_ERR_PARSE = 3,
  SILK_ERR_UNSUPPORTED = 4,
  SILK_ERR_REFUSED = 5, /* the tokenizer refuses the mesh (named reason in the message) */
  SILK_ERR_LIMIT = 6,
  SILK_ERR_CANCELLED = 7,
  SILK_ERR_INTERNAL = 8,
  SILK_ERR_BUFFER_TOO_SMALL = 9,
  SILK_ERR_BUSY = 10 /* a silk_generator used by two calls at once ("generator busy") */
} silk_status;

/* Message of the last call on this thread ("" after a success). Borrowed: valid until the
 * thread's next silk_* call. */
SILK_API const char* silk_last_error(void);
/* Static strings (never freed). */
SILK_API const char* silk_status_name(silk_status s);
/* The library's version, SILK_VERSION_STRING as it was built (e.g. "1.3.0"); a static string. */
SILK_API const char* silk_version(void);

/* ---- logging: the library prints nothing itself ------------------------------------ */
typedef enum silk_log_level {
  SILK_LOG_DEBUG = 0,
  SILK_LOG_INFO = 1,
  SILK_LOG_WARN = 2,
  SILK_LOG_ERROR = 3
} silk_log_level;
/* message is borrowed for the callback's duration. */
typedef void (*silk_log_fn)(silk_log_level level, const char* message, void* user_data);
/* Process-wide; NULL disables logging (the default). Receives every failed call's message
 * (SILK_LOG_ERROR), model loads (SILK_LOG_INFO), ignored settings (SILK_LOG_WARN) and
 * onnxruntime's own warnings. Called on the thread that makes the call. */
SILK_API void silk_log_set_callback(silk_log_fn fn, void* user_data);

/* ---- vocabulary (single source: engine/tokenizer/vocabulary_layout.json) ------------ */
typedef struct silk_vocab_info {
  uint32_t struct_size; /* set by the caller: sizeof(silk_vocab_info) */
  int32_t token_format_version;
  int32_t format_vocab_size; /* 10267: ids 0..10266 */
  int32_t eos_id, pad_id, model_vocab_size;
  int32_t c_id, u_id, e_id;
  int32_t x_begin, x_end, s_begin, s_end, b_begin, b_end, k_begin, k_end, o_begin, o_end;
  int32_t quant_bins, layer_vertex_limit, layer_count_limit, max_faces, max_seq_length;
} silk_vocab_info;
SILK_API silk_status silk_vocab_get_info(silk_vocab_info* out);

/* ---- meshes ------------------------------------------------------------------------- */
typedef struct silk_mesh silk_mesh;

/* Copies the arrays: positions = 3*n_vertices doubles, triangles = 3*n_triangles indices.
 * *out: owned by the caller, silk_mesh_destroy. */
SILK_API silk_status silk_mesh_create(const double* positions, size_t n_vertices, const int32_t* triangles,
                                      size_t n_triangles, silk_mesh** out);
typedef struct silk_load_params {
  uint32_t struct_size; /* set by silk_load_default_params() */
  int32_t point_clouds; /* 1: a PLY without faces or an XYZ/PTS file is a point cloud (default);
                           0: every file is read as a mesh, as the tokenizer sees it (normals ignored) */
} silk_load_params;
SILK_API silk_load_params silk_load_default_params(void);
/* OBJ, PLY, STL, OFF, glTF/GLB, PMD, optionally gzip-compressed (params NULL = defaults). A PLY
 * without faces and an XYZ/PTS file (lines "x y z" or "x y z nx ny nz") are point clouds: they
 * load as a mesh with no triangles and one normal per vertex, which silk_generator_run samples as
 * points. A cloud without normals gets estimated ones (k-nearest-neighbour plane fits, oriented
 * outward along a minimum spanning tree; docs/normals.md); one that has them keeps them as read.
 * Read limits: 50M vertices, 50M triangles, 4 GiB per file; a .gz inflates to at most
 * max(64 MiB, 32 x its compressed size), checked while inflating (a decompression bomb is
 * refused with SILK_ERR_LIMIT naming the file, without allocating its output; docs/io.md).
 * *out: owned by the caller, silk_mesh_destroy. */
SILK_API silk_status silk_mesh_load(const char* path, const silk_load_params* params, silk_mesh** out);
typedef enum silk_mesh_format {
  SILK_FORMAT_BY_EXTENSION = 0,
  SILK_FORMAT_OBJ = 1,
  SILK_FORMAT_PLY = 2,
  SILK_FORMAT_GLB = 3
} silk_mesh_format;
typedef struct silk_save_params {
  uint32_t struct_size;    /* set by silk_save_default_params() */
  int32_t part_colors;     /* .glb: a distinct COLOR_0 per part; default 0 */
  const char* obj_comment; /* .obj: written first as "# ..." lines (one per line of the text); NULL
                              (default) or "": none. Borrowed: read during the call only */
  int32_t format;          /* silk_mesh_format; default SILK_FORMAT_BY_EXTENSION; another value writes
                              that format whatever the path's extension */
} silk_save_params;
SILK_API silk_save_params silk_save_default_params(void);
/* By extension (or params->format): .obj, .ply, or .glb (one node per part: triangles grouped by
 * component, smooth normals per part); written atomically (a failed save leaves no partial file).
 * params NULL = defaults. */
SILK_API silk_status silk_mesh_save(const silk_mesh* mesh, const char* path, const silk_save_params* params);
SILK_API void silk_mesh_destroy(silk_mesh* mesh);
/* Copies (size-query rule above; element counts): positions 3 doubles per vertex, triangles 3
 * indices per triangle, components one part index per triangle (decoded and generated meshes;
 * 0 for loaded ones), normals 3 doubles per vertex for point clouds (0 elements otherwise). */
SILK_API silk_status silk_mesh_copy_positions(const silk_mesh* mesh, double* out, size_t capacity, size_t* out_count);
SILK_API silk_status silk_mesh_copy_triangles(const silk_mesh* mesh, int32_t* out, size_t capacity, size_t* out_count);
SILK_API silk_status silk_mesh_copy_triangle_components(const silk_mesh* mesh, int32_t* out, size_t capacity,
                                                        size_t* out_count);
SILK_API silk_status silk_mesh_copy_normals(const silk_mesh* mesh, double* out, size_t capacity, size_t* out_count);
/* Point clouds: 1 when the mesh carries one normal per vertex. */
SILK_API int32_t silk_mesh_has_normals(const silk_mesh* mesh);

/* ---- files: the reads and writes every Silk tool makes ----------------------------- */
/* Every file libsilk reads (meshes, token files, model files, silk_file_read) must be a regular
 * file: a FIFO, device, socket or folder (a symlink to one included) is SILK_ERR_IO naming it and
 * what it is, refused before it is opened. Every file it writes (silk_mesh_save, silk_tokens_save,
 * silk_file_write) is written to a hidden temporary beside it (".<name>.tmp-<pid>"), synced and
 * renamed into place: a reader sees the old file or the whole new one, never a partial one.
 * SILK_OK when `path` can name an output file: not empty, not a folder, its folder exists, its
 * name fits the file system (and, on Windows, is not a reserved device name such as CON or NUL,
 * holds none of <>:"|?*, and does not end in a dot or space). Otherwise SILK_ERR_INVALID_ARGUMENT
 * naming the path and the problem. Creates nothing; for a check before long work. */
SILK_API silk_status silk_file_check_output(const char* path);
/* Writes `size` bytes to `path` atomically (as above; `bytes` may be NULL when size is 0).
 * SILK_ERR_INVALID_ARGUMENT (silk_file_check_output's reasons) or SILK_ERR_IO naming the path and
 * the OS reason (disk full, permission, ...); on failure `path` is untouched. */
SILK_API silk_status silk_file_write(const char* path, const void* bytes, size_t size);
/* The bytes of the regular file `path` (size-query rule above; out_count: bytes). Over
 * `max_bytes` is SILK_ERR_LIMIT, not a regular file SILK_ERR_IO, both naming the file. */
SILK_API silk_status silk_file_read(const char* path, uint64_t max_bytes, char* out, size_t capacity,
                                    size_t* out_count);
/* Removes the temporary of every write in progress in this process. Async-signal-safe: for a
 * signal handler that ends the process (the renamed outputs are kept, no partial file is left). */
SILK_API void silk_file_discard_partial(void);

/* ---- token sequences ---------------------------------------------------------------- */
typedef struct silk_tokens silk_tokens;
/* *out: owned by the caller, silk_tokens_destroy (also for silk_tokens_load). */
SILK_API silk_status silk_tokens_create(const int32_t* ids, size_t count, silk_tokens** out);
SILK_API silk_status silk_tokens_load(const char* path, silk_tokens** out); /* one id per line */
SILK_API silk_status silk_tokens_save(const silk_tokens* tokens, const char* path);
SILK_API void silk_tokens_destroy(silk_tokens* tokens);
/* The ids (size-query rule above). */
SILK_API silk_status silk_tokens_copy(const silk_tokens* tokens, int32_t* out, size_t capacity, size_t* out_count);

/* ---- encode: mesh -> tokens (bit-exact with the reference tokenizer) ---------------- */
typedef struct silk_encode_params {
  uint32_t struct_size;           /* set by silk_encode_default_params() */
  int32_t normalize;              /* 1: bounding-box normalise first (default); 0: already in [-1,1] */
  double normalize_bound;         /* default 0.95 */
  int32_t nonmanifold_processing; /* default 1 */
} silk_encode_params;
SILK_API silk_encode_params silk_encode_default_params(void);

typedef struct silk_encode_stats {
  uint32_t struct_size; /* set by the caller: sizeof(silk_encode_stats) */
  int32_t input_vertices, input_faces, processed_vertices, processed_faces;
  int32_t emitted_vertices, encodable_faces;
  int32_t components_found, components_encoded, components_dropped_small;
  int32_t layers, max_layer_size, max_layer_count;
  int64_t tokens;
  double seconds;
  /* clean-up before layering: input vertices merged as duplicates, faces dropped, vertices added
   * by non-manifold processing, faces flipped by the orientation pass */
  int32_t merged_vertices, dropped_degenerate_faces, dropped_duplicate_faces, nonmanifold_copies, flipped_faces;
  /* wall time per encoder phase, seconds (their sum is below `seconds`, which adds normalisation) */
  double seconds_quantize_cleanup, seconds_nonmanifold, seconds_orientation, seconds_components, seconds_layering,
      seconds_codecs, seconds_packing;
} silk_encode_stats;
/* params NULL = defaults; stats may be NULL. A refused mesh returns SILK_ERR_REFUSED with the
 * reason's name first in the message (e.g. "mobius: ..."). *out: owned, silk_tokens_destroy. */
SILK_API silk_status silk_mesh_encode(const silk_mesh* mesh, const silk_encode_params* params, silk_tokens** out,
                                      silk_encode_stats* stats);

/* ---- decode: tokens -> mesh (every face the tokens carry, consistently oriented) ----- */
typedef struct silk_decode_params {
  uint32_t struct_size;               /* set by silk_decode_default_params() */
  int32_t grid_coordinates;           /* 1: positions are grid integers 0..127; 0: dequantised [-1,1] (default) */
  int32_t split_nonmanifold_vertices; /* 1: every vertex whose faces form two or more fans is split (one
                                         copy per extra fan, same position, appended); 0: the mesh the
                                         tokens encode (default) */
} silk_decode_params;
SILK_API silk_decode_params silk_decode_default_params(void);
typedef struct silk_decode_stats {
  uint32_t struct_size;                /* set by the caller: sizeof(silk_decode_stats) */
  int32_t vertices, faces, components; /* components: C tokens read (a component may carry no face) */
  int32_t vertices_split;              /* split_nonmanifold_vertices: vertices split */
} silk_decode_stats;
/* params NULL = defaults; stats may be NULL. *out: owned, silk_mesh_destroy. */
SILK_API silk_status silk_tokens_decode(const silk_tokens* tokens, const silk_decode_params* params, silk_mesh** out,
                                        silk_decode_stats* stats);

/* ---- round trip: encode, decode, compare ---------------------------------------------- */
typedef struct silk_roundtrip_report {
  uint32_t struct_size; /* set by the caller: sizeof(silk_roundtrip_report) */
  int64_t tokens;
  int64_t processed_faces;     /* faces of the emitted components, after clean-up */
  int64_t representable_faces; /* processed faces whose three edges the stream carries */
  int64_t recovered;           /* representable faces decoded with the encoder's winding */
  int64_t reversed;            /* ... decoded with the opposite winding */
  int64_t missing;             /* ... not decoded */
  int64_t extra;               /* decoded faces that are not processed faces */
  int64_t decoded_faces;
  int32_t exact; /* 1: nothing missing or reversed */
} silk_roundtrip_report;
/* Encodes `mesh` (params as silk_mesh_encode), decodes the ids and compares faces by grid corners
 * and winding. A mesh the encoder refuses fails as in silk_mesh_encode; an inexact result is SILK_OK. */
SILK_API silk_status silk_mesh_roundtrip(const silk_mesh* mesh, const silk_encode_params* params,
                                         silk_roundtrip_report* out);

/* ---- reports: JSON documents some calls produce -------------------------------------- */
typedef struct silk_report silk_report;
/* The document, NUL-terminated. Borrowed: owned by the report, valid until silk_report_destroy. */
SILK_API const char* silk_report_json(const silk_report* report);
SILK_API void silk_report_destroy(silk_report* report);

/* ---- grammar check of a token stream (token_format.md §9, §11) ----------------------------------- */
typedef enum silk_window_rule {
  SILK_WINDOW_CANONICAL = 0, /* the encoder's rule: self-layer rows must agree about each pair */
  SILK_WINDOW_UNION = 1      /* the official decoder's: a pair is an edge if either row says so */
} silk_window_rule;
typedef struct silk_check_params {
  uint32_t struct_size; /* set by silk_check_default_params() */
  int32_t max_length;   /* tokens incl. EOS; 0 = unlimited; default 10240 (token_format.md §9) */
  int32_t window_rule;  /* silk_window_rule; default SILK_WINDOW_CANONICAL */
  int32_t allow_prefix; /* 1: a stream that stops inside a component is accepted; default 0 */
} silk_check_params;
SILK_API silk_check_params silk_check_default_params(void);
typedef struct silk_check_result {
  uint32_t struct_size; /* set by the caller: sizeof(silk_check_result) */
  int32_t accepted;     /* 1: every id is legal (and the stream ends after an E unless allow_prefix) */
  int32_t reason;       /* 0 when accepted, else a stable code named by silk_reject_reason_name */
  int64_t position;     /* index of the first rejected id (the count when the stream ends too early); -1 if accepted */
  int32_t id;           /* the rejected id; -1 past the end or when accepted */
  char message[512];    /* why, naming the rule and its spec section ("" when accepted; truncated, NUL-terminated) */
} silk_check_result;
/* Runs the ids (EOS optional at the end) through the grammar token by token. A rejected stream is
 * SILK_OK with accepted = 0; only bad arguments fail. */
SILK_API silk_status silk_tokens_check(const silk_tokens* tokens, const silk_check_params* params,
                                       silk_check_result* out);
/* "wrong_class", "not_canonical", ... for a silk_check_result reason ("none" for 0; "unknown" out
 * of range). A static string. */
SILK_API const char* silk_reject_reason_name(int32_t reason);

/* ---- hole repair of a token stream (token_format.md §12.2) --------------------------------------- */
/* What to do with holes (loops of open edges); also silk_generate_params.holes. */
typedef enum silk_hole_policy { SILK_HOLES_OFF = 0, SILK_HOLES_REPORT = 1, SILK_HOLES_REPAIR = 2 } silk_hole_policy;
typedef struct silk_repair_params {
  uint32_t struct_size;  /* set by silk_repair_default_params() */
  int32_t holes;         /* silk_hole_policy; default SILK_HOLES_REPAIR */
  int32_t max_fill_loop; /* longest hole loop (edges) that is triangulated; >= 0; default 8 */
} silk_repair_params;
SILK_API silk_repair_params silk_repair_default_params(void);
typedef struct silk_repair_stats {
  uint32_t struct_size;    /* set by the caller: sizeof(silk_repair_stats) */
  int64_t tokens_accepted; /* ids read before EOS, -1 padding or the first illegal id */
  int64_t illegal_at;      /* index of the first illegal id, -1 if none */
  int32_t vertices, faces, watertight;
  int32_t window_findings; /* self-layer disagreements OR-ed (the official decoder's rule) */
  int32_t holes_found, holes_repaired, faces_added, open_edges_before, open_edges_after;
} silk_repair_stats;
/* Reads the ids through the grammar (union window rule, no length limit) up to EOS, a -1 or the
 * first illegal id, then builds the mesh of the accepted prefix (closed layers) with the hole
 * policy; positions dequantised to [-1, 1]. stats and report may be NULL. *out_mesh: owned,
 * silk_mesh_destroy; *report: owned, silk_report_destroy; it
 * holds {"tokens_accepted", "illegal": null or {"position", "id", "reason", "message"},
 * "vertices", "faces", "watertight", "window_findings": [{"component", "layer", "row_a", "row_b"}],
 * "holes": [{"component", "loop", "layers", "repaired", "added_edges"}], "faces_added",
 * "open_edges_before", "open_edges_after"}. */
SILK_API silk_status silk_tokens_repair(const silk_tokens* tokens, const silk_repair_params* params,
                                        silk_mesh** out_mesh, silk_repair_stats* stats, silk_report** report);

/* ---- random legal token streams (property tests, fuzzing, demos) ---------------------- */
typedef struct silk_random_walk_params {
  uint32_t struct_size;   /* set by silk_random_walk_default_params() */
  uint64_t seed;          /* default 1 */
  int32_t max_components; /* 1..1000; default 2 */
  int32_t max_layers;     /* most layers per component after the root, 0..199 (0 acts as 1); default 6 */
  int32_t max_layer_size; /* largest target layer size, 0..200 (0 acts as 1); default 12 */
} silk_random_walk_params;
SILK_API silk_random_walk_params silk_random_walk_default_params(void);
/* One seeded walk: ids drawn uniformly from the grammar's legal masks (biased toward closing
 * layers) up to EOS (included), and the mesh they decode to (holes off, vertex fans resolved;
 * positions dequantised). out_mesh may be NULL. *out_tokens: owned, silk_tokens_destroy;
 * *out_mesh: owned, silk_mesh_destroy. */
SILK_API silk_status silk_tokens_random_walk(const silk_random_walk_params* params, silk_tokens** out_tokens,
                                             silk_mesh** out_mesh);

/* ---- pre-processing: mesh or point cloud -> the encoder's points ----------------------
 * The one implementation of the pre-processing a model was trained with (model.json
 * "preprocessing", docs/runtime.md); training code uses it too. */
typedef enum silk_preprocess_kind { SILK_PREPROCESS_SILK = 0, SILK_PREPROCESS_OFFICIAL = 1 } silk_preprocess_kind;
typedef struct silk_preprocess_params {
  uint32_t struct_size;           /* set by silk_preprocess_default_params() */
  int32_t kind;                   /* silk_preprocess_kind */
  double normalize_bound;         /* largest extent -> 2 * bound; 0.95 */
  double merge_distance_fraction; /* merge vertices closer than this share of the box diagonal (official 0.01) */
  int32_t surface_samples;        /* > point_count: sample this many, then draw point_count (official 50000);
                                     0 = point_count */
  int32_t round_float16;          /* 1: points and normals rounded to float16 before the draw (official); 0 or 1 */
  int32_t point_count;            /* rows produced (model.json preprocessing.n_points); 4096 */
} silk_preprocess_params;
/* The defaults of a kind (official: official_network.md §4; silk: Silk's own sampling). */
SILK_API silk_preprocess_params silk_preprocess_default_params(int32_t kind);
/* Either a mesh (cloud NULL) or an oriented point cloud (mesh NULL; n_cloud rows of 6 doubles x y z
 * nx ny nz) -> rows of 6 floats (normalised xyz, normal), all draws from `seed`. Size-query rule
 * above, in floats: *out_count = 6 * rows (rows = point_count, or n_cloud when the cloud is
 * smaller); the size query computes nothing. transform (may be NULL) receives cx, cy, cz, scale
 * with model = (input - c) * scale. params NULL = silk_preprocess_default_params(SILK_PREPROCESS_SILK). */
SILK_API silk_status silk_points_prepare(const silk_mesh* mesh, const double* cloud, size_t n_cloud,
                                         const silk_preprocess_params* params, uint64_t seed, float* out,
                                         size_t capacity, size_t* out_count, double* transform);

/* ---- generation: point cloud or mesh -> generated mesh ---------------------------------
 * Needs a libsilk built with onnxruntime (silk_generation_available() == 1); otherwise every
 * call below returns SILK_ERR_UNSUPPORTED.
 *
 * Ownership and threads (onnxruntime-genai's model/generator split):
 *  - a silk_model is immutable; any number of generators on any threads may share it. Each
 *    generator holds a reference to its model, so silk_model_destroy may come before the
 *    generators' destroy calls, even while they run (from another thread or from their own
 *    callbacks): the model is freed with its last generator. Calls that take the model handle
 *    itself (silk_generator_create, silk_model_get_*) must not race its destroy;
 *  - a silk_generator (KV cache, scratch, one generation in progress) serves one thread at a
 *    time: a call made while another thread is inside a call on the same generator fails with
 *    SILK_ERR_BUSY ("generator busy"). Use one generator per thread. Two calls are the
 *    exceptions and may come at any time, from any thread or from the generator's own progress
 *    and cancel callbacks: silk_generator_cancel, and silk_generator_destroy (see there: during a
 *    call it cancels the call and the generator is freed as that call returns). After destroy the
 *    handle is gone for every thread: a call that begins after it is a use after free;
 *  - inputs are borrowed for the length of the call: a silk_mesh, point array or params passed to
 *    silk_generator_run / silk_generator_start must not be destroyed or changed until it returns
 *    (its callbacks included). The same holds for every other call and handle (silk_mesh,
 *    silk_tokens, silk_report): none is reference counted or locked, so destroy one only when no
 *    call uses it;
 *  - all models in a process share one onnxruntime thread pool, sized by the first model loaded. */
typedef struct silk_model silk_model;
typedef struct silk_generator silk_generator;

SILK_API int32_t silk_generation_available(void);

/* Decoder precision; SILK_DECODER_INT8 keeps the value of the former "int8 = 1" option. */
typedef enum silk_decoder_precision {
  SILK_DECODER_DEFAULT = 0, /* model.json files.default_decoder */
  SILK_DECODER_INT8 = 1,
  SILK_DECODER_FP32 = 2,
  SILK_DECODER_INT4 = 3
} silk_decoder_precision;

/* Element type of the self-attention K/V cache (docs/runtime.md, "KV cache precision"). */
typedef enum silk_kv_precision {
  SILK_KV_DEFAULT = 0, /* the model's: model.json files.default_kv_precision when the chosen decoder has
                          that variant, else fp32 */
  SILK_KV_FP32 = 1,
  SILK_KV_FP16 = 2,
  SILK_KV_INT8 = 3 /* int8 values + one float32 scale per row (C API 1.2) */
} silk_kv_precision;

typedef struct silk_model_params {
  uint32_t struct_size; /* set by silk_model_default_params() */
  int32_t threads;      /* threads of the process's shared pool (first load decides); 0 = physical
                           cores (default); at most max(64, hardware threads) */
  int32_t decoder;      /* silk_decoder_precision (error if the model lacks that file); default SILK_DECODER_DEFAULT */
  int32_t kv_precision; /* silk_kv_precision (SILK_ERR_UNSUPPORTED naming the precision and folder if the
                           chosen decoder has no such variant); default SILK_KV_DEFAULT */
} silk_model_params;
SILK_API silk_model_params silk_model_default_params(void);
/* dir holds model.json, encoder.onnx, decoder.onnx (docs/model_contract.md); it may also be a model
 * name or "" for the bundled model (silk_model_find, C API 1.3). A model of another
 * format/token-format version is refused with SILK_ERR_UNSUPPORTED. Every file the folder names,
 * ONNX external data included, must resolve inside it (no absolute path, no "..", no symlink
 * leading out): otherwise SILK_ERR_PARSE naming the model file and the location. params NULL = defaults.
 * *out: owned by the caller, silk_model_destroy (generators keep the model alive, see above). */
SILK_API silk_status silk_model_load(const char* dir, const silk_model_params* params, silk_model** out);
SILK_API void silk_model_destroy(silk_model* model);

/* The network a model folder holds (model.json "arch"; silk_model_info.arch). */
typedef enum silk_arch {
  SILK_ARCH_SILK = 0,    /* "silk": Silk's own architecture */
  SILK_ARCH_OFFICIAL = 1 /* "official": the released Mesh Silksong network's (docs/official_network.md) */
} silk_arch;

typedef struct silk_model_info {
  uint32_t struct_size; /* set by the caller: sizeof(silk_model_info) */
  char config[32];      /* model.json "config" (truncated) */
  int32_t d_model, n_layers, n_heads, head_dim, n_latents;
  int32_t default_points; /* encoder points per generation by default (model.json dims.n_points) */
  int32_t max_seq_len;
  int32_t threads;
  /* Deprecated, removed in 2.0: 1 when decoder == SILK_DECODER_INT8 (read .decoder). */
  int32_t int8 SILK_DEPRECATED("silk_model_info.int8 is removed in 2.0: read .decoder");
  int32_t decoder;        /* silk_decoder_precision in use (never DEFAULT) */
  int32_t arch;           /* silk_arch */
  int32_t encoder_points; /* the encoder graph's fixed point count; -1 = any */
  int32_t kv_precision;   /* silk_kv_precision in use (never DEFAULT) */
} silk_model_info;
/* The model's pre-processing (model.json "preprocessing"); out->struct_size as for an out struct. */
SILK_API silk_status silk_model_get_preprocess_params(const silk_model* model, silk_preprocess_params* out);
SILK_API silk_status silk_model_get_info(const silk_model* model, silk_model_info* out);

/* ---- models by name (C API 1.3) ---------------------------------------------------------
 * A model argument (silk_model_load's dir, silkgen --model, silk_mesh.Model) is a folder or a
 * name. A path always wins: an existing folder is taken as it is. A model name (1-100 characters
 * of A-Z a-z 0-9 . _ -, not starting with '.' or '-', so never a separator or "..") that is not a
 * folder means <models folder>/<name>. The user's models folder: $SILK_MODELS, else
 * %LOCALAPPDATA%\silk\models on Windows, $XDG_DATA_HOME/silk/models (an absolute XDG_DATA_HOME) or
 * $HOME/.local/share/silk/models. Paths are UTF-8, copied by the size-query rule with capacity in
 * bytes, the terminating NUL included. */
/* name NULL: the models folder (it need not exist yet); else <models folder>/<name>
 * (SILK_ERR_INVALID_ARGUMENT stating the rule when name is not a model name). SILK_ERR_IO when no
 * variable gives a folder. */
SILK_API silk_status silk_models_dir(const char* name, char* out, size_t capacity, size_t* out_count);
/* The bundled model's folder, found beside libsilk: <lib>/../model (pip wheel, Blender add-on),
 * <lib>/../share/silk/models/default (cmake --install), <lib>/models/default (Windows zip), then a
 * build tree's source models/default. SILK_ERR_IO listing where it looked. */
SILK_API silk_status silk_model_default_dir(char* out, size_t capacity, size_t* out_count);
/* The folder silk_model_load takes for name_or_dir: NULL or "" = the bundled model; an existing
 * folder as given; a model name = <models folder>/<name> (SILK_ERR_IO naming both places when
 * neither exists); anything else as given (the load then names the missing folder). */
SILK_API silk_status silk_model_find(const char* name_or_dir, char* out, size_t capacity, size_t* out_count);
/* Every model a caller can name, read from model.json files (nothing is loaded), as a JSON report:
 * {"models_dir": PATH or null (+ "models_dir_error"), "models": [{"name", "dir", "bundled", "arch",
 * "config", "parameters": {"d_model", "n_layers", "n_heads"}, "bytes", "decoders", "default_decoder",
 * "kv_precisions", "default_kv_precision"}, ...], "not_listed": N}: the bundled model first (name
 * "default"), then each folder of the models folder by name; a folder that is not a usable model
 * has "error" instead of the model fields. SILK_ERR_UNSUPPORTED without onnxruntime. */
SILK_API silk_status silk_models_list(silk_report** out);

/* *out: owned by the caller, silk_generator_destroy. */
SILK_API silk_status silk_generator_create(const silk_model* model, silk_generator** out);
/* NULL is ignored. With no call on the generator in progress it is freed at once. During a call
 * (from another thread, or from that call's own progress or cancel callback) the call's run is
 * cancelled (the call returns SILK_ERR_CANCELLED, or SILK_ERR_BUSY for a query) and the generator
 * is freed as the call returns: never under it. Either way the handle must not be used again. */
SILK_API void silk_generator_destroy(silk_generator* generator);

/* Per candidate: with best of N (silk_generate_params.candidates) the counts start again for
 * each candidate, which `candidate` (0-based, of `candidates`) names. */
typedef struct silk_generate_progress {
  uint32_t struct_size;          /* set by the library: sizeof(silk_generate_progress) of this libsilk */
  int64_t tokens, max_tokens;    /* max_tokens == tokens on the candidate's last id (a bar reaches 100 %) */
  int32_t components;            /* started so far */
  int32_t faces;                 /* at the last layer end when max_faces is set (before the cap), else -1 */
  double seconds;                /* since the candidate's encoder run began */
  int32_t candidate, candidates; /* the candidate generating (0-based) and N */
} silk_generate_progress;
/* Called after every generated id (the last one included), on the calling thread. */
typedef void (*silk_progress_fn)(const silk_generate_progress* progress, void* user_data);
/* Polled as the call begins, before point sampling, every 65,536 surface samples, before each
 * candidate's encoder run, while the input's points are indexed for orientation, before every
 * id, and after a candidate's last id while its parts are oriented (before each face) and it is
 * scored (every 4,096 points: ~10 ms), except in silk_generator_finish (a finish must be able to
 * end a cancelled run); non-zero stops the generation with SILK_ERR_CANCELLED.
 * (silk_generator_cancel is honoured everywhere else too: see there.) */
typedef int32_t (*silk_cancel_fn)(void* user_data);

/* silk_generate_params.report_flags: what the generation keeps for silk_generator_report. */
enum {
  SILK_GENERATE_RECORD_TRACE = 1 /* keep the encoder points and every id's legal set (report trace 1) */
};
/* "Use the model's value" (model.json "sampling" / "preprocessing"): the one sentinel of
 * silk_generate_params.temperature, top_k, top_p, top_p_temperature, preprocessing, candidates,
 * face_guidance, face_tolerance and rows (their default). Exactly -1 (the value these fields always
 * took); any other negative, NaN or infinite value is SILK_ERR_INVALID_ARGUMENT naming the field
 * and value. (SILK_STOP_NONE, also -1, is a stop reason, not this.) */
#define SILK_MODEL_VALUE (-1)
/* The measured default of silk_generate_params.surface_tolerance. */
#define SILK_DEFAULT_SURFACE_TOLERANCE 2
/* Deprecated aliases of SILK_MODEL_VALUE for .candidates, removed in 2.0. */
#define SILK_MODEL_CANDIDATES SILK_MODEL_VALUE
#define SILK_DEFAULT_CANDIDATES SILK_MODEL_VALUE
/* Part orientation (silk_generate_params.orient). */
typedef enum silk_orientation {
  SILK_ORIENT_TOKENS = 0, /* the winding the ids carry (what decoding the token file gives) */
  SILK_ORIENT_INPUT = 1   /* each part turned to face the side the input's normals call outside */
} silk_orientation;
#define SILK_DEFAULT_ORIENT SILK_ORIENT_INPUT
/* Face guidance (silk_generate_params.face_guidance; C API 1.3). */
typedef enum silk_face_guidance {
  SILK_FACE_GUIDANCE_OFF = 0,  /* connectivity ids as the model draws them */
  SILK_FACE_GUIDANCE_HARD = 1, /* between-layer ids whose faces stray from the input are removed */
  SILK_FACE_GUIDANCE_SOFT = 2  /* their logits are lowered by how far they stray */
} silk_face_guidance;

/* temperature, top_k, top_p, top_p_temperature and preprocessing default to SILK_MODEL_VALUE (-1):
 * the model's (model.json "sampling" / "preprocessing"; v2 models: 0.5, 50, 1.0, 0, Silk's kind).
 * Any other value outside its range (silk_param_range below), NaN, and a flag or enum out of its
 * range is SILK_ERR_INVALID_ARGUMENT naming the field, its value and the range. */
typedef struct silk_generate_params {
  uint32_t struct_size;      /* set by silk_generate_default_params() */
  uint64_t seed;             /* default 0 */
  double temperature;        /* 0 = greedy */
  int32_t top_k;             /* 0 = off */
  double top_p;              /* 1.0 = off */
  int32_t max_tokens;        /* ids incl. EOS; 0 = the model's limit (default); else >= 14 (one triangle) */
  int32_t max_faces;         /* a hard cap on the result's faces; 0 = off (default). The generation stops at
                                the first layer end with >= max_faces faces; since that layer may overshoot,
                                the mesh (silk_generator_get_mesh too) keeps at most max_faces faces: in generation
                                order, each unless it would give a vertex a second fan, so the result stays
                                edge- and vertex-manifold and consistently oriented (it may have fewer than
                                max_faces; unused vertices and empty parts are dropped). The ids are not cut:
                                decoding them gives the whole last layer (docs/runtime.md "Caps") */
  int32_t holes;             /* silk_hole_policy, default SILK_HOLES_OFF */
  int32_t point_count;       /* encoder points; 0 = the model's (silk_model_info.default_points; default) */
  silk_progress_fn progress; /* may be NULL */
  silk_cancel_fn cancel;     /* may be NULL */
  void* user_data;           /* passed to both callbacks */
  double top_p_temperature; /* > 0: top-p on the top-k logits at this temperature (official chain); 0: at temperature */
  int32_t preprocessing;    /* silk_preprocess_kind with that kind's defaults */
  int32_t
      raw_points; /* 1 (point clouds only): the points are the encoder input as given, output in the model's frame */
  int32_t report_flags; /* SILK_GENERATE_* bits (SILK_GENERATE_RECORD_TRACE); default 0 */
  /* Surface guidance: each new vertex's block and offset ids are restricted to grid cells (of the
   * model's 128^3 grid) within this many cells (Euclidean) of a cell holding an encoder point;
   * when no legal id is that close, the nearest legal ones are kept (a "fallback" in the stats),
   * so the mask never empties. 0 = off; 0..127.
   * Default: SILK_DEFAULT_SURFACE_TOLERANCE (chosen by measurement, docs/runtime.md). */
  int32_t surface_tolerance;
  /* Best of N, 1..64: a generation runs N candidates (up to `rows` of them decoded together, below)
   * on the same encoder points with seeds derived from `seed` (candidate 0: seed itself, so N = 1 is a plain run;
   * candidate i >= 1: the first SplitMix64 output seeded with seed + i) and returns the one whose
   * surface is closest to the input (symmetric Chamfer distance to the encoder's points; one with
   * faces always beats one without). silk_generator_run and the step-wise API alike (the same ids and
   * mesh for the same params): step-wise, advance runs the candidates in turn, silk_generator_get_mesh
   * shows the one in progress and finish returns the chosen one. Default: SILK_MODEL_VALUE (-1), the model's N
   * (model.json "sampling.candidates", chosen by measurement for that model: docs/runtime.md;
   * 1 when the model names none). */
  int32_t candidates;
  /* silk_orientation. SILK_ORIENT_INPUT: every generated part whose winding disagrees with the
   * encoder's points' normals (the sum over its faces of area * dot(face normal, normal of the
   * nearest point) is negative) has all its faces reversed, in the final mesh and in
   * silk_generator_get_mesh; the ids are unchanged. Default: SILK_DEFAULT_ORIENT (docs/runtime.md). */
  int32_t orient;
  /* Reserved, 0 (the default). C API 1.0-1.3 had two measurement switches here ("unconstrained",
   * "debug_flags"); they left the public API, and a non-zero value is SILK_ERR_INVALID_ARGUMENT
   * naming the slot, so a caller that set one never silently gets a different generation. */
  int32_t reserved[2];
  /* ---- appended in C API 1.3 (a 1.0-1.2 caller's shorter struct gets the defaults) ---- */
  /* Face guidance: each legal between-layer id is judged by the faces it would close (their
   * corners, edge midpoints and centroid within face_tolerance cells of the input's points, their
   * normals within 60 degrees of the nearby input normals, up to sign); silk_face_guidance.
   * Default SILK_MODEL_VALUE (-1): the model's (model.json "sampling.face_guidance"), else
   * libsilk's measured default (docs/runtime.md "Face guidance"). */
  int32_t face_guidance;
  double face_tolerance; /* cells, 0.5..64; default SILK_MODEL_VALUE (-1): the model's, else libsilk's */
  /* ---- appended in C API 1.5 (a 1.0-1.4 caller's shorter struct gets the default) ---- */
  /* Best of N: how many of the candidates are decoded together, at most, 1..64. Rows of one
   * decoder call read every weight once; each candidate's ids are exactly those it gets alone
   * (same seeds), so the result does not depend on rows, only the time does. 1: the candidates
   * one after another (as C API 1.0-1.4 ran them; for baselines and checks). With N candidates
   * min(rows, N) rows are used (1 with a model folder before decoder contract v4, whose decoder
   * takes one row per call, and with the INT8 decoder, whose rows would move each other's ids:
   * its activations take one quantization scale per call); a candidate that ends leaves its row to the next candidate.
   * Default SILK_MODEL_VALUE (-1): the model's (model.json "sampling.rows"), else libsilk's 8. */
  int32_t rows;
} silk_generate_params;
SILK_API silk_generate_params silk_generate_default_params(void);

/* The valid values of a numeric generation setting, from the one table the generation calls check
 * against (C API 1.4). `name` is the field's name in silk_generate_params or silk_model_params:
 * "temperature", "top_k", "top_p", "top_p_temperature", "max_tokens", "max_faces",
 * "surface_tolerance", "face_tolerance", "candidates", "rows" (C API 1.5), "point_count", "threads";
 * and silk_batch_params' "parallel" (C API 1.6).
 * silk_param_range: *lo..*hi inclusive (*hi = INT32_MAX: no upper bound); *zero_too = 1 where 0
 * is valid as well though below *lo (max_tokens, point_count: "the model's"); any out may be NULL.
 * silk_param_check: SILK_OK when `value` is valid, else SILK_ERR_INVALID_ARGUMENT with the message
 * the generation calls give ("temperature 150 is not in [0, 100] (0 = greedy)"); SILK_MODEL_VALUE
 * is not a value here. Both: SILK_ERR_INVALID_ARGUMENT for an unknown name, SILK_ERR_UNSUPPORTED
 * without generation (silk_generation_available() == 0). */
SILK_API silk_status silk_param_range(const char* name, double* lo, double* hi, int32_t* zero_too);
SILK_API silk_status silk_param_check(const char* name, double value);

typedef enum silk_stop_reason {
  SILK_STOP_NONE = -1, /* still running */
  SILK_STOP_EOS = 0,
  SILK_STOP_MAX_TOKENS = 1,
  SILK_STOP_MAX_FACES = 2,
  SILK_STOP_GRAMMAR_DEAD_END = 3, /* no legal id left (a grammar bug; the closed part is returned) */
  SILK_STOP_CANCELLED = 4
} silk_stop_reason;
/* "eos", "max_tokens", "max_faces", "grammar_dead_end", "cancelled" ("none" for SILK_STOP_NONE;
 * "unknown" out of range). */
SILK_API const char* silk_stop_reason_name(int32_t reason);

/* The caller sets struct_size (silk_generate_stats st = {sizeof st};); the library writes only
 * struct_size bytes. */
typedef struct silk_generate_stats {
  uint32_t struct_size;
  int64_t tokens, forced_tokens, sampled_tokens, model_calls;
  int32_t stop_reason; /* silk_stop_reason */
  int32_t faces, vertices, components;
  int32_t holes_found, holes_repaired, faces_added;
  int32_t edge_manifold, watertight, consistently_oriented, open_edges;
  int64_t illegal_at; /* -1: every id is legal (the grammar mask guarantees it; in-tree measurement
                        runs without the mask give the index of the first id it rejects) */
  /* vertex_manifold: the faces around every vertex of the output form one fan; the decoder's
   * vertex-fan rule closed fan_gaps_closed gaps (repair policy) and split vertices_split vertices */
  int32_t vertex_manifold, nonmanifold_vertices, fan_gaps_closed, vertices_split;
  /* surface guidance: vertex ids sampled under it; vertex ids (sampled or forced) taken outside
   * the tolerance because no legal id was within it */
  int64_t guided_tokens, guidance_fallbacks;
  int32_t candidates;       /* candidates run (N; after a cancel those started, the cancelled one
                               included, whose score is 0 when it was not scored). During a
                               step-wise run: N */
  int32_t chosen_candidate; /* index of the returned one (the report JSON lists every seed and score);
                               during a step-wise run: the one in progress */
  double score;             /* returned mesh: symmetric Chamfer distance to the encoder's points, model frame */
  int32_t parts_flipped;    /* surface patches (faces joined by edges) turned to face the input (params.orient) */
  /* ---- timings (measurement; seconds, wall clock) ---- */
  double tokens_per_second;
  double seconds_prepare, seconds_encoder, seconds_decoder, seconds_grammar, seconds_sampling, seconds_build_mesh,
      seconds_guidance, seconds_scoring, seconds_total;
  /* ---- appended in C API 1.3 ---- */
  /* face guidance: between-layer ids sampled under it; of those, the steps where no legal one's
   * faces passed (hard: the best-scoring kept; soft: all penalised); its seconds */
  int64_t face_guided_tokens, face_fallbacks;
  double seconds_face_guidance;
  /* ---- appended in C API 1.5 ---- */
  int32_t rows; /* best of N's rows used: min(params.rows, candidates) candidates decoded together */
} silk_generate_stats;

/* What to generate from: exactly one of mesh / points (or a point-cloud silk_mesh), borrowed for
 * the call. The caller sets struct_size (silk_generate_input in = {sizeof in};). */
typedef struct silk_generate_input {
  uint32_t struct_size;
  const silk_mesh* mesh; /* a mesh (area-weighted surface samples with normals) or a point cloud
                            (a silk_mesh without triangles, with normals: a seeded subset) */
  const double* points;  /* or point_rows rows of 6 doubles (x y z nx ny nz), input frame */
  size_t point_rows;     /* (params.raw_points: the encoder's input as is, output in the model frame) */
} silk_generate_input;

/* ---- step-wise generation --------------------------------------------------------------
 * start -> advance ... (done) -> finish. start prepares the points and runs the encoder; each
 * advance adds ids; silk_generator_get_tokens / _get_mesh / _get_stats show
 * the state at any point (tokens and mesh: those of the candidate in progress, the mesh being the
 * faces of its layers completed so far, in the input frame); finish returns the final mesh (hole
 * policy, verdicts) and ends the generation. With best of N (params.candidates) the candidates
 * run in turn inside advance, done comes after the last, and finish returns the chosen one:
 * exactly what silk_generator_run returns for the same params. A new start discards an unfinished one. */
SILK_API silk_status silk_generator_start(silk_generator* generator, const silk_generate_input* input,
                                          const silk_generate_params* params);
typedef enum silk_advance_until {
  SILK_ADVANCE_IDS = 0,  /* max_ids ids (fewer if the generation ends), across candidates */
  SILK_ADVANCE_LAYER = 1 /* up to the next completed layer or the end of a candidate, at most max_ids ids */
} silk_advance_until;
/* max_ids >= 1. When a candidate before the last has ended, the next advance scores it and starts
 * the next one (its encoder run) before adding ids. *out_done (may be NULL) becomes 1 once the
 * last candidate has a stop reason. A cancel (the params' cancel callback or silk_generator_cancel)
 * returns SILK_ERR_CANCELLED, ends the run and leaves it finishable: finish then returns the best of
 * the candidates so far (the one cancelled with its completed layers) and stop reason CANCELLED. */
SILK_API silk_status silk_generator_advance(silk_generator* generator, int32_t max_ids, int32_t until,
                                            int32_t* out_done);
/* Thread-safe, any time, also from the generator's own callbacks. Cancels the run in progress: a
 * silk_generator_run call from its first instruction to its return, or a step-wise generation from
 * silk_generator_start until silk_generator_finish (or a failed start). With no run in progress
 * it does nothing (it never reaches a later run). A cancelled silk_generator_run returns
 * SILK_ERR_CANCELLED with no mesh or ids, whenever in the call the cancel came (input conversion
 * and checks, point sampling and the encoder run are interrupted, ids stop before the next one,
 * scoring stops within ~10 ms; one that comes after the last of these still cancels the call).
 * Step-wise: start returns SILK_ERR_CANCELLED, or (cancel after start's last poll) the next
 * advance does; finish still returns the candidates' best so far (see silk_generator_advance). */
SILK_API void silk_generator_cancel(silk_generator* generator);
/* The ids so far (during a generation: the candidate in progress; after it: the last run's).
 * *out: a new silk_tokens owned by the caller, silk_tokens_destroy (a copy: later advances do not change it). */
SILK_API silk_status silk_generator_get_tokens(silk_generator* generator, silk_tokens** out);
/* During a generation only: the faces of the completed layers, input frame.
 * *out: a new silk_mesh owned by the caller, silk_mesh_destroy (a copy). */
SILK_API silk_status silk_generator_get_mesh(silk_generator* generator, silk_mesh** out);
/* During a generation: tokens, counters, faces of the completed layers, stop reason (NONE while
 * running). After finish: the final figures, as silk_generator_run fills them. out->struct_size
 * as for every out struct (set by the caller). */
SILK_API silk_status silk_generator_get_stats(silk_generator* generator, silk_generate_stats* out);
/* out_mesh required, out_tokens and stats may be NULL. Scores the last candidate and returns the
 * chosen one. Before the end, it cancels first (as above). *out_mesh: owned by the caller,
 * silk_mesh_destroy; *out_tokens: owned by the caller, silk_tokens_destroy (both NULL on error). */
SILK_API silk_status silk_generator_finish(silk_generator* generator, silk_mesh** out_mesh, silk_tokens** out_tokens,
                                           silk_generate_stats* stats);
/* The last finished generation as a JSON report (settings, input, figures; trace 1: also the
 * encoder points and every id's legal set, for a generation run with report_flags
 * SILK_GENERATE_RECORD_TRACE).
 * *out: owned by the caller, silk_report_destroy. */
SILK_API silk_status silk_generator_report(silk_generator* generator, int32_t trace, silk_report** out);
/* The encoder's points of the current or last generation (from its start on), in the input's
 * frame: rows of 6 doubles x y z nx ny nz (the model-frame floats with the normalisation undone;
 * unit normals; raw_points: as given). A point cloud loaded without normals shows the estimated
 * ones. Copy rule: capacity and *out_count in doubles (6 per point); before any generation
 * SILK_ERR_INVALID_ARGUMENT. */
SILK_API silk_status silk_generator_copy_points(silk_generator* generator, double* out, size_t capacity,
                                                size_t* out_count);

/* ---- one-call generation: start + advance to the end + finish --------------------------
 * From any input (a mesh, a point-cloud silk_mesh or rows of points). The result is in the
 * input's frame; silk_mesh_copy_triangle_components gives each triangle's part. out_tokens and
 * stats may be NULL; after a cancel, stats are still filled (stop reason CANCELLED).
 * *out_mesh: owned by the caller, silk_mesh_destroy; *out_tokens: owned by the caller,
 * silk_tokens_destroy (both NULL on error). */
SILK_API silk_status silk_generator_run(silk_generator* generator, const silk_generate_input* input,
                                        const silk_generate_params* params, silk_mesh** out_mesh,
                                        silk_tokens** out_tokens, silk_generate_stats* stats);

/* ---- names of the enums (C API 1.4) ------------------------------------------------------
 * The one spelling of each enum's values: the names silkgen's options, model.json, the reports
 * and the Python binding use. silk_<enum>_name(value) returns a static string, "unknown" for a
 * value out of range (never NULL). Each enum's values are contiguous from its first one (-1 for
 * silk_stop_reason, else 0): a client lists the names by counting up until "unknown".
 * silk_<enum>_from_name(name, out) sets *out to the value of that exact (lower-case) name, or
 * returns SILK_ERR_INVALID_ARGUMENT naming the text and the accepted names (*out unchanged).
 * silk_status_name (above) stays the status's readable text. */
SILK_API const char* silk_log_level_name(int32_t level); /* "debug", "info", "warn", "error" */
SILK_API silk_status silk_log_level_from_name(const char* name, int32_t* out);
SILK_API const char* silk_mesh_format_name(int32_t format); /* "by_extension", "obj", "ply", "glb" */
SILK_API silk_status silk_mesh_format_from_name(const char* name, int32_t* out);
SILK_API const char* silk_window_rule_name(int32_t rule); /* "canonical", "union" */
SILK_API silk_status silk_window_rule_from_name(const char* name, int32_t* out);
SILK_API const char* silk_hole_policy_name(int32_t policy); /* "off", "report", "repair" */
SILK_API silk_status silk_hole_policy_from_name(const char* name, int32_t* out);
SILK_API const char* silk_preprocess_kind_name(int32_t kind); /* "silk", "official" */
SILK_API silk_status silk_preprocess_kind_from_name(const char* name, int32_t* out);
SILK_API const char* silk_decoder_precision_name(int32_t precision); /* "default", "int8", "fp32", "int4" */
SILK_API silk_status silk_decoder_precision_from_name(const char* name, int32_t* out);
SILK_API const char* silk_kv_precision_name(int32_t precision); /* "default", "fp32", "fp16", "int8" */
SILK_API silk_status silk_kv_precision_from_name(const char* name, int32_t* out);
SILK_API const char* silk_arch_name(int32_t arch); /* silk_model_info.arch: "silk", "official" */
SILK_API silk_status silk_arch_from_name(const char* name, int32_t* out);
SILK_API const char* silk_orientation_name(int32_t orient); /* "tokens", "input" */
SILK_API silk_status silk_orientation_from_name(const char* name, int32_t* out);
SILK_API const char* silk_face_guidance_name(int32_t guidance); /* "off", "hard", "soft" */
SILK_API silk_status silk_face_guidance_from_name(const char* name, int32_t* out);
SILK_API const char* silk_advance_until_name(int32_t until); /* "ids", "layer" */
SILK_API silk_status silk_advance_until_from_name(const char* name, int32_t* out);
/* silk_stop_reason_name is declared beside silk_stop_reason ("none" ... "cancelled"). */
SILK_API silk_status silk_stop_reason_from_name(const char* name, int32_t* out);

/* ---- best of N's candidates while they run (C API 1.5) -----------------------------------
 * The step-wise view of every candidate of the generation in progress (params.candidates = N),
 * not only the one silk_generator_get_mesh shows: whether a candidate waits, generates, has ended
 * or has been scored, its ids and faces so far, its score, the best so far, and its mesh. The
 * candidates run one after another or together as rows of one decoder call: the view is the same.
 * Like silk_generator_get_mesh these answer during a generation only (from a successful start
 * until finish; a cancelled run stays viewable until its finish): otherwise, and for an index
 * outside [0, N), SILK_ERR_INVALID_ARGUMENT (the message names the index and N). Same generator
 * rules as the other step-wise queries: one call at a time on a generator (SILK_ERR_BUSY while
 * another call, e.g. an advance on another thread or inside its own callbacks, is in it). */
typedef enum silk_candidate_state {
  SILK_CANDIDATE_WAITING = 0, /* not started */
  SILK_CANDIDATE_RUNNING = 1, /* generating ids; also one whose ids have ended but whose mesh is not built
                                 yet (one after another: until the next advance, the last one until finish) */
  SILK_CANDIDATE_ENDED = 2,   /* its ids have ended and its mesh is built; not scored yet */
  SILK_CANDIDATE_SCORED = 3   /* scored: score set, compared with the others scored so far */
} silk_candidate_state;
SILK_API const char* silk_candidate_state_name(int32_t state); /* "waiting", "running", "ended", "scored" */
SILK_API silk_status silk_candidate_state_from_name(const char* name, int32_t* out);

/* One candidate as silk_generator_get_candidate fills it. The caller sets struct_size
 * (silk_candidate_info c = {sizeof c};); fields may only be appended. */
typedef struct silk_candidate_info {
  uint32_t struct_size;
  int32_t index;  /* 0 .. N-1: the seed order, as silk_generate_stats.chosen_candidate counts */
  int32_t state;  /* silk_candidate_state */
  int32_t faces;  /* ended or scored: its mesh's faces; -1 (unknown) while waiting or running */
  int64_t tokens; /* its ids so far (0 while waiting) */
  double score;   /* scored only (lower is better, as silk_generate_stats.score); NaN otherwise */
  int32_t best;   /* 1: the best of those scored so far (the one finish returns if no later one beats it) */
} silk_candidate_info;

/* *n = N, the candidates of the generation in progress. */
SILK_API silk_status silk_generator_candidate_count(silk_generator* generator, int32_t* n);
/* Candidate `index` of the generation in progress into *out (struct_size bytes at most). */
SILK_API silk_status silk_generator_get_candidate(silk_generator* generator, int32_t index, silk_candidate_info* out);
/* Candidate `index`'s mesh in the input frame: while it runs, the faces of its completed layers
 * (as silk_generator_get_mesh shows the one in progress); once ended, its whole mesh; a mesh with
 * no faces while it waits.
 * *out: a new silk_mesh owned by the caller, silk_mesh_destroy (a copy). */
SILK_API silk_status silk_generator_get_candidate_mesh(silk_generator* generator, int32_t index, silk_mesh** out);

/* ---- a batch of inputs, several meshes decoded together (C API 1.6) ----------------------
 * Pull-style: add inputs (each with its own silk_generate_params), then pull each finished one
 * with silk_batch_next as soon as it ends, with its input index (the order added: 0, 1, ...), so a
 * caller writes outputs as they end and reports in input order. Up to params.parallel meshes are
 * in flight at once as rows of one decoder call (a model folder of decoder contract v4): every
 * weight is read once per step for all of them; a freed row goes to the next candidate of the
 * first mesh in input order that has one to start. Each input's mesh, ids and figures (timings
 * aside) are exactly those silk_generator_run returns for the same input and params; parallel 1,
 * or a folder before contract v4 (one row per call), runs the inputs one after another. An input's
 * error (bad points, a refused param) is its own result and never stops the others. One call at a
 * time on a batch (SILK_ERR_BUSY otherwise, e.g. from inside its own callbacks); silk_batch_cancel
 * is thread-safe. */
typedef struct silk_batch silk_batch;
/* Progress of input `input` (its own candidate and candidates in the report). */
typedef void (*silk_batch_progress_fn)(int32_t input, const silk_generate_progress* progress, void* user_data);
typedef struct silk_batch_params {
  uint32_t struct_size; /* set by silk_batch_default_params() */
  /* Meshes in flight at most, 1..16 (silk_param_range("parallel")); 1: one after another (the
   * default, as a loop of silk_generator_run). */
  int32_t parallel;
  /* Decoder rows per mesh in flight (the batch holds parallel x rows), 1..64; each mesh's candidates
   * take at most min(its params' rows, its candidates) at once. Default SILK_MODEL_VALUE (-1): the
   * model's (model.json "sampling.rows"), else 8. */
  int32_t rows;
  silk_batch_progress_fn progress; /* may be NULL; the inputs' own params.progress is not called */
  silk_cancel_fn cancel;           /* may be NULL; polled as silk_generator_run polls it: stops the batch */
  void* user_data;                 /* passed to both */
} silk_batch_params;
SILK_API silk_batch_params silk_batch_default_params(void);
/* A batch on `model` (which it keeps alive). *out: owned by the caller, silk_batch_destroy. */
SILK_API silk_status silk_batch_create(const silk_model* model, const silk_batch_params* params, silk_batch** out);
SILK_API void silk_batch_destroy(silk_batch* batch);
/* Queues an input (copied: the caller's mesh or points may go) with its params (NULL: the
 * defaults; progress, cancel and user_data there are not used: the batch's are). *out_index (may
 * be NULL): its index. The params and input are checked when the input starts: their errors come
 * back from silk_batch_next as that input's result. SILK_ERR_INVALID_ARGUMENT after
 * silk_batch_close or a cancel. Add at most a few inputs beyond parallel ahead of the pulls: a
 * queued input holds its copy (and, in rows, its encoder points) until it starts. */
SILK_API silk_status silk_batch_add(silk_batch* batch, const silk_generate_input* input,
                                    const silk_generate_params* params, int32_t* out_index);
/* No more inputs: silk_batch_add is refused from now on (the queued ones still run). */
SILK_API silk_status silk_batch_close(silk_batch* batch);
/* Runs until an input ends and returns its result: *out_index its index; SILK_OK with *out_mesh
 * (owned by the caller, silk_mesh_destroy), *out_tokens and stats (both may be NULL) as
 * silk_generator_run fills them; or the input's error (silk_last_error names it) with the outs
 * NULL / blank. After a cancel (params.cancel or silk_batch_cancel) the inputs in flight come back
 * with SILK_ERR_CANCELLED (stats: stop reason CANCELLED), and so do the queued ones, never started
 * (every input added comes back exactly once). When no
 * input is queued or in flight: SILK_ERR_INVALID_ARGUMENT with *out_index -1. */
SILK_API silk_status silk_batch_next(silk_batch* batch, int32_t* out_index, silk_mesh** out_mesh,
                                     silk_tokens** out_tokens, silk_generate_stats* stats);
/* Inputs in flight (started, not ended) and queued (added, not started): either may be NULL. */
SILK_API silk_status silk_batch_counts(silk_batch* batch, int32_t* in_flight, int32_t* queued);
/* Thread-safe, any time: cancels the batch (the silk_batch_next in progress returns soon). */
SILK_API void silk_batch_cancel(silk_batch* batch);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* SILK_SILK_H_ */
