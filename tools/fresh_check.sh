#!/usr/bin/env bash
# Runs the README's two first commands on a fresh Debian 12 machine, as a newcomer would: copies the
# committed tree (git archive of REF, default HEAD; never the working tree) into a pristine Debian 12
# (bookworm) root made by `debootstrap --variant=minbase`, and there, as root in /root/loom, runs the first two
# indented command lines of that tree's README.md (now `tools/setup.sh && build/loom run scenes/...toml` and
# `tools/test.sh`). A CI that is green on a developer's machine hides install steps that only that machine
# has; this check does not.
#
# Usage (as root, from anywhere in the repository):
#   tools/fresh_check.sh [--keep] [--jobs N] [--refresh] [--env N=V]... [REF]
#     REF        commit, branch or tag to check (default HEAD); uncommitted changes are not seen
#     --keep     keep the root afterwards for inspection (unmounted; `chroot ROOT bash` to look around)
#     --jobs N   LOOM_JOBS=N for the build and ctest in the root (default: setup.sh's, all cores)
#     --refresh  debootstrap again instead of reusing the cached pristine root
#     --env N=V  add N=V to the commands' environment (a diagnosis, e.g. OPENBLAS_CORETYPE=Haswell)
# Environment: LOOM_FRESH_CACHE (default /var/tmp/loom-fresh: the pristine root tarball, the runs' roots and
#   logs/), LOOM_FRESH_MIRROR (default http://deb.debian.org/debian).
#
# Each phase is printed with its duration; the whole log is kept in $LOOM_FRESH_CACHE/logs/. Exits 0 when both
# commands pass, otherwise non-zero and names the command that failed.
# How long (two cores): debootstrap 1-2 minutes, on the first run only (later runs unpack the cached tarball
# in seconds); the first command, apt installs and the build of the program, about 11 minutes; the second, the test
# programs' build and the default suite, about 23 minutes (measured at cc2490f: 10m56s and 22m46s).
# Disk: ~4 GB per root (removed afterwards unless --keep), 164 MB for the cached tarball. Uses only Debian
# packages (debootstrap, installed with apt if missing).
set -euo pipefail

usage() { sed -n '9,18p' "$0" | sed 's/^# \{0,1\}//'; }
keep=0 jobs="" refresh=0 ref=HEAD extra_env=() args=("$@")
while [ $# -gt 0 ]; do
  case $1 in
    --keep) keep=1 ;;
    --jobs) [ $# -ge 2 ] || { echo "fresh_check: --jobs needs a number" >&2; exit 2; }; jobs=$2; shift ;;
    --jobs=*) jobs=${1#--jobs=} ;;
    --refresh) refresh=1 ;;
    --env) if [ $# -lt 2 ] || [[ $2 != [A-Za-z_]*=* ]]; then echo "fresh_check: --env wants NAME=VALUE" >&2; exit 2; fi
           extra_env+=("$2"); shift ;;
    -h|--help) usage; exit 0 ;;
    -*) echo "fresh_check: unknown option $1" >&2; usage >&2; exit 2 ;;
    *) ref=$1 ;;
  esac
  shift
done
if [ -n "$jobs" ] && ! [[ $jobs =~ ^[1-9][0-9]*$ ]]; then
  echo "fresh_check: --jobs wants a positive number, not '$jobs'" >&2; exit 2
fi
if [ "$(id -u)" -ne 0 ]; then
  echo "fresh_check: needs root (debootstrap, chroot and mounts): run it as 'sudo $0 ${args[*]}'" >&2
  exit 2
fi

repo=$(git -C "$(dirname "$0")" rev-parse --show-toplevel)
commit=$(git -C "$repo" rev-parse --verify --quiet "$ref^{commit}") || { echo "fresh_check: no commit '$ref'" >&2; exit 2; }
short=$(git -C "$repo" rev-parse --short "$commit")

cache=${LOOM_FRESH_CACHE:-/var/tmp/loom-fresh}
mirror=${LOOM_FRESH_MIRROR:-http://deb.debian.org/debian}
arch=$(dpkg --print-architecture)
pristine=$cache/bookworm-minbase-$arch.tar
mkdir -p "$cache/logs"
work=$(mktemp -d "$cache/run-$(date +%Y%m%d-%H%M%S)-$short.XXXX")
root=$work/root
log=$cache/logs/$(basename "$work").log
: > "$log"
# tee ignores Ctrl-C so that the clean-up's messages still reach the terminal and the log.
exec > >(trap '' INT TERM; exec tee -a "$log") 2>&1
tee_pid=$!

mounts=() child=""
cleanup() {
  local rc=$? i
  trap - EXIT INT TERM
  if [ -n "$child" ] && kill -0 "$child" 2>/dev/null; then  # interrupted: stop the command's whole group first
    kill -TERM -- "-$child" 2>/dev/null
    for i in $(seq 20); do kill -0 "$child" 2>/dev/null || break; sleep 0.5; done
    kill -KILL -- "-$child" 2>/dev/null || true
    wait "$child" 2>/dev/null || true
  fi
  for ((i = ${#mounts[@]} - 1; i >= 0; i--)); do
    umount -R "${mounts[i]}" 2>/dev/null || umount -R -l "${mounts[i]}" || echo "fresh_check: could not unmount ${mounts[i]}"
  done
  [ ${#timings[@]} -gt 0 ] && summary
  if awk -v r="$root" '$5 == r || index($5, r "/") == 1 { f = 1 } END { exit !f }' /proc/self/mountinfo; then
    echo "fresh_check: something is still mounted under $root; not removing it"
  elif [ "$keep" = 1 ]; then
    echo "fresh_check: root kept: $root (chroot $root bash; remove with rm -rf $work)"
  else
    rm -rf --one-file-system "$work"
  fi
  echo "fresh_check: log: $log"
  exec >&- 2>&-
  wait "$tee_pid" 2>/dev/null || true   # tee writes the last lines before the prompt returns
  exit "$rc"
}
trap cleanup EXIT
trap 'echo "fresh_check: interrupted"; exit 130' INT
trap 'echo "fresh_check: terminated"; exit 143' TERM

t_start=$(date +%s)
phase_t0=0
phase() { phase_t0=$(date +%s); echo; echo "=== fresh_check: $1 ($(date '+%H:%M:%S'))"; }
took() { local d=$(($(date +%s) - phase_t0)); printf '=== fresh_check: %s took %dm%02ds\n' "$1" $((d / 60)) $((d % 60)); timings+=("$(printf '%-40s %3dm%02ds' "$1" $((d / 60)) $((d % 60)))"); }
timings=()
summary() { # the phases' durations and ctest's count
  local d=$(($(date +%s) - t_start)) tests
  echo
  echo "fresh_check: timings"
  printf '  %s\n' "${timings[@]}"
  printf '  %-40s %3dm%02ds\n' "total" $((d / 60)) $((d % 60))
  tests=$(grep -aE '^[0-9]+% tests passed' "$log" | tail -1) && echo "fresh_check: ctest: $tests"
  timings=()
}

echo "fresh_check: $short ($(git -C "$repo" log -1 --format=%s "$commit" | cut -c1-80)) in a fresh Debian 12 minbase root"
echo "fresh_check: root $root, log $log"

# 1. The pristine root: debootstrap once, cached as a tarball; every run unpacks a new copy.
if [ "$refresh" = 1 ] || [ ! -s "$pristine" ]; then
  phase "debootstrap bookworm minbase from $mirror"
  if ! command -v debootstrap >/dev/null; then
    apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends debootstrap
  fi
  fresh=$cache/debootstrap.$$
  rm -rf --one-file-system "$fresh"
  debootstrap --variant=minbase --arch="$arch" bookworm "$fresh" "$mirror"
  rm -f "$fresh"/var/cache/apt/archives/*.deb
  tar -C "$fresh" --numeric-owner -cpf "$pristine.tmp.$$" .
  mv "$pristine.tmp.$$" "$pristine"
  rm -rf --one-file-system "$fresh"
  took "debootstrap (cached for later runs)"
fi
phase "unpack the pristine root ($pristine)"
mkdir "$root"
tar -C "$root" --numeric-owner -xpf "$pristine"
took "unpack pristine root"

# 2. The committed tree, and what a chroot needs. policy-rc.d keeps package scripts from starting
# services (on the host's kernel) while apt installs in the root.
phase "copy $short (git archive) to /root/loom"
git -C "$repo" archive --format=tar --prefix=loom/ "$commit" | tar -C "$root/root" -xf -
mapfile -t cmds < <(awk '/^    [^ ]/ { sub(/^    /, ""); print; if (++n == 2) exit }' "$root/root/loom/README.md")
[ ${#cmds[@]} -eq 2 ] || { echo "fresh_check: README.md of $short has no two indented command lines"; exit 2; }
took "copy (git archive)"

printf '#!/bin/sh\nexit 101\n' > "$root/usr/sbin/policy-rc.d"
chmod 755 "$root/usr/sbin/policy-rc.d"
mnt() { # mnt TARGET MOUNT-ARGS...: mount and remember, private so nothing propagates back to the host
  local target=$1; shift
  mount "$@" "$target" || return 1
  mounts+=("$target")
  mount --make-rprivate "$target"
}
mnt "$root/proc" -t proc proc
mnt "$root/sys" -t sysfs sysfs 2>/dev/null || mnt "$root/sys" --rbind /sys
mnt "$root/dev" --bind /dev
mnt "$root/dev/pts" --bind /dev/pts
mkdir -p "$root/dev/shm"
mnt "$root/dev/shm" -t tmpfs -o mode=1777 tmpfs
if [ -L "$root/etc/resolv.conf" ] || [ ! -f "$root/etc/resolv.conf" ]; then
  rm -f "$root/etc/resolv.conf"; : > "$root/etc/resolv.conf"
fi
mnt "$root/etc/resolv.conf" --bind "$(readlink -f /etc/resolv.conf)"

# 3. The README's commands, as root in the root's copy of the repository, with a login's plain environment.
env_in=(HOME=/root PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin TERM=dumb)
[ -n "$jobs" ] && env_in+=(LOOM_JOBS="$jobs")
env_in+=("${extra_env[@]}")
names=("setup+build+default scene" "tests")
for i in 0 1; do
  phase "command $((i + 1)): ${cmds[i]}"
  # In a process group of its own, waited for in the background, so that Ctrl-C or a TERM reaches the
  # clean-up at once, which stops the group before it unmounts.
  setsid env -i "${env_in[@]}" chroot "$root" /bin/bash -c "cd /root/loom && ${cmds[i]}" < /dev/null &
  child=$!
  rc=0; wait "$child" || rc=$?
  child=""
  took "${names[i]}"
  if [ $rc -ne 0 ]; then
    summary
    echo "fresh_check: FAILED: README command $((i + 1)) \`${cmds[i]}\` exited $rc on a fresh Debian 12 root ($short)"
    exit 1
  fi
done

summary
echo "fresh_check: PASSED: both README commands on a fresh Debian 12 root ($short)"
