#!/usr/bin/env bash
# Puts CGAL's sample meshes (bunny00.off, armadillo.off, elephant.off: meshes such as a CGAL user
# would bring) into DIR, from Debian's libcgal-demo package (its data.tar.gz),
# without installing the package. Then:
#   pierce_bench_kernels --scene none --mesh DIR/bunny00.off --mesh DIR/armadillo.off --mesh DIR/elephant.off
# Usage: bench/fetch_cgal_meshes.sh DIR   (DIR is created; meshes already there are kept)
set -euo pipefail
if [ $# -ne 1 ]; then
  echo "usage: $0 DIR" >&2
  exit 2
fi
dest=$1
meshes=(bunny00.off armadillo.off elephant.off)
mkdir -p "$dest"
missing=()
for m in "${meshes[@]}"; do [ -e "$dest/$m" ] || missing+=("data/meshes/$m"); done
if [ ${#missing[@]} -eq 0 ]; then
  echo "all meshes already in $dest"
  exit 0
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
# apt-get download writes into the current directory; as root it warns that _apt cannot write
# there, which is harmless.
(cd "$work" && apt-get download libcgal-demo >/dev/null 2>&1) || {
  echo "$0: 'apt-get download libcgal-demo' failed (no network or no Debian package lists?)" >&2
  exit 1
}
deb=$(ls "$work"/libcgal-demo_*.deb)
dpkg-deb -x "$deb" "$work/x"
data=$(find "$work/x" -name data.tar.gz | head -n 1)
if [ -z "$data" ]; then
  echo "$0: $deb holds no data.tar.gz" >&2
  exit 1
fi
tar -xzf "$data" -C "$work" "${missing[@]}"
for m in "${missing[@]}"; do
  cp -n "$work/$m" "$dest/"
  echo "$dest/$(basename "$m")"
done
