# Sourced by scripts/setup.sh and scripts/fuzz.sh: the one way crtforge's scripts install Debian
# packages. Not a command of its own.

# Prints the given packages that are not installed, one per line.
missing_apt_packages() {
  local pkg
  for pkg in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
      echo "$pkg"
    fi
  done
}

# install_apt_packages LABEL PKG...: installs them (sudo when not root), quietly, saying so first.
install_apt_packages() {
  local label=$1
  shift
  (($#)) || return 0
  echo "$label: installing $*"
  local sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -qq
  $sudo apt-get install -y -qq --no-install-recommends "$@" >/dev/null
}
