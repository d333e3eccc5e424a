#!/usr/bin/env bash
# Writes the robot's bundle: make-bundle.sh AGENT_BINARY POLICY_CKPT BUNDLE_DIR.
# The aarch64 upkie-rl-agent, the arm64 libraries it needs beyond the C library (lib/, on its
# run path), a policy, the robot's URDF, a run script and a README. Refuses a binary that
# needs a library the bundle does not hold.
set -euo pipefail
agent="$1"; policy="$2"; bundle="$3"
here="$(cd "$(dirname "$0")" && pwd)"
root="$(cd "$here/../.." && pwd)"
arm64_libdir=/usr/lib/aarch64-linux-gnu
cross_libdir=/usr/aarch64-linux-gnu/lib
rm -rf "$bundle"
mkdir -p "$bundle/lib"
cp "$agent" "$bundle/upkie-rl-agent"
aarch64-linux-gnu-strip "$bundle/upkie-rl-agent"
# yaml-cpp 0.7 and urdfdom 3 on Debian 12, 0.8 and 4 on Debian 13 (the sonames
# cmake/agent_only.cmake linked).
for library in libyaml-cpp.so.0.[0-9] liburdfdom_model.so.[0-9].0 libtinyxml.so.2.6.2 \
               libconsole_bridge.so.1.0; do
  cp -L "$arm64_libdir"/$library "$bundle/lib/"
done
cp -L "$cross_libdir/libstdc++.so.6" "$cross_libdir/libgcc_s.so.1" "$bundle/lib/"
cp "$policy" "$bundle/policy.ckpt"
cp "$root/models/upkie/upkie.urdf" "$bundle/upkie.urdf"
cp "$here/run-agent.sh" "$here/README.md" "$bundle/"
# Every library needed is in lib/ or the C library's (libc, libm, the loader). One that a
# library above needs in its turn is taken from Debian's arm64 libraries too (urdfdom 4 needs
# TinyXML2 on Debian 13), until nothing is missing.
added=1
while [ "$added" = 1 ]; do
  added=0
  for file in "$bundle/upkie-rl-agent" "$bundle"/lib/*; do
    for needed in $(aarch64-linux-gnu-readelf -d "$file" | sed -n 's/.*Shared library: \[\(.*\)\]/\1/p'); do
      case "$needed" in
        libc.so.6|libm.so.6|ld-linux-aarch64.so.1) ;;
        *)
          [ -f "$bundle/lib/$needed" ] && continue
          if [ -f "$arm64_libdir/$needed" ]; then
            cp -L "$arm64_libdir/$needed" "$bundle/lib/"
            added=1
          else
            echo "make-bundle: $file needs $needed, not in lib/ nor in $arm64_libdir" >&2
            exit 1
          fi
          ;;
      esac
    done
  done
done
echo "bundle $bundle: $(du -sh "$bundle" | cut -f1), binary $(du -h "$bundle/upkie-rl-agent" | cut -f1)"
