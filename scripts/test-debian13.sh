#!/usr/bin/env bash
# `make test-debian13`: builds and tests a clean clone of HEAD inside a Debian 13 (trixie)
# chroot made by debootstrap, with the dependencies installed by the repository's own
# scripts/install-deps.sh. The chroot is made once and reused (a marker file says it is
# complete); the clone and its build directory are made anew at every run, and ccache,
# kept in the chroot, makes a rebuild of unchanged sources mostly cache hits.
# Needs root (debootstrap, mount, chroot) and the Debian mirror.
#
# Settings (environment):
#   DEBIAN13_ROOT    the chroot's directory (/var/tmp/upkie-rl-trixie)
#   DEBIAN13_MIRROR  the Debian mirror debootstrap reads (http://deb.debian.org/debian)
#   DEBIAN13_PYTEST  1 (default): run the Python tests after ctest; 0: ctest only
#   JOBS             parallel compile and test jobs (2)
set -euo pipefail

root="${DEBIAN13_ROOT:-/var/tmp/upkie-rl-trixie}"
mirror="${DEBIAN13_MIRROR:-http://deb.debian.org/debian}"
run_pytest="${DEBIAN13_PYTEST:-1}"
jobs="${JOBS:-2}"
repo_dir="$(cd "$(dirname "$0")/.." && pwd)"
# Inside the chroot: the clone, and its build directory.
chroot_src=/src/upkie-rl

if [ "$(id -u)" -ne 0 ]; then
  echo "test-debian13: needs root (debootstrap, mount, chroot)" >&2
  exit 1
fi
for tool in debootstrap chroot mount umount git; do
  command -v "$tool" >/dev/null || { echo "test-debian13: $tool is missing" >&2; exit 1; }
done

stage_start=0
stage() {
  stage_start=$(date +%s)
  echo "test-debian13: == $1 ($(date -u +%H:%M:%S) UTC)"
}
stage_done() {
  echo "test-debian13: == $1 took $(($(date +%s) - stage_start)) s"
}

# 1. The chroot, once: the marker is written only after debootstrap succeeded, so an
# interrupted debootstrap is started again from scratch.
marker="$root/.upkie-rl-debootstrap-complete"
if [ ! -f "$marker" ]; then
  stage "debootstrap trixie into $root"
  # Never remove a tree with the host's /dev or /proc still mounted in it (a killed run).
  if grep -q " $root/" /proc/mounts; then
    echo "test-debian13: file systems are still mounted under $root: unmount them first" >&2
    exit 1
  fi
  rm -rf "$root"
  debootstrap --variant=minbase --include=ca-certificates trixie "$root" "$mirror"
  touch "$marker"
  stage_done debootstrap
else
  echo "test-debian13: reusing the chroot $root"
fi

# 2. The kernel's file systems, unmounted on any exit (only those mounted here, innermost
# first). /dev/shm: the spine's tests map shared memory.
mounted=()
cleanup() {
  local index
  for ((index = ${#mounted[@]} - 1; index >= 0; index--)); do
    umount "${mounted[index]}" 2>/dev/null || umount -l "${mounted[index]}" || true
  done
}
trap cleanup EXIT
mount_into() {  # mount_into TARGET MOUNT_ARGUMENTS...
  local target="$root$1"
  shift
  mkdir -p "$target"
  if ! mountpoint -q "$target"; then
    mount "$@" "$target"
    mounted+=("$target")
  fi
}
mount_into /proc -t proc proc
mount_into /sys -t sysfs sysfs
mount_into /dev --bind /dev
mount_into /dev/pts --bind /dev/pts
mount_into /dev/shm -t tmpfs -o mode=1777 tmpfs
cp /etc/resolv.conf "$root/etc/resolv.conf"
# The host's own certificate authorities (a TLS proxy's, say), so that pip and npm in the
# chroot reach the registries as the host does.
if compgen -G "/usr/local/share/ca-certificates/*.crt" >/dev/null; then
  mkdir -p "$root/usr/local/share/ca-certificates"
  cp /usr/local/share/ca-certificates/*.crt "$root/usr/local/share/ca-certificates/"
  chroot "$root" update-ca-certificates >/dev/null
fi

# 3. A clean clone of HEAD (committed work only; no build/, venvs or node_modules of the
# host). The previous run's clone and build go first.
stage "clone of HEAD ($(git -C "$repo_dir" rev-parse --short HEAD))"
rm -rf "$root$chroot_src"
mkdir -p "$(dirname "$root$chroot_src")"
git clone --quiet --no-local --depth 1 "file://$repo_dir" "$root$chroot_src"
stage_done clone

in_chroot() {
  chroot "$root" /usr/bin/env -i HOME=/root TERM="${TERM:-dumb}" LANG=C.UTF-8 \
    PATH=/usr/local/sbin:/usr/local/bin:/usr/sbin:/usr/bin:/sbin:/bin \
    CCACHE_DIR=/root/.ccache CCACHE_BASEDIR="$chroot_src" \
    PIP_CERT=/etc/ssl/certs/ca-certificates.crt NODE_EXTRA_CA_CERTS=/etc/ssl/certs/ca-certificates.crt \
    UPKIE_RL_BUILD_DIR="$chroot_src/build" PYTHONPATH="$chroot_src/build/python" \
    bash -c "cd $chroot_src && $1"
}

# 4. The repository's own dependency script; git first, which the build records commits with.
stage "install-deps.sh"
in_chroot "command -v git >/dev/null || { apt-get update -q &&
  DEBIAN_FRONTEND=noninteractive apt-get install -y -q --no-install-recommends git; }"
in_chroot "bash scripts/install-deps.sh"
stage_done install-deps

stage "configure"
# The benchmarks are no tests: not built.
in_chroot "cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython_EXECUTABLE=/usr/bin/python3 \\
  -DUPKIE_RL_BUILD_BENCH=OFF"
stage_done configure

stage "build (-j $jobs, nice 10)"
in_chroot "nice -n 10 cmake --build build -j $jobs"
stage_done build

status=0
stage "ctest"
in_chroot "cd build && ctest --output-on-failure -j $jobs" || status=$?
stage_done ctest
if [ "$run_pytest" = "1" ]; then
  stage "pytest (Debian 13's python3)"
  # The docs site first (MkDocs from PyPI into .venv-docs), which test_docs_site.py checks.
  in_chroot "make docs PYTHON=/usr/bin/python3 BUILD_DIR=build" || status=$?
  in_chroot "python3 -m pytest -q -rs python/tests" || status=$?
  stage_done pytest
fi
echo "test-debian13: $(in_chroot '. /etc/os-release; echo $PRETTY_NAME'), exit status $status"
exit "$status"
