#!/usr/bin/env bash
# RetroArch agreement: each listed .slangp rendered by RetroArch 1.20 (Vulkan, lavapipe) and by
# crtforge's import of it (its Vulkan target, or --target T), at the same viewport, frames and
# input, judged by PSNR. Needs scripts/setup-retroarch.sh's root and a built crtforge.
#
#   agreement.sh [--corpus DIR] [--viewport WxH] [--frames "1 3 9"] [--target spirv] [--out DIR]
#                [--min-psnr 40] [--set FILE] PRESET.slangp...      (paths relative to --corpus)
#
# --set FILE adds the presets FILE lists, one per line (# starts a comment): agreement-set.txt
# beside this script is the curated set, `agreement.sh --set tools/retroarch-runner/agreement-set.txt`.
#
# Prints one line per preset and frame: "psnr  preset  frame", then a summary; exits 1 when any
# PSNR is below --min-psnr. crtforge draws onto an 8-bit display as RetroArch's swapchain is
# (render --display rgba8: values clamp, a NaN shows as 0). Frames: RetroArch's `--max-frames N` shows the frame its Vulkan driver
# drew with FrameCount N + 1 after N + 1 runs of the chain (README.md, measured); crtforge draws
# frames 0..N with frameCount starting at 1 (render --frame-count-base 1): the same sequence.
set -euo pipefail

here=$(cd "$(dirname "$0")" && pwd)
project=$(cd "$here/../.." && pwd)
corpus="$project/../shared/slang-shaders"
viewport=640x480
frames="1 3 9"
target=spirv
out=""
min_psnr=40
crtforge="${CRTFORGE:-$project/build/crtforge}"
presets=()
while [ $# -gt 0 ]; do
    case "$1" in
        --corpus) corpus=$2; shift 2 ;;
        --viewport) viewport=$2; shift 2 ;;
        --frames) frames=$2; shift 2 ;;
        --target) target=$2; shift 2 ;;
        --out) out=$2; shift 2 ;;
        --min-psnr) min_psnr=$2; shift 2 ;;
        --set)
            [ -f "$2" ] || { echo "agreement.sh: --set $2: no such file" >&2; exit 2; }
            while read -r line; do
                line=${line%%#*}
                line=$(echo "$line" | xargs)
                [ -n "$line" ] && presets+=("$line")
            done < "$2"
            shift 2 ;;
        -*) echo "agreement.sh: unknown option $1" >&2; exit 2 ;;
        *) presets+=("$1"); shift ;;
    esac
done
[ ${#presets[@]} -gt 0 ] || { echo "agreement.sh: name at least one preset" >&2; exit 2; }
[ -x "$crtforge" ] || { echo "agreement.sh: no crtforge at $crtforge (build it, or set CRTFORGE)" >&2; exit 2; }
corpus=$(cd "$corpus" && pwd)
work=${out:-$(mktemp -d /tmp/crtforge-agreement.XXXXXX)}
mkdir -p "$work"
input="$work/input.ppm"
python3 "$here/probes/pictures.py" bars "$input" 320 240

last=0
count=0
for n in $frames; do
    count=$((count + 1))
    [ "$n" -gt "$last" ] && last=$n
done
failed=0
total=0
below=0
for preset in "${presets[@]}"; do
    name=$(basename "$preset" .slangp)
    overlay="$work/$name.overlay"
    rm -rf "$overlay"
    # One overlay per preset, so one name serves them all.
    if ! "$crtforge" import "$corpus/$preset" --out "$overlay" --root "$corpus" --name imported -q 2>"$work/$name.import.log"; then
        echo "import-failed  $preset  $(tail -1 "$work/$name.import.log")"
        failed=$((failed + count)); total=$((total + count))
        continue
    fi
    # crtforge draws frames 0..last once; each listed frame is one of its pictures.
    if ! "$crtforge" --templates "$overlay" render --preset imported --target "$target" --input "$input" \
        --output "$work/$name.cf.%d.png" --size "$viewport" --fit stretch --frames "0:$last" --frame-count-base 1 --display rgba8 \
        >/dev/null 2>"$work/$name.cf.log"; then
        echo "crtforge-failed  $preset  $(tail -1 "$work/$name.cf.log")"
        failed=$((failed + count)); total=$((total + count))
        continue
    fi
    for n in $frames; do
        total=$((total + 1))
        ra="$work/$name.ra.$n.png"
        cf="$work/$name.cf.$n.png"
        if ! "$here/render.sh" --preset "$corpus/$preset" --input "$input" --viewport "$viewport" --frames "$n" --out "$ra" \
            --log "$work/$name.ra.$n.log" >/dev/null 2>&1; then
            echo "retroarch-failed  $preset  $n"
            failed=$((failed + 1))
            continue
        fi
        psnr=$(python3 "$here/probes/pictures.py" psnr "$ra" "$cf")
        echo "$psnr  $preset  $n"
        if [ "$psnr" != inf ] && awk "BEGIN { exit !($psnr < $min_psnr) }"; then below=$((below + 1)); fi
    done
done
echo "agreement: $((total - failed - below)) of $total renders at >= $min_psnr dB; $below below, $failed failed (pictures in $work)"
[ $failed -eq 0 ] && [ $below -eq 0 ]
