/* silk.h — the one public C API of libsilk (Mesh Silksong engine).
 * Opaque handles, create/destroy pairs, *_default_params(), status codes plus a per-thread
 * error message, query-then-copy buffers; no exception ever crosses this boundary. */
#ifndef SILK_SILK_H_
#define SILK_SILK_H_

#include <stddef.h>
#include <stdint.h>

#if defined(_WIN32)
#define SILK_API __declspec(dllexport)
#else
#define SILK_API __attribute__((visibility("default")))
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* ---- status and errors ------------------------------------------------------------- */
typedef enum silk_status {
  SILK_OK = 0,
  SILK_ERR_INVALID_ARGUMENT = 1,
  SILK_ERR_IO = 2,
  SILK_ERR_PARSE = 3,
  SILK_ERR_UNSUPPORTED = 4,
  SILK_ERR_REFUSED = 5,        /* the tokenizer refuses the mesh (named reason in the message) */
  SILK_ERR_LIMIT = 6,
  SILK_ERR_CANCELLED = 7,
  SILK_ERR_INTERNAL = 8,
  SILK_ERR_BUFFER_TOO_SMALL = 9
} silk_status;

/* Message of the last failed call on this thread ("" if none). Valid until the next call. */
SILK_API const char* silk_last_error(void);
SILK_API const char* silk_status_name(silk_status s);
SILK_API const char* silk_version(void);

/* ---- logging: the library prints nothing itself ------------------------------------ */
typedef enum silk_log_level { SILK_LOG_DEBUG = 0, SILK_LOG_INFO = 1, SILK_LOG_WARN = 2, SILK_LOG_ERROR = 3 } silk_log_level;
typedef void (*silk_log_fn)(silk_log_level level, const char* message, void* user_data);
/* Process-wide; NULL disables logging (the default). */
SILK_API void silk_set_log_callback(silk_log_fn fn, void* user_data);

/* ---- vocabulary (single source: engine/tokenizer/vocabulary_layout.json) ------------ */
typedef struct silk_vocab_info {
  int32_t token_format_version;
  int32_t format_vocab_size; /* 10267: ids 0..10266 */
  int32_t eos_id, pad_id, model_vocab_size;
  int32_t c_id, u_id, e_id;
  int32_t x_begin, x_end, s_begin, s_end, b_begin, b_end, k_begin, k_end, o_begin, o_end;
  int32_t quant_bins, layer_vertex_limit, layer_count_limit, max_faces, max_seq_length;
} silk_vocab_info;
SILK_API silk_vocab_info silk_vocab(void);

/* ---- meshes ------------------------------------------------------------------------- */
typedef struct silk_mesh silk_mesh;
/* Copies the arrays: positions = 3*n_vertices doubles, triangles = 3*n_triangles indices. */
SILK_API silk_status silk_mesh_create(const double* positions, size_t n_vertices, const int32_t* triangles,
                                      size_t n_triangles, silk_mesh** out);
/* OBJ, PLY, STL, OFF, glTF/GLB, PMD, optionally gzip-compressed. */
SILK_API silk_status silk_mesh_load(const char* path, silk_mesh** out);
/* By extension: .obj or .ply; written atomically. */
SILK_API silk_status silk_mesh_save(const silk_mesh* mesh, const char* path);
SILK_API void silk_mesh_destroy(silk_mesh* mesh);
SILK_API size_t silk_mesh_vertex_count(const silk_mesh* mesh);
SILK_API size_t silk_mesh_triangle_count(const silk_mesh* mesh);
/* Query-then-copy: capacity in elements (3 per vertex / triangle). */
SILK_API silk_status silk_mesh_copy_positions(const silk_mesh* mesh, double* out, size_t capacity);
SILK_API silk_status silk_mesh_copy_triangles(const silk_mesh* mesh, int32_t* out, size_t capacity);
/* Component index per triangle (decoded meshes; 0 for loaded ones). capacity = triangles. */
SILK_API silk_status silk_mesh_copy_triangle_components(const silk_mesh* mesh, int32_t* out, size_t capacity);

/* ---- token sequences ---------------------------------------------------------------- */
typedef struct silk_tokens silk_tokens;
SILK_API silk_status silk_tokens_create(const int32_t* ids, size_t count, silk_tokens** out);
SILK_API silk_status silk_tokens_load(const char* path, silk_tokens** out); /* one id per line */
SILK_API silk_status silk_tokens_save(const silk_tokens* tokens, const char* path);
SILK_API void silk_tokens_destroy(silk_tokens* tokens);
SILK_API size_t silk_tokens_count(const silk_tokens* tokens);
SILK_API silk_status silk_tokens_copy(const silk_tokens* tokens, int32_t* out, size_t capacity);

/* ---- encode: mesh -> tokens (bit-exact with the reference tokenizer) ---------------- */
typedef struct silk_encode_params {
  int32_t normalize;              /* 1: bounding-box normalise first (default); 0: already in [-1,1] */
  double normalize_bound;         /* default 0.95 */
  int32_t nonmanifold_processing; /* default 1 */
} silk_encode_params;
SILK_API silk_encode_params silk_encode_default_params(void);

typedef struct silk_encode_stats {
  int32_t input_vertices, input_faces, processed_vertices, processed_faces;
  int32_t emitted_vertices, encodable_faces;
  int32_t components_found, components_encoded, components_dropped_small;
  int32_t layers, max_layer_size, max_layer_count;
  int64_t tokens;
  double seconds;
} silk_encode_stats;
/* stats may be NULL. A refused mesh returns SILK_ERR_REFUSED with the reason's name first in
 * the message (e.g. "mobius: ..."). */
SILK_API silk_status silk_encode(const silk_mesh* mesh, const silk_encode_params* params, silk_tokens** out,
                                 silk_encode_stats* stats);

/* ---- decode: tokens -> mesh (every face the tokens carry, consistently oriented) ----- */
typedef struct silk_decode_params {
  int32_t grid_coordinates; /* 1: positions are grid integers 0..127; 0: dequantised [-1,1] (default) */
} silk_decode_params;
SILK_API silk_decode_params silk_decode_default_params(void);
SILK_API silk_status silk_decode(const silk_tokens* tokens, const silk_decode_params* params, silk_mesh** out);

#ifdef __cplusplus
} /* extern "C" */
#endif

#endif /* SILK_SILK_H_ */
