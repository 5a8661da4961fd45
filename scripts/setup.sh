#!/usr/bin/env bash
# Installs what crtforge needs on a Debian 12 machine. Idempotent: quiet when nothing is missing.
set -euo pipefail

APT_PACKAGES=(
  build-essential cmake pkg-config
  glslang-dev glslang-tools spirv-tools libspirv-cross-c-shared-dev spirv-cross
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libegl-dev libgles-dev libopengl-dev libgl1-mesa-dri libegl-mesa0
  godot3 xvfb
  libopenimageio-dev libfmt-dev catch2
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libxxhash-dev
)

missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done

if ((${#missing[@]})); then
  echo "crtforge setup: installing ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
