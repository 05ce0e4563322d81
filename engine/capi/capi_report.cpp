// SPDX-License-Identifier: MIT
// C API: silk_report, the JSON document a call hands back (variable-length findings such as the
// holes of a repair), owned by the caller until silk_report_destroy.
#include "capi/capi_internal.h"

extern "C" {

const char* silk_report_json(const silk_report* report) { return report ? report->json.c_str() : ""; }
void silk_report_destroy(silk_report* report) { delete report; }

}  // extern "C"
