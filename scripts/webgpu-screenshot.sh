#!/usr/bin/env bash
# Chromium's own WebGPU (SwiftShader, headless) renders a preset through the exported npm package:
# the screenshot in docs/images, reproducible. It exports the preset (WGSL) to a temporary folder,
# serves examples/webgpu/ and the export on localhost, loads examples/webgpu/screenshot.html in
# headless Chromium (driven over the DevTools protocol by tools/screenshot/screenshot.mjs) and
# writes the PNG the page reads back from its WebGPU target.
#
#   scripts/webgpu-screenshot.sh PRESET OUT.png [WIDTHxHEIGHT] [FRAMES]
#   scripts/webgpu-screenshot.sh classic docs/images/classic-webgpu-chromium.png 640x480
#
# Installs Debian's chromium when missing (not a dependency of the build or the tests). As root,
# Chromium runs with --no-sandbox.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
if (($# < 2)); then
  echo "usage: scripts/webgpu-screenshot.sh PRESET OUT.png [WIDTHxHEIGHT] [FRAMES]" >&2
  exit 2
fi
preset=$1
out=$(realpath -m -- "$2")
size=${3:-640x480}
frames=${4:-1}
if [[ ! $size =~ ^([1-9][0-9]{0,3})x([1-9][0-9]{0,3})$ ]]; then
  echo "webgpu-screenshot: size must be WIDTHxHEIGHT (1..9999 each), got '$size'" >&2
  exit 2
fi
width=${BASH_REMATCH[1]}
height=${BASH_REMATCH[2]}
if [[ ! $frames =~ ^[1-9][0-9]{0,2}$ ]]; then
  echo "webgpu-screenshot: frames must be 1..999, got '$frames'" >&2
  exit 2
fi

source "$root/scripts/apt-packages.sh"
mapfile -t missing < <(missing_apt_packages chromium)
install_apt_packages "webgpu-screenshot" "${missing[@]}"
[[ -x "$root/build/crtforge" ]] || "$root/scripts/build.sh"

tmp=$(mktemp -d)
server=""
cleanup() {
  [[ -n $server ]] && kill "$server" 2>/dev/null || true
  rm -rf "$tmp"
}
trap cleanup EXIT

"$root/build/crtforge" export -q --target wgsl --preset "$preset" --out "$tmp/export"
mkdir -p "$tmp/www/examples"
ln -s "$root/examples/webgpu" "$tmp/www/examples/webgpu"
ln -s "$tmp/export" "$tmp/www/export"
port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
python3 -m http.server "$port" --bind 127.0.0.1 --directory "$tmp/www" >"$tmp/http.log" 2>&1 &
server=$!
for _ in $(seq 50); do
  python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$port/export/manifest.json')" 2>/dev/null && break
  sleep 0.1
done

# The DevTools driver (npm chrome-remote-interface, pinned by tools/screenshot's lock file).
if [[ ! -f "$root/tools/screenshot/node_modules/chrome-remote-interface/package.json" ]]; then
  echo "webgpu-screenshot: installing npm packages for tools/screenshot"
  npm ci --prefix "$root/tools/screenshot" --no-audit --no-fund --ignore-scripts --loglevel=error >/dev/null
fi

sandbox=()
[[ $(id -u) -eq 0 ]] && sandbox=(--no-sandbox)
debug_port=$(python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
chromium --headless=new "${sandbox[@]}" --enable-unsafe-webgpu --use-webgpu-adapter=swiftshader \
  --remote-debugging-port="$debug_port" --user-data-dir="$tmp/profile" about:blank >"$tmp/chromium.log" 2>&1 &
browser=$!
cleanup() {
  kill "$browser" 2>/dev/null || true
  [[ -n $server ]] && kill "$server" 2>/dev/null || true
  wait 2>/dev/null || true
  rm -rf "$tmp"
}
for _ in $(seq 100); do
  python3 -c "import urllib.request; urllib.request.urlopen('http://127.0.0.1:$debug_port/json/version')" 2>/dev/null && break
  sleep 0.1
done

url="http://127.0.0.1:$port/examples/webgpu/screenshot.html?package=/export/npm/&preset=$preset&width=$width&height=$height&frames=$frames"
mkdir -p "$(dirname "$out")"
if ! node "$root/tools/screenshot/screenshot.mjs" "$debug_port" "$url" "$out.tmp"; then
  rm -f "$out.tmp"
  echo "webgpu-screenshot: ${preset} was not rendered (Chromium's last line: $(tail -n 1 "$tmp/chromium.log"))" >&2
  exit 1
fi
mv "$out.tmp" "$out"
echo "webgpu-screenshot: $out (${width}x${height}, $(chromium --version 2>/dev/null | head -n 1), WebGPU on SwiftShader)"
