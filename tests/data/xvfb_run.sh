#!/usr/bin/env bash
# Runs a command under xvfb-run (a virtual X display) and exits with the command's own status.
# xvfb-run itself exits 5 when it cannot remove its temporary directory, which happens when the command
# ends within a fraction of a second (Xvfb may still be writing there): a demo that refuses its input at
# once would then read as a failure of the wrong kind.
status_file=$(mktemp) || exit 1
xvfb-run -a -s "-screen 0 1280x720x24" bash -c '"$@"; echo $? > "$0"' "$status_file" "$@"
xvfb_status=$?
status=$(cat "$status_file" 2>/dev/null)
rm -f "$status_file"
[ -n "$status" ] && exit "$status"
exit "$xvfb_status"
