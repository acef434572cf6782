// VTK renders charts through OpenGL on an X display, even offscreen; without one it crashes. So a
// figure command checks for a display first, and without one runs itself again under xvfb-run
// (a virtual X server; Debian packages xvfb and xauth), or fails with one clear line.
#pragma once

namespace msislab::plot {

/// True when $DISPLAY is set and an X connection to it opens.
bool x_display_available();

/// Replaces this process by `xvfb-run -a <this executable> argv[1..]` (same arguments, stdout,
/// stderr and exit status), with MSISLAB_UNDER_XVFB=1 set so that the child cannot loop. Throws
/// io::InputError when that is impossible: no xvfb-run or xauth on the PATH, or already the child.
[[noreturn]] void rerun_under_xvfb(int argc, char** argv);

}  // namespace msislab::plot
