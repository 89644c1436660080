# Sourced by the scripts that render (demo.sh, test.sh, sanitize.sh): sets `run` to the
# command prefix that gives them an X display, empty when DISPLAY is set.
# -noreset: by default Xvfb resets when its last client disconnects, and drops a client
# that connects meanwhile; with tests in parallel one test's window then fails to open
# ("bad X server connection", VTK aborts). 4 processes opening and closing the display
# 1200 times failed 30 times without it, 0 with it.
run=()
[ -n "${DISPLAY:-}" ] || run=(xvfb-run -a -s "-screen 0 1920x1080x24 -noreset")
