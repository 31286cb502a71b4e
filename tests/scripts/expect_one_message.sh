#!/bin/bash
# usage: expect_one_message.sh REGEX command args...
# Runs the command; passes if it exits with status 1, its stderr holds
# exactly one "tmfdem: " message, no raw parser report (muparser's
# "Message:/Formula:/Token:/Position:/Errc:" lines), and matches REGEX
# (extended grep, over the whole stderr).
pattern=$1; shift
stderr_file=$(mktemp)
"$@" > /dev/null 2> "$stderr_file"
status=$?
echo "exit status: $status (expected 1)"
echo "stderr:"; cat "$stderr_file"
fail() { rm -f "$stderr_file"; echo "FAIL: $1"; exit 1; }
[ "$status" -eq 1 ] || fail "wrong exit status"
[ "$(grep -c '^tmfdem: ' "$stderr_file")" -eq 1 ] || fail "not exactly one tmfdem message"
! grep -E -q '^(Message|Formula|Token|Position|Errc): ' "$stderr_file" || fail "raw parser report on stderr"
tr '\n' ' ' < "$stderr_file" | grep -E -q -- "$pattern" || fail "message does not match /$pattern/"
rm -f "$stderr_file"
echo "PASS"
