# SPDX-License-Identifier: MIT
# Windows cross-build: nlohmann-json from Debian's nlohmann-json3-dev (header-only).
include(${CMAKE_CURRENT_LIST_DIR}/host_headers.cmake)
silk_host_header_target(nlohmann_json::nlohmann_json nlohmann)
