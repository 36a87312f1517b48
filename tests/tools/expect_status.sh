#!/usr/bin/env bash
# expect_status.sh STATUS TEXT -- COMMAND ARGS...
# Runs COMMAND, prints its output, and passes only if it exits with STATUS *and* its output (stdout and
# stderr) contains TEXT (a fixed string). ctest's PASS_REGULAR_EXPRESSION alone ignores the exit status: a
# tool that prints the right words and then fails (or succeeds where it must refuse) would pass.
set -u
if [[ $# -lt 4 || "$3" != "--" ]]; then
  echo "usage: expect_status.sh STATUS TEXT -- COMMAND ARGS..." >&2
  exit 2
fi
want="$1" text="$2"
shift 3
out=$("$@" 2>&1)
got=$?
printf '%s\n' "$out"
ok=1
if [[ "$got" != "$want" ]]; then
  echo "expect_status: exit status $got, expected $want" >&2
  ok=0
fi
if ! grep -qF -- "$text" <<<"$out"; then
  echo "expect_status: output lacks \"$text\"" >&2
  ok=0
fi
[[ $ok == 1 ]]
