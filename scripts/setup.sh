#!/usr/bin/env bash
# Installs what crtforge needs on a Debian 12 machine. Idempotent: quiet when nothing is missing.
set -euo pipefail

APT_PACKAGES=(
  build-essential cmake pkg-config
  glslang-dev glslang-tools spirv-tools libspirv-cross-c-shared-dev spirv-cross
  libvulkan-dev mesa-vulkan-drivers vulkan-validationlayers
  libegl-dev libgles-dev libopengl-dev libgl1-mesa-dri libegl-mesa0
  godot3 xvfb
  chromium-common  # SwiftShader's Vulkan driver: validate's second, independent Vulkan driver
  libopenimageio-dev libfmt-dev catch2
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libxxhash-dev
)

missing=()
for pkg in "${APT_PACKAGES[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$pkg")
  fi
done
# The Dawn engine runs Node.js: Debian's nodejs and npm, unless node and npm come from elsewhere.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  missing+=(nodejs npm)
fi

if ((${#missing[@]})); then
  echo "crtforge setup: installing ${missing[*]}"
  SUDO=""
  if [[ $(id -u) -ne 0 ]]; then SUDO="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# Dawn for the WGSL runner: the npm package webgpu at the version package-lock.json pins. Its
# postinstall script only does work on macOS, so install scripts stay off.
WGSL_RUNNER="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/wgsl-runner"
WEBGPU_VERSION=0.6.2
webgpu_manifest="$WGSL_RUNNER/node_modules/webgpu/package.json"
installed=""
if [[ -f "$webgpu_manifest" ]]; then
  installed=$(node -p 'require(process.argv[1]).version' "$webgpu_manifest" 2>/dev/null || true)
fi
if [[ "$installed" != "$WEBGPU_VERSION" ]]; then
  echo "crtforge setup: installing npm packages for the WGSL runner"
  npm ci --prefix "$WGSL_RUNNER" --no-audit --no-fund --ignore-scripts --loglevel=error >/dev/null
fi
