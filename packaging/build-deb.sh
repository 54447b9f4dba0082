#!/usr/bin/env bash
# Builds the Debian package of Pierce: configures the Release tree ${PIERCE_BUILD_DIR:-build}
# (reused when present) for the prefix /usr, builds it, and runs CPack's DEB generator.
# Its last line of output is the path of the .deb:
#
#   deb=$(bash packaging/build-deb.sh | tail -n 1)
#   sudo apt-get install "$deb"          # (an absolute path, or ./pierce_*.deb)
#
# Needs dpkg-dev (dpkg-shlibdeps computes Depends) and help2man (the man page):
# packaging/install-deps.sh installs both.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD_DIR=${PIERCE_BUILD_DIR:-build}
for tool in dpkg-shlibdeps dpkg-deb help2man; do
  command -v "$tool" >/dev/null || { echo "build-deb: $tool not found (run packaging/install-deps.sh)" >&2; exit 1; }
done

# build.sh (re)configures with its Release settings; the prefix /usr gives the Debian layout
# (GNUInstallDirs: lib/x86_64-linux-gnu). Its output goes to stderr: stdout ends with the path.
bash packaging/build.sh -DCMAKE_INSTALL_PREFIX=/usr >&2

out="$BUILD_DIR/packages"
rm -rf "$out"
mkdir -p "$out"
(cd "$BUILD_DIR" && cpack -G DEB -B "$PWD/packages") >&2
shopt -s nullglob
debs=("$out"/pierce_*.deb)
if [ ${#debs[@]} -ne 1 ]; then
  echo "build-deb: expected one pierce_*.deb in $out, found ${#debs[@]}" >&2
  exit 1
fi
readlink -f "${debs[0]}"
