#!/usr/bin/env bash
# Renders a RetroArch .slangp preset over a still picture with the real RetroArch 1.20 (Debian 13)
# from the root that scripts/setup-retroarch.sh builds, headless (Xvfb) on Mesa's lavapipe (Vulkan)
# or Mesa's GL (glcore), and writes the post-shader frame as a PNG. See README.md beside this file.
#
#   render.sh --preset /abs/x.slangp --input in.ppm --viewport 640x480 --frames 3 --out out.png
#             [--driver vulkan|glcore] [--log log.txt] [--timeout 600] [--set key=value]... [--keep]
#
# --set overrides one line of the generated retroarch.cfg (for probes); --keep keeps the job folder.
#
# RetroArch runs in a chroot into the root, inside a private mount namespace (unshare -m), so the
# bind mounts it needs vanish with it. Needs root with CAP_SYS_ADMIN (mount, chroot).
set -euo pipefail

ROOT="${CRTFORGE_RETROARCH_ROOT:-/var/cache/crtforge/retroarch-trixie}"
CORE=/opt/crtforge/crtforge_still_libretro.so   # inside the root
ME=render.sh

die() { echo "$ME: error: $*" >&2; exit 1; }
usage() {
  sed -n '6,9p' "${BASH_SOURCE[0]}" | sed 's/^# *//' >&2
  exit 2
}

preset="" input="" viewport="" frames="" out="" driver=vulkan log="" keep=0 overrides=() timeout_s=600
while (($#)); do
  case "$1" in
    --preset) preset="${2:-}"; shift 2 ;;
    --input) input="${2:-}"; shift 2 ;;
    --viewport) viewport="${2:-}"; shift 2 ;;
    --frames) frames="${2:-}"; shift 2 ;;
    --out) out="${2:-}"; shift 2 ;;
    --driver) driver="${2:-}"; shift 2 ;;
    --log) log="${2:-}"; shift 2 ;;
    --set) [[ "${2:-}" =~ ^[a-z0-9_]+=.*$ ]] || die "--set wants key=value, got '${2:-}'"
           overrides+=("$2"); shift 2 ;;
    --timeout) timeout_s="${2:-}"; shift 2 ;;
    --keep) keep=1; shift ;;
    -h|--help) usage ;;
    *) echo "$ME: unknown argument '$1'" >&2; usage ;;
  esac
done
[[ -n "$preset" && -n "$input" && -n "$viewport" && -n "$frames" && -n "$out" ]] || usage
[[ "$viewport" =~ ^([1-9][0-9]*)x([1-9][0-9]*)$ ]] || die "--viewport must be WxH, got '$viewport'"
width="${BASH_REMATCH[1]}" height="${BASH_REMATCH[2]}"
[[ "$frames" =~ ^[1-9][0-9]*$ ]] || die "--frames must be a positive integer, got '$frames'"
[[ "$driver" == vulkan || "$driver" == glcore ]] || die "--driver must be vulkan or glcore"
[[ "$timeout_s" =~ ^[1-9][0-9]*$ ]] || die "--timeout must be a positive number of seconds"
[[ -f "$preset" ]] || die "no preset file '$preset'"
[[ -f "$input" ]] || die "no input picture '$input'"
case "$(head -c 2 "$input")" in
  P6) input_ext=ppm ;;
  P7) input_ext=pam ;;
  *) die "input '$input' is neither a binary PPM (P6) nor a PAM (P7)" ;;
esac
[[ "$(id -u)" == 0 ]] || die "must run as root (it chroots into $ROOT)"
[[ -f "$ROOT/.crtforge-root-complete" && -f "$ROOT$CORE" ]] ||
  die "no RetroArch root at $ROOT: run scripts/setup-retroarch.sh"

preset="$(realpath "$preset")"
out="$(realpath -m "$out")"
# The paths are written into a generated shell script and config: keep them plain.
[[ "$preset" != *[\"\$\`\\]* ]] || die "preset path must not contain quotes, \$, \` or backslashes"
[[ -d "$(dirname "$out")" ]] || die "no folder for --out: $(dirname "$out")"
[[ -z "$log" ]] || log="$(realpath -m "$log")"

# The preset's tree is bound into the root at its own path, so its relative references ("../..")
# and #includes resolve as on the host. Bind its top-level folder unless that would hide the
# root's own system folders.
top="/$(echo "$preset" | cut -d/ -f2)"
case "$top" in
  /bin|/boot|/dev|/etc|/lib|/lib32|/lib64|/libx32|/opt|/proc|/run|/sbin|/sys|/usr|/var)
    die "preset must not live under $top (it is bound into the root at its own path): copy it elsewhere" ;;
esac

# The job folder lives in the host's /tmp, which the root sees as its /tmp (so Xvfb's display
# locks are shared with the host's and xvfb-run -a picks a display that is really free).
job="$(mktemp -d /tmp/crtforge-retroarch.XXXXXX)"
cleanup() { if ((keep)); then echo "$ME: kept $job" >&2; else rm -rf "$job"; fi; }
trap cleanup EXIT
mkdir -p "$job/home" "$job/xdg-runtime" "$job/shots" "$job/dirs"
chmod 700 "$job/xdg-runtime"
cp "$input" "$job/input.$input_ext"
shot="$job/shots/shot.png"

# A complete config: RetroArch reads no other (--config; HOME and XDG folders point into the job).
# Every setting that could change the picture or the frame count is pinned here.
cat >"$job/retroarch.cfg" <<EOF
video_driver = "$driver"
audio_driver = "null"
audio_enable = "false"
input_driver = "null"
input_joypad_driver = "null"
menu_driver = "null"
video_fullscreen = "false"
video_windowed_fullscreen = "false"
video_window_save_positions = "true"
video_window_custom_size_enable = "true"
video_windowed_position_x = "0"
video_windowed_position_y = "0"
video_windowed_position_width = "$width"
video_windowed_position_height = "$height"
video_window_show_decorations = "false"
video_scale = "1.0"
video_scale_integer = "false"
video_aspect_ratio_auto = "false"
aspect_ratio_index = "23"
custom_viewport_x = "0"
custom_viewport_y = "0"
custom_viewport_width = "$width"
custom_viewport_height = "$height"
video_rotation = "0"
video_allow_rotate = "false"
video_vsync = "false"
video_adaptive_vsync = "false"
video_threaded = "false"
video_hard_sync = "false"
video_frame_delay = "0"
video_frame_delay_auto = "false"
video_black_frame_insertion = "0"
video_shader_subframes = "1"
video_scan_subframes = "false"
video_hdr_enable = "false"
video_smooth = "false"
video_filter = ""
video_shader_enable = "true"
video_shader_watch_files = "false"
video_shader_remember_last_dir = "false"
auto_shaders_enable = "false"
video_shader_dir = "$job/dirs"
video_font_enable = "false"
menu_enable_widgets = "false"
fps_show = "false"
framecount_show = "false"
memory_show = "false"
statistics_show = "false"
input_overlay_enable = "false"
rewind_enable = "false"
run_ahead_enabled = "false"
preemptive_frames_enable = "false"
vrr_runloop_enable = "false"
fastforward_ratio = "0.0"
pause_nonactive = "false"
video_gpu_screenshot = "true"
screenshots_in_content_dir = "false"
auto_screenshot_filename = "false"
screenshot_directory = "$job/shots"
notification_show_screenshot = "false"
config_save_on_exit = "false"
remap_save_on_exit = "false"
savestate_auto_load = "false"
savestate_auto_save = "false"
game_specific_options = "false"
auto_overrides_enable = "false"
auto_remaps_enable = "false"
global_core_options = "false"
check_firmware_before_loading = "false"
network_cmd_enable = "false"
stdin_cmd_enable = "false"
discord_allow = "false"
cheevos_enable = "false"
history_list_enable = "false"
content_runtime_log = "false"
content_runtime_log_aggregate = "false"
core_info_cache_enable = "false"
input_autodetect_enable = "false"
load_dummy_on_core_shutdown = "false"
log_verbosity = "true"
frontend_log_level = "0"
libretro_log_level = "0"
log_to_file = "false"
savefile_directory = "$job/dirs"
savestate_directory = "$job/dirs"
system_directory = "$job/dirs"
cache_directory = "$job/dirs"
log_dir = "$job/dirs"
playlist_directory = "$job/dirs"
runtime_log_directory = "$job/dirs"
libretro_directory = "/opt/crtforge"
libretro_info_path = "$job/dirs"
core_options_path = "$job/dirs/core.opt"
rgui_config_directory = "$job/dirs"
input_remapping_directory = "$job/dirs"
content_favorites_path = "$job/dirs/content_favorites.lpl"
EOF
for kv in "${overrides[@]}"; do
  key="${kv%%=*}"
  sed -i "/^$key = /d" "$job/retroarch.cfg"
  echo "$key = \"${kv#*=}\"" >>"$job/retroarch.cfg"
done

# Runs inside the root: an Xvfb a little larger than the window (it picks a free display itself,
# -displayfd, so parallel renders never race for one), a D-Bus session, RetroArch.
cat >"$job/inside.sh" <<EOF
#!/bin/bash
export HOME="$job/home" XDG_CONFIG_HOME="$job/home/.config" XDG_CACHE_HOME="$job/home/.cache"
export XDG_RUNTIME_DIR="$job/xdg-runtime" LC_ALL=C.UTF-8 LANG=C.UTF-8
export PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin
export VK_ICD_FILENAMES=/usr/share/vulkan/icd.d/lvp_icd.json LIBGL_ALWAYS_SOFTWARE=1
${LP_NUM_THREADS:+export LP_NUM_THREADS=$LP_NUM_THREADS}
Xvfb -displayfd 3 -screen 0 $((width + 64))x$((height + 64))x24 -nolisten tcp 3>"$job/display" &
for _ in \$(seq 200); do [[ -s "$job/display" ]] && break; sleep 0.05; done
[[ -s "$job/display" ]] || { echo "[ERROR] Xvfb did not start"; exit 1; }
export DISPLAY=:\$(cat "$job/display")
dbus-run-session -- retroarch --verbose --config "$job/retroarch.cfg" -L "$CORE" \\
  --set-shader "$preset" --max-frames "$frames" --max-frames-ss --max-frames-ss-path "$shot" \\
  "$job/input.$input_ext"
EOF
chmod +x "$job/inside.sh"

# A private mount and PID namespace: the mounts vanish with it and, when its first process ends,
# the kernel ends whatever it left (Xvfb). The timeout bounds a hung run.
rc=0
timeout -k 10 "$timeout_s" unshare --mount --propagation private --pid --fork /bin/bash -euc '
  root="$1" job="$2" top="$3"
  mount -t proc proc "$root/proc"
  mount --rbind /dev "$root/dev"
  mount --rbind /sys "$root/sys"
  mount --bind /tmp "$root/tmp"
  if [[ "$top" != /tmp ]]; then
    mkdir -p "$root$top"
    mount --rbind "$top" "$root$top"
  fi
  chroot "$root" "$job/inside.sh"
' _ "$ROOT" "$job" "$top" >"$job/retroarch.log" 2>&1 || rc=$?
((rc != 124 && rc != 137)) || die "$preset: RetroArch did not finish within ${timeout_s}s (--timeout)"
[[ -z "$log" ]] || cp "$job/retroarch.log" "$log"

# A preset that fails to compile or load still lets RetroArch run (on its stock shader) and exit
# 0, so the log decides: any error line from the shader system fails the render, and at least
# one "[slang]: Compiling shader" line must show that the preset's passes were really built.
log_file="$job/retroarch.log"
first_error() { grep -m1 -E '^\[ERROR\]' "$log_file" | sed 's/[[:space:]]*$//' || tail -n 1 "$log_file"; }
err="$(grep -m1 -iE '^\[ERROR\].*(shader|slang|glslang|spir-?v|filter.?chain|preset|compil|link)' \
        "$log_file" | sed 's/[[:space:]]*$//' || true)"
[[ -z "$err" ]] || die "$preset: shader preset failed in RetroArch: $err"
[[ "$rc" == 0 ]] || die "$preset: RetroArch exited with status $rc: $(first_error)"
grep -q '^\[INFO\] \[slang\]: Compiling shader' "$log_file" ||
  die "$preset: RetroArch did not load the preset (no shader compiled): $(first_error)"
[[ -f "$shot" ]] || die "$preset: no screenshot appeared: $(first_error)"
# The GPU screenshot holds the viewport only, so its size proves the viewport covered the window.
read -r b0 b1 b2 b3 b4 b5 b6 b7 < <(od -An -tu1 -j16 -N8 "$shot")
shot_w=$(( (b0 << 24) | (b1 << 16) | (b2 << 8) | b3 )) shot_h=$(( (b4 << 24) | (b5 << 16) | (b6 << 8) | b7 ))
[[ "${shot_w}x${shot_h}" == "$viewport" ]] ||
  die "$preset: the screenshot is ${shot_w}x${shot_h}, not the requested $viewport"
cp "$shot" "$out"
