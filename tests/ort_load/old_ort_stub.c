/* SPDX-License-Identifier: MIT */
/* A stand-in for an onnxruntime release older than Silk's headers (tests/ort_load): it reports
 * version 1.10.0 and, asked for a newer C API, prints its own complaint to stderr as such a
 * release does, then refuses. Silk must refuse it without asking (its message alone). */
#include <stddef.h>
#include <stdio.h>

typedef struct StubApiBase {
  const void* (*GetApi)(unsigned version);
  const char* (*GetVersionString)(void);
} StubApiBase;

static const void* StubGetApi(unsigned version) {
  fprintf(stderr,
          "The requested API version [%u] is not available, only API versions [1, 10] are supported "
          "in this build. Current ORT Version is: 1.10.0\n",
          version);
  return NULL;
}

static const char* StubVersion(void) { return "1.10.0"; }

static const StubApiBase kBase = {StubGetApi, StubVersion};

const StubApiBase* OrtGetApiBase(void) { return &kBase; }
