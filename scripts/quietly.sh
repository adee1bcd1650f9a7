#!/usr/bin/env bash
# quietly.sh LOG COMMAND...: runs COMMAND with its output appended to LOG; on failure prints the
# command and LOG's tail (where pip and the compiler put their errors) and exits with its status.
set -uo pipefail
log=$1
shift
mkdir -p "$(dirname "$log")"
echo "\$ $*" >>"$log"
"$@" >>"$log" 2>&1
status=$?
if [ "$status" -ne 0 ]; then
  echo "failed ($status): $*" >&2
  echo "the last lines of $log:" >&2
  tail -n 60 "$log" >&2
fi
exit "$status"
