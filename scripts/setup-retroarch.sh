#!/usr/bin/env bash
# Builds the RetroArch reference root for tools/retroarch-runner: a minimal Debian 13 ("trixie")
# root with RetroArch 1.20 (Debian 12's 1.14 has no slang shader compiler), Mesa's lavapipe Vulkan
# driver, Xvfb and D-Bus, plus crtforge's still-picture libretro core compiled into it.
#
#   CRTFORGE_RETROARCH_ROOT   where the root lives (default /var/cache/crtforge/retroarch-trixie);
#                             keep it outside any build tree: it is about 1.7 GB.
#   CRTFORGE_DEBIAN_MIRROR    Debian mirror (default http://deb.debian.org/debian)
#
# Idempotent: a complete root carries a stamp naming what it was built with; with a matching stamp
# only the core is recompiled, and only when its source changed. A root is built in a temporary
# sibling folder and renamed into place only when complete, so an interrupted run never leaves a
# half root that looks done. Needs root (debootstrap, chroot, mount).
set -euo pipefail

ROOT="${CRTFORGE_RETROARCH_ROOT:-/var/cache/crtforge/retroarch-trixie}"
MIRROR="${CRTFORGE_DEBIAN_MIRROR:-http://deb.debian.org/debian}"
SUITE=trixie
# --no-install-recommends keeps the root small; these are all RetroArch needs to render headless:
# libretro.h (retroarch-dev, in /usr/include/libretro-common) for the core, lavapipe
# (mesa-vulkan-drivers) for Vulkan, Mesa's GL (libgl1-mesa-dri, libglx-mesa0) for glcore, Xvfb and
# its keymap compiler (x11-xkb-utils), xauth (xvfb-run, for debugging by hand), dbus for
# dbus-run-session (RetroArch needs a session bus).
PACKAGES=(retroarch retroarch-dev libvulkan1 mesa-vulkan-drivers libgl1-mesa-dri libglx-mesa0
          xvfb xauth x11-xkb-utils dbus)
STAMP_NAME=.crtforge-root-complete
STAMP_TEXT="crtforge retroarch root v1: suite=$SUITE variant=minbase packages=${PACKAGES[*]}"

HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
CORE_SRC="$HERE/tools/retroarch-runner/still_core.c"
CORE_DIR=opt/crtforge
CORE_NAME=crtforge_still_libretro.so

say() { echo "setup-retroarch: $*"; }
die() { echo "setup-retroarch: error: $*" >&2; exit 1; }

[[ "$(id -u)" == 0 ]] || die "must run as root (debootstrap, chroot and mount need it)"
[[ "$ROOT" == /* ]] || die "CRTFORGE_RETROARCH_ROOT must be an absolute path, got '$ROOT'"
[[ -f "$CORE_SRC" ]] || die "missing $CORE_SRC"

# Host tools: debootstrap to build the root, a C compiler for the core (built on the host, against
# the root's libretro.h; it needs only libc, and trixie's glibc runs what bookworm's built).
host_missing=()
command -v debootstrap >/dev/null 2>&1 || host_missing+=(debootstrap)
command -v cc >/dev/null 2>&1 || host_missing+=(gcc libc6-dev)
if ((${#host_missing[@]})); then
  say "installing on the host: ${host_missing[*]}"
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq >/dev/null 2>&1 || die "apt-get update failed"
  apt-get install -y -qq --no-install-recommends "${host_missing[@]}" >/dev/null 2>&1 ||
    die "apt-get install ${host_missing[*]} failed"
fi
[[ -f /usr/share/debootstrap/scripts/$SUITE ]] || die "this debootstrap does not know '$SUITE'"

# Unmounts everything mounted at or below $1 (deepest first), so rm -rf never walks into /proc.
unmount_below() {
  local dir="$1" m
  [[ -d "$dir" ]] || return 0
  dir="$(cd "$dir" && pwd -P)"
  while read -r m; do
    umount -l "$m" 2>/dev/null || true
  done < <(awk -v d="$dir" '$2 == d || index($2, d "/") == 1 { print $2 }' /proc/self/mounts | sort -r)
}
remove_tree() { unmount_below "$1"; rm -rf --one-file-system "$1"; }

parent="$(dirname "$ROOT")"
base="$(basename "$ROOT")"
mkdir -p "$parent"

if [[ -f "$ROOT/$STAMP_NAME" && "$(cat "$ROOT/$STAMP_NAME")" == "$STAMP_TEXT" ]]; then
  say "root ready at $ROOT"
else
  # Leftovers of interrupted runs, and an old or unfinished root, go first.
  for old in "$parent/.$base.partial."*; do
    [[ -e "$old" ]] && { say "removing unfinished $old"; remove_tree "$old"; }
  done
  work="$parent/.$base.partial.$$"
  debs="$parent/.$base.debs"   # package cache: survives an interrupted run, removed on success
  mkdir -p "$debs"
  log="$parent/.$base.setup.log"
  : >"$log"
  # Long steps run in the background and are waited for, so that a signal is handled at once:
  # the step is stopped and the unfinished tree removed (EXIT trap).
  child=""
  step() { "$@" >>"$log" 2>&1 & child=$!; wait "$child"; }
  trap 'remove_tree "$work"' EXIT
  trap '[[ -z "$child" ]] || kill "$child" 2>/dev/null; wait; exit 130' INT TERM
  say "building a Debian $SUITE root in $work (log: $log); this downloads ~500 MB"
  step debootstrap --variant=minbase --cache-dir="$debs" "$SUITE" "$work" "$MIRROR" ||
    die "debootstrap failed: $(tail -n 1 "$work/debootstrap/debootstrap.log" 2>/dev/null || tail -n 1 "$log")"

  mount -t proc proc "$work/proc"
  mkdir -p "$work/var/cache/apt/archives"
  mount --bind "$debs" "$work/var/cache/apt/archives"
  echo "deb $MIRROR $SUITE main" >"$work/etc/apt/sources.list"
  say "installing into the root: ${PACKAGES[*]}"
  step chroot "$work" /usr/bin/env DEBIAN_FRONTEND=noninteractive LC_ALL=C.UTF-8 \
    apt-get -o Dpkg::Use-Pty=0 update || die "apt-get update in the root failed (see $log)"
  step chroot "$work" /usr/bin/env DEBIAN_FRONTEND=noninteractive LC_ALL=C.UTF-8 \
    apt-get -o Dpkg::Use-Pty=0 install -y --no-install-recommends "${PACKAGES[@]}" ||
    die "apt-get install in the root failed: $(grep -E '^E:' "$log" | tail -n 1)"
  [[ -x "$work/usr/bin/retroarch" && -f "$work/usr/include/libretro-common/libretro.h" ]] ||
    die "root has no /usr/bin/retroarch or /usr/include/libretro-common/libretro.h"
  version="$(chroot "$work" dpkg-query -W -f '${Version}' retroarch)"
  unmount_below "$work"
  mkdir -p "$work/$CORE_DIR"
  echo "$STAMP_TEXT" >"$work/$STAMP_NAME"
  if [[ -e "$ROOT" ]]; then
    say "replacing the old root at $ROOT"
    mv "$ROOT" "$parent/.$base.partial.old.$$"
    remove_tree "$parent/.$base.partial.old.$$"
  fi
  mv "$work" "$ROOT"
  trap - EXIT
  rm -rf "$debs"
  say "root ready at $ROOT (retroarch $version, $(du -sh "$ROOT" | cut -f1))"
fi

# The still-picture core, recompiled when its source changed (hash kept beside it).
core="$ROOT/$CORE_DIR/$CORE_NAME"
src_hash="$(sha256sum "$CORE_SRC" | cut -d' ' -f1)"
if [[ -f "$core" && "$(cat "$core.src-sha256" 2>/dev/null)" == "$src_hash" ]]; then
  say "still core up to date: $core"
else
  mkdir -p "$ROOT/$CORE_DIR"
  cc -std=c99 -O2 -Wall -Wextra -Werror -shared -fPIC -I"$ROOT/usr/include/libretro-common" \
    -o "$core.tmp" "$CORE_SRC" 2>"$ROOT/$CORE_DIR/build.log" ||
    die "compiling $CORE_SRC failed: $(head -n 1 "$ROOT/$CORE_DIR/build.log")"
  mv "$core.tmp" "$core"
  echo "$src_hash" >"$core.src-sha256"
  say "still core built: $core"
fi
