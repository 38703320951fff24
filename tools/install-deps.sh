#!/usr/bin/env bash
# Installs what the raymarcher needs on Debian 12, and nothing when all is present.
# Debian packages come from the system's own sources; Fennel 1.5.x comes from the trixie
# suite's .deb, fetched through a private apt state so the system stays on bookworm.
set -euo pipefail

# Extra packages may be named on the command line (make report adds gnuplot-nox).
# LÖVE and SDL load OpenGL at run time and depend on no driver package: name Mesa's
# GL/EGL libraries and its DRI drivers (llvmpipe) so that a bare machine renders.
packages=(love luajit lua5.4 glslang-tools libosmesa6 lua-busted lua-filesystem
          libgl1 libegl1 libglx-mesa0 libegl-mesa0 libgl1-mesa-dri "$@")
fennel_suite=trixie
mirror=${DEBIAN_MIRROR:-http://deb.debian.org/debian}
keyring=/usr/share/keyrings/debian-archive-keyring.gpg

sudo=""
if [ "$(id -u)" != 0 ]; then sudo="sudo"; fi
export DEBIAN_FRONTEND=noninteractive

# Runs an apt command, waiting while another process (an unattended upgrade, another
# install) holds apt's or dpkg's lock, up to 10 minutes; its output is shown only if
# it fails for another reason.
apt_waiting() {
  local log waited=0
  log=$(mktemp)
  while ! "$@" >"$log" 2>&1; do
    if grep -qiE "could not get lock|unable to acquire the dpkg frontend lock|unable to lock" "$log" \
       && [ "$waited" -lt 600 ]; then
      [ "$waited" -eq 0 ] && echo "install-deps: apt is busy (another process holds its lock); waiting for it" >&2
      sleep 5; waited=$((waited + 5))
      continue
    fi
    cat "$log" >&2
    rm -f "$log"
    echo "install-deps: failed: $*" >&2
    return 1
  done
  rm -f "$log"
}
lock_wait=(-o DPkg::Lock::Timeout=600)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  apt_waiting $sudo apt-get update -qq
  apt_waiting $sudo apt-get "${lock_wait[@]}" install -y -qq --no-install-recommends "${missing[@]}"
fi

fennel_ok() {
  command -v fennel >/dev/null 2>&1 && fennel --version 2>/dev/null | grep -q '^Fennel 1\.[5-9]'
}

if ! fennel_ok; then
  echo "install-deps: fetching fennel from Debian $fennel_suite (private apt state, system sources untouched)"
  state=$(mktemp -d)
  trap 'rm -rf "$state"' EXIT
  mkdir -p "$state/lists/partial" "$state/cache/archives/partial" "$state/parts" "$state/deb"
  echo "deb [signed-by=$keyring] $mirror $fennel_suite main" > "$state/sources.list"
  apt_private=(-o "Dir::Etc::SourceList=$state/sources.list" -o "Dir::Etc::SourceParts=$state/parts"
               -o "Dir::State::Lists=$state/lists" -o "Dir::Cache=$state/cache"
               -o "APT::Sandbox::User=root")
  apt-get "${apt_private[@]}" update -qq
  (cd "$state/deb" && apt-get "${apt_private[@]}" download -qq fennel)
  apt_waiting $sudo apt-get "${lock_wait[@]}" install -y -qq --no-install-recommends "$state"/deb/fennel_*.deb
  fennel_ok || { echo "install-deps: fennel was installed but 'fennel --version' is not 1.5+" >&2; exit 1; }
fi
