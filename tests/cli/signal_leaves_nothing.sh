#!/bin/bash
# `watergen compare` killed while its counting workers run (valgrind callgrind, minutes of CPU
# each): SIGNAL to the parent must leave no worker running and nothing in $TMPDIR (no
# watergen-count-* directory, no valgrind FIFO).
# SIGTERM and SIGINT: the parent's handler kills the workers and removes the directories, then
# ends by the signal. SIGKILL: the workers die with it (PR_SET_PDEATHSIG); their directories
# stay until the next count sweeps them, which is what the last step checks.
# Usage: signal_leaves_nothing.sh WATERGEN SIGNAL WORKDIR
set -u
watergen=$1 signal=$2 work=$3
rm -rf "$work" && mkdir -p "$work/tmp" || exit 1
export TMPDIR=$work/tmp # the scratch root (std::filesystem::temp_directory_path)
# compare runs in a process group of its own (setsid execs it: same pid), which its workers
# share: they are found, and on a failure ended, by that group alone.
fail() { echo "FAIL ($signal): $*"; kill -KILL -- -$parent 2>/dev/null; exit 1; }
survivors() { pgrep -g $parent | grep -vx $parent || true; }

compare_args=(compare --fresnel schlick,exact --views beach --size 16 --rounds 3 --draws 1
              --cost-size 16)
# (env --default-signal: a non-interactive shell starts background jobs with SIGINT ignored.)
setsid env --default-signal=INT,TERM "$watergen" "${compare_args[@]}" --out "$work/report" \
  >"$work/out.txt" 2>&1 &
parent=$!
# Wait for both workers to be counting (their directories and processes exist).
for _ in $(seq 1 600); do
  dirs=$(ls -d "$work"/tmp/watergen-count-* 2>/dev/null | wc -l)
  [ "$dirs" -ge 1 ] && [ -n "$(survivors)" ] && break
  kill -0 $parent 2>/dev/null || fail "compare ended before its workers started: $(cat "$work/out.txt")"
  sleep 0.2
done
[ -n "$(survivors)" ] || fail "no worker started within 120 s"
sleep 1 # the workers well into valgrind
kill -s "$signal" $parent
wait $parent
status=$?
expected=$((128 + $(kill -l "$signal")))
[ $status -eq $expected ] || fail "compare exited $status, expected $expected (killed by SIG$signal)"
# The workers are gone at once (killed, then waited for, by the handler; by the kernel on SIGKILL).
for _ in $(seq 1 50); do [ -z "$(survivors)" ] && break; sleep 0.1; done
[ -z "$(survivors)" ] || fail "workers still running: $(survivors | tr '\n' ' ')"
left=$(ls -A "$work"/tmp)
if [ "$signal" = KILL ]; then
  [ -n "$left" ] || fail "expected the killed process's directories to stay until the next count"
  # The next count sweeps them (their process is gone); it ends normally, leaving nothing.
  "$watergen" "${compare_args[@]}" --out "$work/report2" >"$work/out2.txt" 2>&1 ||
    fail "the next compare failed: $(cat "$work/out2.txt")"
  left=$(ls -A "$work"/tmp)
fi
[ -z "$left" ] || fail "left behind: $left"
echo "SIG$signal: compare exited $status, no worker running, nothing left in TMPDIR"
rm -rf "$work"
