#!/bin/bash
# A build onto a disk that fills up: exit 1 naming "No space left on device", no abort, nothing
# half-written beside the output (no <out>.tmp-*), and an earlier output left exactly as it was.
# Without a cache, with a fresh cache on the full disk, with a cache elsewhere, and as a shard.
# The disk is a 1 MB tmpfs with 700 KB taken, mounted as root; elsewhere the test is skipped
# (exit 77), saying why.
# Usage: full_disk.sh WATERGEN MATERIAL SCENE WORKDIR
set -u
watergen=$1 material=$2 scene=$3 work=$4
[ "$(id -u)" = 0 ] || { echo "SKIP: mounting a small tmpfs needs root"; exit 77; }
rm -rf "$work" && mkdir -p "$work/disk" || exit 1
mount -t tmpfs -o size=1m tmpfs "$work/disk" 2>"$work/mount.txt" ||
  { echo "SKIP: mount -t tmpfs refused: $(cat "$work/mount.txt")"; exit 77; }
trap 'umount "$work/disk"; rm -rf "$work"' EXIT
head -c 700000 /dev/zero >"$work/disk/filler" || exit 1
# An earlier output: a directory of one file a build would replace (its manifest says so).
mkdir -p "$work/disk/o" && printf '{"generator": "watergen 0"}\n' >"$work/disk/o/manifest.json"
result=0
run() {
  local name=$1
  shift
  "$watergen" build "$material" --scene "$scene" --out "$work/disk/o" -q -j 1 "$@" \
    >"$work/$name.txt" 2>&1
  local status=$? said
  said=$(cat "$work/$name.txt")
  if [ $status -ne 1 ]; then
    echo "FAIL: $name: exit $status (expected 1): $said"; result=1
  elif ! grep -q "No space left on device" "$work/$name.txt"; then
    echo "FAIL: $name: no 'No space left on device' in: $said"; result=1
  elif grep -q "terminate called" "$work/$name.txt"; then
    echo "FAIL: $name: an uncaught exception: $said"; result=1
  else
    echo "$name: exit 1: $(grep -m1 'No space' "$work/$name.txt")"
  fi
  local left
  left=$(ls -d "$work"/disk/o.* 2>/dev/null)
  [ -z "$left" ] || { echo "FAIL: $name: left beside the output: $left"; result=1; }
  [ "$(ls -A "$work/disk/o")" = manifest.json ] &&
    [ "$(cat "$work/disk/o/manifest.json")" = '{"generator": "watergen 0"}' ] ||
    { echo "FAIL: $name: the earlier output changed: $(ls -A "$work/disk/o")"; result=1; }
}
run no_cache --no-cache
run cache_on_the_full_disk --cache "$work/disk/cache"
rm -rf "$work/disk/cache"
run cache_elsewhere --cache "$work/cache"
run shard --no-cache --shard 1/2
[ $result -eq 0 ] && echo "full disk: every build exited 1 and left the earlier output as it was"
exit $result
