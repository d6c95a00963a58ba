#!/usr/bin/env bash
# What the experimenter console's own window costs the participant's frames:
# the same scripted pilot session (8 trials, fixed-length input) run ROUNDS
# times with the console in its own window (--console-monitor 1) and
# without it, alternating, on two monitors (two_monitors.sh), 640 x 480. It
# prints, per layout, the median over trials of each trial's median frame
# time and of its 95th percentile, and the share of late frames (later than
# 1.5 refresh intervals), then open / closed ratios. Prints, never asserts.
# Usage: tests/app/bench_console_window.sh [BUILD_DIR] [ROUNDS]
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
build=${1:-$root/build}
rounds=${2:-3}
dtlab="$build/app/dtlab"
[ -x "$dtlab" ] || { echo "no $dtlab: build the dtlab target first" >&2; exit 2; }
command -v sqlite3 >/dev/null || { echo "needs the sqlite3 command (Debian package sqlite3)" >&2; exit 2; }
if [ -z "${DTLAB_BENCH_INNER:-}" ]; then
  DTLAB_BENCH_INNER=1 exec "$root/tests/app/two_monitors.sh" "$0" "$build" "$rounds"
fi
dir=$(mktemp -d "${TMPDIR:-/tmp}/dtlab-bench-console.XXXXXX")
trap 'rm -rf "$dir"' EXIT
cat > "$dir/bench.script" <<'SCRIPT'
[start]
wait 0.3
click_item "Participant ID"
type "bench-01"
click_item "age"
type "30"
click_item "Start session"
[instructions]
wait 0.2
click_item "Continue"
[training]
key Enter
[trial T1]
drag 320 240 480 250 2
key Enter
[answer T1]
type "23"
key Enter
[trial T2]
drag 320 240 320 160 2
key Enter
[answer T2]
click_item "K"
[trial T3]
hold Up 1
turn 200 1
key Enter
[answer T3]
click_item "floor plan" 0.55 0.45
click_item "Confirm"
[trial T4]
turn -150 1
hold Up 1
key Enter
[answer T4]
type "5"
key Enter
[break]
key Space
[questionnaire]
key 3
[questionnaire preference]
click_item "on"
[questionnaire depth_self]
key 2
[depth_test]
click_item "A"
[end]
click_item "Close"
SCRIPT
run() {  # $1 tag, rest: extra options
  local tag=$1
  shift
  "$dtlab" run "$root/protocols/pilot.toml" --db "$dir/$tag.sqlite" --size 640x480 --script "$dir/bench.script" "$@" \
    >"$dir/$tag.log" 2>&1 || { echo "session $tag failed:" >&2; cat "$dir/$tag.log" >&2; exit 1; }
  sqlite3 -separator ' ' "$dir/$tag.sqlite" \
    "SELECT frame_ms_median, frame_ms_p95, late_frames, frame_count FROM trial_results" >>"$dir/${tag%%-*}.rows"
}
for r in $(seq 1 "$rounds"); do
  run "closed-$r"
  run "open-$r" --console-monitor 1
done
summary() {  # median of trial medians, median of trial p95s, late frames / frames
  sort -n -k1,1 "$1" | awk '{m[NR]=$1} END {printf "%.2f ", (NR%2 ? m[(NR+1)/2] : (m[NR/2]+m[NR/2+1])/2)}'
  sort -n -k2,2 "$1" | awk '{m[NR]=$2} END {printf "%.2f ", (NR%2 ? m[(NR+1)/2] : (m[NR/2]+m[NR/2+1])/2)}'
  awk '{l+=$3; f+=$4} END {printf "%.3f\n", l/f}' "$1"
}
read -r cm cp cl <<<"$(summary "$dir/closed.rows")"
read -r om op ol <<<"$(summary "$dir/open.rows")"
printf '%-28s %14s %14s %12s\n' "layout ($rounds rounds x 8 trials)" "median ms" "p95 ms" "late share"
printf '%-28s %14s %14s %12s\n' "no console window" "$cm" "$cp" "$cl"
printf '%-28s %14s %14s %12s\n' "console window open" "$om" "$op" "$ol"
awk -v a="$om" -v b="$cm" -v c="$op" -v d="$cp" 'BEGIN {printf "%-28s %14.3f %14.3f\n", "ratio open / closed", a/b, c/d}'
