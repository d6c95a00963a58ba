#!/usr/bin/env bash
# Runs a command on an X server with two monitors, side by side, each
# 1280 x 1024: Xorg with the dummy video driver (Xvfb has one RandR output,
# so GLFW sees one monitor whatever -screen or +xinerama says; the dummy
# driver has 16 outputs and xrandr switches the second one on). The server
# listens on a Unix socket only, under a display number no other server
# uses, and is stopped when the command ends. Exit status: the command's;
# 77 (ctest's "skipped") with the reason when Xorg, the dummy driver or
# xrandr is missing or the server does not start (Debian packages
# xserver-xorg-core, xserver-xorg-video-dummy, x11-xserver-utils).
set -uo pipefail
[ $# -ge 1 ] || { echo "usage: $0 COMMAND [ARG...]" >&2; exit 2; }
skip() { echo "two_monitors.sh: skipped: $*" >&2; exit 77; }
xorg=$(command -v Xorg || true)
[ -n "$xorg" ] || skip "Xorg is not installed (xserver-xorg-core)"
ls /usr/lib/xorg/modules/drivers/dummy_drv.so >/dev/null 2>&1 || skip "the dummy video driver is not installed (xserver-xorg-video-dummy)"
command -v xrandr >/dev/null || skip "xrandr is not installed (x11-xserver-utils)"

dir=$(mktemp -d "${TMPDIR:-/tmp}/dtlab-two-monitors.XXXXXX")
display=""
pid=""
cleanup() {
  [ -n "$pid" ] && kill "$pid" 2>/dev/null && wait "$pid" 2>/dev/null
  rm -rf "$dir"
}
trap cleanup EXIT
mkdir "$dir/conf.d"
cat > "$dir/xorg.conf" <<'CONF'
Section "ServerFlags"
  Option "AutoAddDevices" "false"
  Option "AutoAddGPU" "false"
  Option "DontVTSwitch" "true"
EndSection
Section "Device"
  Identifier "dummy"
  Driver "dummy"
  VideoRam 65536
EndSection
Section "Monitor"
  Identifier "monitor"
  HorizSync 5.0 - 1000.0
  VertRefresh 5.0 - 200.0
  Modeline "1280x1024" 108.00 1280 1328 1440 1688 1024 1025 1028 1066 +hsync +vsync
EndSection
Section "Screen"
  Identifier "screen"
  Device "dummy"
  Monitor "monitor"
  DefaultDepth 24
  SubSection "Display"
    Depth 24
    Modes "1280x1024"
    Virtual 2560 1024
  EndSubSection
EndSection
CONF

# A display number no server holds (its lock file and socket are free), as xvfb-run -a picks one.
for n in $(seq 120 220); do
  [ -e "/tmp/.X$n-lock" ] || [ -e "/tmp/.X11-unix/X$n" ] || { display=":$n"; break; }
done
[ -n "$display" ] || skip "no free X display number in 120..220"
"$xorg" "$display" -config "$dir/xorg.conf" -configdir "$dir/conf.d" -noreset -nolisten tcp \
  -logfile "$dir/xorg.log" >"$dir/xorg.out" 2>&1 &
pid=$!
for _ in $(seq 1 100); do
  [ -e "/tmp/.X11-unix/X${display#:}" ] && DISPLAY=$display xrandr >/dev/null 2>&1 && break
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
DISPLAY=$display xrandr >/dev/null 2>&1 || skip "Xorg with the dummy driver did not start: $(tail -n 3 "$dir/xorg.out" "$dir/xorg.log" 2>/dev/null | tr '\n' ' ')"
# The second output: its mode, then on, right of the first; a full query makes the server probe the
# outputs again, so clients see it as connected.
DISPLAY=$display xrandr --addmode DUMMY1 1280x1024 &&
  DISPLAY=$display xrandr --output DUMMY1 --mode 1280x1024 --right-of DUMMY0 &&
  DISPLAY=$display xrandr >/dev/null || skip "xrandr could not switch on the second monitor"
DISPLAY=$display "$@"
