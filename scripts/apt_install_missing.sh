# SPDX-License-Identifier: MIT
# Sourced by the setup scripts (scripts/setup.sh, scripts/setup_windows.sh): installs
# those of the given Debian packages that are not installed yet, and runs no apt at all (no
# update, no network) when every one is present. Usage: apt_install_missing <who> <package>...
apt_install_missing() {
  local who="$1" p missing=()
  shift
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  if ((${#missing[@]} == 0)); then
    echo "$who: all system packages present"
    return 0
  fi
  echo "$who: installing ${missing[*]}"
  local sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
}
