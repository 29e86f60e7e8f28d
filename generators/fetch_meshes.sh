#!/bin/sh
# Fetches the CGAL sample meshes (armadillo, bunny, elephant, dragon, ...) for the mesh:NAME scenes.
# They ship in Debian's libcgal-demo package as usr/share/doc/libcgal-dev/data.tar.gz; this script
# downloads the package with `apt-get download` (no root needed, nothing installed), takes the mesh
# files (data/meshes/*.off|obj|ply|stl) out of that archive, and puts them in the cache folder
# .cache/meshes at the root of the repository (ignored by git), where `bspbench scenes` finds them.
# Two files get the short names users expect: bunny00.off becomes bunny.off and
# ChineseDragon-10kv.off becomes dragon.off. MANIFEST.tsv records, for every file, its name in the
# cache, its path in the package, its size and its SHA-256.
#
# Usage: generators/fetch_meshes.sh [CACHE_DIR]    (exit 0 on success, 1 when the package cannot be had)
set -eu

repo=$(cd "$(dirname "$0")/.." && pwd)
cache=${1:-"$repo/.cache/meshes"}
package=libcgal-demo
archive=./usr/share/doc/libcgal-dev/data.tar.gz

work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if ! (cd "$work" && apt-get download "$package" >"$work/apt.log" 2>&1); then
  echo "fetch_meshes: could not download $package with apt-get (see below); try 'apt-get update' first" >&2
  cat "$work/apt.log" >&2
  exit 1
fi
deb=$(ls "$work"/${package}_*.deb)
dpkg-deb --fsys-tarfile "$deb" | tar -x -C "$work" "$archive"
mkdir -p "$work/data"
tar -xzf "$work/$archive" -C "$work/data" data/meshes

short_name() {
  case "$1" in
    bunny00.off) echo bunny.off ;;
    ChineseDragon-10kv.off) echo dragon.off ;;
    *) echo "$1" ;;
  esac
}

mkdir -p "$cache"
manifest="$cache/MANIFEST.tsv"
printf 'name\tpackage_path\tbytes\tsha256\n' >"$manifest.tmp"
count=0
for f in "$work"/data/data/meshes/*; do
  case "$f" in *.off | *.obj | *.ply | *.stl) ;; *) continue ;; esac
  base=$(basename "$f")
  # Point clouds (a PLY with no faces, such as b9.ply) are no scenes.
  if grep -a -q '^element face 0' "$f"; then continue; fi
  name=$(short_name "$base")
  cp "$f" "$cache/$name.tmp" && mv "$cache/$name.tmp" "$cache/$name"
  printf '%s\t%s\t%s\t%s\n' "$name" "$(basename "$deb"):data.tar.gz:data/meshes/$base" \
    "$(wc -c <"$f" | tr -d ' ')" "$(sha256sum "$f" | cut -d' ' -f1)" >>"$manifest.tmp"
  count=$((count + 1))
done
mv "$manifest.tmp" "$manifest"
echo "fetch_meshes: $count meshes from $(basename "$deb") in $cache"
