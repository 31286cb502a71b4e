#!/bin/bash
# usage: expect_error.sh EXIT_STATUS REGEX command args...
# Runs the command; passes if it exits with EXIT_STATUS and its stderr
# matches REGEX (extended grep), so that each bad input is proven to get a
# clear message and the right exit status, not a crash.
expected_status=$1; shift
pattern=$1; shift
stderr_file=$(mktemp)
"$@" > /dev/null 2> "$stderr_file"
status=$?
echo "exit status: $status (expected $expected_status)"
echo "stderr:"; cat "$stderr_file"
if [ "$status" -ne "$expected_status" ]; then rm -f "$stderr_file"; echo "FAIL: wrong exit status"; exit 1; fi
if ! grep -E -q -- "$pattern" "$stderr_file"; then rm -f "$stderr_file"; echo "FAIL: message does not match /$pattern/"; exit 1; fi
rm -f "$stderr_file"
echo "PASS"
