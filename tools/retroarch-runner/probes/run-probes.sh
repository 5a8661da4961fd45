#!/usr/bin/env bash
# Re-measures the conventions that tools/retroarch-runner/README.md states, with the probe presets
# in this folder, and prints the evidence. Needs the root (scripts/setup-retroarch.sh) and root.
#
#   probes/run-probes.sh [--timing]     (--timing also times corpus presets, ~1 minute)
set -euo pipefail

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
RENDER="$HERE/../render.sh"
PICS="$HERE/pictures.py"
SHADERS="${CRTFORGE_SLANG_SHADERS:-$(cd "$HERE/../../.." && pwd)/shared/slang-shaders}"
[[ -d "$SHADERS" ]] || SHADERS=/work/shared/slang-shaders
work="$(mktemp -d /tmp/crtforge-probes.XXXXXX)"
trap 'rm -rf "$work"' EXIT

python3 "$PICS" bars "$work/bars.ppm"
python3 "$PICS" ramp "$work/ramp.pam"
python3 "$PICS" checker "$work/checker.ppm" 4

render() { "$RENDER" --input "$work/bars.ppm" --viewport 640x480 --frames 3 "$@"; }
frame_count() { python3 "$PICS" values "$1" | awk '/FrameCount/ { print $2; exit }'; }
first_pixel() { python3 "$PICS" info "$1" | sed -n 2p | sed 's/.*\[(\([0-9, ]*\)).*/\1/'; }

echo "== (a) FrameCount in the screenshot, and how often the chain ran (counter.slangp)"
for driver in vulkan glcore; do
  for n in 1 3 10; do
    render --driver "$driver" --frames "$n" --preset "$HERE/values.slangp" --out "$work/a.png"
    "$RENDER" --driver "$driver" --frames "$n" --preset "$HERE/counter.slangp" --input "$work/bars.ppm" \
      --viewport 64x48 --out "$work/c.png"
    IFS=', ' read -r runs first last < <(first_pixel "$work/c.png")
    echo "  $driver --max-frames $n: FrameCount $(frame_count "$work/a.png"); chain ran $runs times," \
         "FrameCount $first on the first run, $last on the last"
  done
done

echo "== (b) size and orientation (values.slangp writes its cells at vTexCoord.y ~ 0)"
for vp in 640x480 333x217 800x300; do
  render --viewport "$vp" --preset "$HERE/values.slangp" --out "$work/b.png"
  python3 "$PICS" values "$work/b.png" | grep 'PNG row' | sed 's/^/  /'
done

echo "== (c) determinism: two runs, byte-compared"
for p in "$HERE/values.slangp" "$SHADERS/crt/crt-guest-advanced.slangp"; do
  render --preset "$p" --out "$work/c1.png"
  render --preset "$p" --out "$work/c2.png"
  if cmp -s "$work/c1.png" "$work/c2.png"; then echo "  $(basename "$p"): identical"; else echo "  $(basename "$p"): DIFFERENT"; fi
done

echo "== (d) input bytes -> Source (256x4 RGBA ramp at a 256x4 viewport)"
for driver in vulkan glcore; do
  for p in bytes exact alpha; do
    "$RENDER" --driver "$driver" --preset "$HERE/$p.slangp" --input "$work/ramp.pam" --viewport 256x4 \
      --frames 1 --out "$work/d-$p.png"
  done
  echo "  $driver: RGB read back vs input: $(python3 "$PICS" compare "$work/d-bytes.png" "$work/ramp.pam")"
  echo "  $driver: Source.a vs the PAM alpha (the XRGB X byte): $(python3 "$PICS" compare "$work/d-alpha.png" "$work/ramp.pam" --alpha)"
  echo "  $driver: exactness (128 = exact byte/255): values $(python3 -c "
import sys; sys.path.insert(0, '$HERE'); import pictures
print(sorted(set(pictures.read_png('$work/d-exact.png')[3])))")"
done
for f in unset linear nearest; do
  "$RENDER" --preset "$HERE/filter-$f.slangp" --input "$work/checker.ppm" --viewport 64x64 --frames 1 --out "$work/f.png"
  echo "  filter $f (video_smooth=false): $(python3 -c "
import sys; sys.path.insert(0, '$HERE'); import pictures
px = pictures.read_png('$work/f.png')[3]; print(len(set(px)), 'distinct byte values')")"
done
"$RENDER" --preset "$HERE/filter-unset.slangp" --input "$work/checker.ppm" --viewport 64x64 --frames 1 \
  --out "$work/f.png" --set video_smooth=true
echo "  filter unset (video_smooth=true): $(python3 -c "
import sys; sys.path.insert(0, '$HERE'); import pictures
w, h, ch, px = pictures.read_png('$work/f.png'); print(len(set(px)), 'distinct byte values; pixel (0,8) =', px[(8 * w) * ch])")"

echo "== (e) sizes in one-pass presets (and a 2-pass one) at 640x480 over 320x240"
for p in values values-viewport values-source2x; do
  render --preset "$HERE/$p.slangp" --out "$work/e.png"
  echo "  $p: $(python3 "$PICS" values "$work/e.png" | grep -E '(Source|Original|Output|FinalViewport)Size\.[xy] ' |
               awk '{ printf "%s=%s ", $1, $2 }')"
done

echo "== failure detection"
for p in broken missing; do
  if "$RENDER" --preset "$HERE/$p.slangp" --input "$work/bars.ppm" --viewport 64x48 --frames 1 \
       --out "$work/x.png" 2>"$work/err.txt"; then
    echo "  $p.slangp: NOT detected"
  else
    echo "  $p.slangp: $(cat "$work/err.txt")"
  fi
done

if [[ "${1:-}" == --timing ]]; then
  echo "== (f) wall time of one cold render at 640x480, --frames 3"
  for p in "$HERE/values.slangp" crt/zfast-crt crt/crt-lottes crt/crt-geom crt/crt-easymode \
           crt/crt-guest-advanced crt/crt-royale; do
    [[ "$p" == /* ]] || p="$SHADERS/$p.slangp"
    start=$(date +%s%N)
    render --preset "$p" --out "$work/t.png"
    echo "  $(basename "$p"): $(( ($(date +%s%N) - start) / 1000000 )) ms"
  done
fi
