# SPDX-License-Identifier: MIT
# Windows cross-build: CLI11 from Debian's libcli11-dev (header-only).
include(${CMAKE_CURRENT_LIST_DIR}/host_headers.cmake)
silk_host_header_target(CLI11::CLI11 CLI)
