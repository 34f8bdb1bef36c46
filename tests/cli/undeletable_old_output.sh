#!/bin/bash
# A build that replaces an output whose old tree cannot be removed: the new output is in place,
# exit 0, and one warning names where the old tree was left (it stays until removed by hand).
# The old tree is made undeletable with an immutable file (chattr +i) as root, for whom
# permissions do not stop a removal, and with a read-only directory otherwise.
# Usage: undeletable_old_output.sh WATERGEN MATERIAL WORKDIR
set -u
watergen=$1 material=$2 work=$3
rm -rf "$work" && mkdir -p "$work" || exit 1
out=$work/out
"$watergen" build "$material" --out "$out" --no-cache -q >"$work/first.txt" 2>&1 ||
  { echo "FAIL: the first build failed: $(cat "$work/first.txt")"; exit 1; }
pin=$out/pinned
mkdir "$pin" && echo kept >"$pin/file"
if [ "$(id -u)" = 0 ]; then
  chattr +i "$pin/file" 2>"$work/chattr.txt" ||
    { echo "SKIP: running as root and chattr +i failed ($(cat "$work/chattr.txt")): no way to make a tree undeletable"; exit 0; }
  release() { chattr -i "$pin"/file "$work"/out.tmp-*/pinned/file 2>/dev/null; }
else
  chmod 0555 "$pin"
  release() { chmod 0755 "$pin" "$work"/out.tmp-*/pinned 2>/dev/null; }
fi
"$watergen" build "$material" --out "$out" --no-cache -q >"$work/second.txt" 2>&1
status=$?
said=$(cat "$work/second.txt")
left=$(ls -d "$work"/out.tmp-* 2>/dev/null)
release
result=0
[ $status -eq 0 ] || { echo "FAIL: the second build exited $status: $said"; result=1; }
[ -n "$left" ] || { echo "FAIL: no old tree left (nothing to warn about?)"; result=1; }
[ -e "$out/pinned" ] && { echo "FAIL: the old output is still at $out"; result=1; }
expected="watergen: warning: cannot remove the replaced $left: "
case "$said" in
  *"$expected"*"; remove it by hand"*) ;;
  *) echo "FAIL: expected a warning starting '$expected', got: $said"; result=1 ;;
esac
[ $result -eq 0 ] && echo "old tree left at $left, and said: $(grep warning "$work/second.txt")"
release
rm -rf "$work"
exit $result
