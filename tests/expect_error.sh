#!/usr/bin/env bash
# Runs the simulator on <base.prm> with extra lines appended and checks that it
# exits with <code> and prints text matching <regex> (extended grep).
# Usage: expect_error.sh <exe> <base.prm> <code> <regex> <extra prm lines...>
# An extra line @FILE appends that file (for values CMake cannot pass, e.g. ';').
# With <base.prm> = "-" the first extra argument is run as the input path itself.
set -u
exe=$1 base=$2 code=$3 regex=$4
shift 4
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
input="$work/input.prm"
if [ "$base" = "-" ]; then
  input=$1
else
  {
    cat "$base"
    for line in "$@"; do
      case "$line" in @*) cat "${line#@}" ;; *) printf '%s\n' "$line" ;; esac
    done
    printf 'subsection Output\n  set Directory = %s/out\n  set Write VTU = false\nend\n' "$work"
  } > "$input"
fi
out=$("$exe" --quiet "$input" 2>&1)
rc=$?
echo "$out"
[ "$rc" -eq "$code" ] || { echo "FAIL: exit code $rc, expected $code"; exit 1; }
echo "$out" | grep -Eq "$regex" || { echo "FAIL: output does not match /$regex/"; exit 1; }
echo "OK: exit code $rc and message matches /$regex/"
