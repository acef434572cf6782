#include "plot/display.hpp"

#include <X11/Xlib.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "io/input_error.hpp"

namespace msislab::plot {
namespace {

constexpr const char* kGuard = "MSISLAB_UNDER_XVFB";

std::optional<std::string> find_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return std::nullopt;
  const std::string dirs(path);
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t colon = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = dirs.substr(start, colon - start);
    const std::string candidate = (dir.empty() ? "." : dir) + "/" + program;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
    start = colon + 1;
  }
  return std::nullopt;
}

}  // namespace

void* open_x_display() {
  const char* name = std::getenv("DISPLAY");
  if (name == nullptr || *name == '\0') return nullptr;
  for (int attempt = 0; attempt < 200; ++attempt) {
    errno = 0;
    Display* display = XOpenDisplay(nullptr);
    // A full queue of pending connections (EAGAIN) or one dropped during the handshake
    // (ECONNRESET) is transient; no server at all (ENOENT, ECONNREFUSED) is not.
    if (display != nullptr || (errno != EAGAIN && errno != ECONNRESET && errno != EINTR)) {
      return display;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return nullptr;
}

void close_x_display(void* display) {
  if (display != nullptr) XCloseDisplay(static_cast<Display*>(display));
}

bool x_display_available() {
  void* display = open_x_display();
  close_x_display(display);
  return display != nullptr;
}

void rerun_under_xvfb(int argc, char** argv) {
  const char* display = std::getenv("DISPLAY");
  const std::string why = display && *display
                              ? "the X display '" + std::string(display) + "' cannot be opened"
                              : "no X display ($DISPLAY is not set)";
  if (std::getenv(kGuard) != nullptr) {
    throw io::InputError(why + ", even under xvfb-run: check that Xvfb starts");
  }
  const std::optional<std::string> xvfb_run = find_on_path("xvfb-run");
  if (!xvfb_run || !find_on_path("xauth")) {
    throw io::InputError(why +
                         " and xvfb-run (with xauth) is not installed: VTK needs a display to "
                         "draw; run under `xvfb-run -a msislab ...` (Debian: apt-get install "
                         "xvfb xauth)");
  }
  std::error_code ec;
  const std::string self = std::filesystem::read_symlink("/proc/self/exe", ec).string();
  if (ec)
    throw io::InputError("cannot find this executable to run it under xvfb-run: " + ec.message());
  // `xvfb-run -a` takes the first free display from :99 on, and two started at once can both
  // take the same one (one of them then cannot open it). The first one this process tries is
  // its own, from its process id, so msislab children drawing beside one another (a Monte Carlo's
  // or a sweep's `msislab plot`, or a test suite's programs under `xvfb-run -a`) start apart
  // (-n before -a: xvfb-run searches from the number it has when it reads -a).
  const std::string first_display = std::to_string(100 + ::getpid() % 30000);
  std::vector<std::string> args = {
      *xvfb_run, "-n", first_display, "-a", "-s", "-screen 0 1920x1200x24", self};
  for (int i = 1; i < argc; ++i) args.emplace_back(argv[i]);
  std::vector<char*> c_args;
  for (std::string& a : args) c_args.push_back(a.data());
  c_args.push_back(nullptr);
  ::setenv(kGuard, "1", 1);
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  ::execv(xvfb_run->c_str(), c_args.data());
  throw io::InputError("cannot run " + *xvfb_run + ": " + std::strerror(errno));
}

}  // namespace msislab::plot
