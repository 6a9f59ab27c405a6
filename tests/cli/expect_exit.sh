#!/bin/sh
# expect_exit.sh STATUS REGEX -- COMMAND...: passes when COMMAND exits with STATUS and its
# output (stdout and stderr) matches the extended regular expression REGEX.
want="$1"; regex="$2"; shift 2
[ "$1" = "--" ] && shift
out=$("$@" 2>&1); got=$?
printf '%s\n' "$out"
if [ "$got" -ne "$want" ]; then echo "FAIL: exit status $got, expected $want"; exit 1; fi
if ! printf '%s\n' "$out" | grep -Eq -- "$regex"; then echo "FAIL: output does not match /$regex/"; exit 1; fi
echo "PASS: exit $got and the message names the problem"
