/* SPDX-License-Identifier: MIT */
/* Compiles silk.h as plain C (C99) and exercises it: encode a tetrahedron, decode it back,
 * the generation entry points' argument/availability errors, and the point pre-processing. */
#include <stdio.h>
#include <string.h>

#include "silk/silk.h"

int main(void) {
  const double xyz[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  const int32_t tris[12] = {0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3};
  silk_mesh* mesh = NULL;
  silk_tokens* tokens = NULL;
  silk_mesh* back = NULL;
  silk_encode_params ep = silk_encode_default_params();
  silk_encode_stats stats = {.struct_size = sizeof stats};
  size_t count = 0;
  if (silk_mesh_create(xyz, 4, tris, 4, &mesh) != SILK_OK) return 1;
  if (silk_mesh_encode(mesh, &ep, &tokens, &stats) != SILK_OK) {
    fprintf(stderr, "encode: %s\n", silk_last_error());
    return 2;
  }
  if (silk_tokens_copy(tokens, NULL, 0, &count) != SILK_OK || count != 17 || stats.processed_faces != 4)
    return 3; /* token_format.md §8.3: 17 tokens */
  if (silk_tokens_decode(tokens, NULL, &back, NULL) != SILK_OK) return 4;
  if (silk_mesh_copy_triangles(back, NULL, 0, &count) != SILK_OK || count != 12) return 5;
  if (silk_mesh_copy_positions(back, NULL, 0, &count) != SILK_OK || count != 12) return 5;
  /* errors: NULL arguments give a status and a message, never a crash */
  if (silk_mesh_encode(NULL, NULL, &tokens, NULL) != SILK_ERR_INVALID_ARGUMENT || strlen(silk_last_error()) == 0)
    return 6;
  /* generation entry points exist in every build; without onnxruntime they say so */
  {
    silk_generate_params gp = silk_generate_default_params();
    silk_model* model = NULL;
    silk_mesh* out = NULL;
    silk_status st = silk_model_load("/nonexistent-model-dir", NULL, &model);
    /* sampling and pre-processing default to "the model's" (-1) */
    if (gp.top_k != -1 || gp.temperature != -1 || gp.top_p_temperature != -1 || gp.preprocessing != -1 ||
        gp.max_tokens != 0 || gp.raw_points != 0)
      return 7;
    if (st == SILK_OK || model != NULL || strlen(silk_last_error()) == 0) return 8;
    if (!silk_generation_available() && st != SILK_ERR_UNSUPPORTED) return 9;
    silk_generate_input in = {.struct_size = sizeof in};
    silk_generate_stats gs = {.struct_size = sizeof gs};
    in.mesh = mesh;
    if (gp.struct_size != sizeof gp) return 19;
    if (silk_generator_run(NULL, &in, &gp, &out, NULL, &gs) != SILK_ERR_INVALID_ARGUMENT || out != NULL) return 10;
  }
  /* pre-processing works in every build: size query, then the official kind's rows */
  {
    silk_preprocess_params pp = silk_preprocess_default_params(SILK_PREPROCESS_OFFICIAL);
    size_t floats = 0;
    float buf[6 * 64];
    double transform[4];
    pp.point_count = 64;
    if (pp.surface_samples != 50000 || pp.round_float16 != 1) return 11;
    if (silk_points_prepare(mesh, NULL, 0, &pp, 1, NULL, 0, &floats, NULL) != SILK_OK || floats != 6 * 64) return 12;
    if (silk_points_prepare(mesh, NULL, 0, &pp, 1, buf, 10, &floats, NULL) != SILK_ERR_BUFFER_TOO_SMALL) return 13;
    if (silk_points_prepare(mesh, NULL, 0, &pp, 1, buf, 6 * 64, &floats, transform) != SILK_OK) return 14;
    if (transform[3] != 1.9 || buf[0] < -0.951f || buf[0] > 0.951f) return 15;
    if (silk_points_prepare(mesh, xyz, 2, &pp, 1, buf, 6 * 64, &floats, NULL) != SILK_ERR_INVALID_ARGUMENT) return 16;
    pp.kind = 7;
    if (silk_points_prepare(mesh, NULL, 0, &pp, 1, buf, 6 * 64, &floats, NULL) != SILK_ERR_INVALID_ARGUMENT) return 17;
  }
  /* the tokenizer tools silktok uses: round trip, grammar check, repair (+ its JSON report), walk */
  {
    silk_roundtrip_report rr = {.struct_size = sizeof rr};
    silk_check_result cr = {.struct_size = sizeof cr};
    silk_repair_stats rs = {.struct_size = sizeof rs};
    silk_report* report = NULL;
    silk_mesh* repaired = NULL;
    silk_tokens* walk = NULL;
    silk_random_walk_params wp = silk_random_walk_default_params();
    if (silk_mesh_roundtrip(mesh, NULL, &rr) != SILK_OK || !rr.exact || rr.tokens != 17) return 18;
    if (silk_tokens_check(tokens, NULL, &cr) != SILK_OK || !cr.accepted) return 19;
    if (silk_tokens_repair(tokens, NULL, &repaired, &rs, &report) != SILK_OK || rs.faces != 4 || !rs.watertight)
      return 20;
    if (strstr(silk_report_json(report), "\"holes\"") == NULL) return 21;
    silk_report_destroy(report);
    silk_mesh_destroy(repaired);
    wp.seed = 5;
    if (silk_tokens_random_walk(&wp, &walk, NULL) != SILK_OK || silk_tokens_copy(walk, NULL, 0, &count) != SILK_OK ||
        count < 14)
      return 22;
    silk_tokens_destroy(walk);
  }
  /* best of N's candidates (1.5): the names, and a NULL generator refused with a message */
  {
    silk_candidate_info ci = {.struct_size = sizeof ci};
    silk_mesh* cm = NULL;
    int32_t n = -1, state = -1;
    const silk_status refused = silk_generation_available() ? SILK_ERR_INVALID_ARGUMENT : SILK_ERR_UNSUPPORTED;
    if (strcmp(silk_candidate_state_name(SILK_CANDIDATE_SCORED), "scored") != 0 ||
        strcmp(silk_candidate_state_name(SILK_CANDIDATE_SCORED + 1), "unknown") != 0)
      return 24;
    if (silk_candidate_state_from_name("running", &state) != SILK_OK || state != SILK_CANDIDATE_RUNNING) return 25;
    if (silk_generator_candidate_count(NULL, &n) != refused || silk_generator_get_candidate(NULL, 0, &ci) != refused ||
        silk_generator_get_candidate_mesh(NULL, 0, &cm) != refused || cm != NULL || strlen(silk_last_error()) == 0)
      return 26;
  }
  silk_mesh_destroy(back);
  silk_tokens_destroy(tokens);
  silk_mesh_destroy(mesh);
  /* the header's version is the library's */
  if (strcmp(silk_version(), SILK_VERSION_STRING) != 0 ||
      SILK_VERSION_NUMBER != 10000 * SILK_VERSION_MAJOR + 100 * SILK_VERSION_MINOR + SILK_VERSION_PATCH)
    return 23;
  printf("C API from C: ok (%s)\n", silk_version());
  return 0;
}
