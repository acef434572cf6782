// VTK renders charts through OpenGL on an X display, even offscreen; without one it crashes. So a
// figure command checks for a display first, and without one runs itself again under xvfb-run
// (a virtual X server; Debian packages xvfb and xauth), or fails with one clear line.
#pragma once

namespace msislab::plot {

/// Opens the X display named by $DISPLAY (an Xlib Display*, opaque here), retrying for up to
/// 10 s while the connection fails transiently (EAGAIN: the server's queue of pending connections
/// is full; ECONNRESET: dropped during the handshake), as Xvfb does now and then on a loaded
/// machine; VTK would abort on such a failure. nullptr when there is no display. Close it with
/// close_x_display.
void* open_x_display();
void close_x_display(void* display);

/// True when $DISPLAY is set and an X connection to it opens.
bool x_display_available();

/// Replaces this process by `xvfb-run -a <this executable> argv[1..]` (same arguments, stdout,
/// stderr and exit status), with MSISLAB_UNDER_XVFB=1 set so that the child cannot loop. Throws
/// io::InputError when that is impossible: no xvfb-run or xauth on the PATH, or already the child.
[[noreturn]] void rerun_under_xvfb(int argc, char** argv);

}  // namespace msislab::plot
