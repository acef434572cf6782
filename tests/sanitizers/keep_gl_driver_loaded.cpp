// Sanitizer builds only (MSISLAB_SANITIZE, linked into every program that draws through
// msislab_plot): loads Mesa's software OpenGL driver at start-up and marks it never to be unloaded.
//
// Why: VTK's X window makes Mesa dlopen this driver, and Mesa dlcloses it again when the window
// goes. Two 56-byte blocks the driver allocates once are never freed, and at exit LeakSanitizer
// reports them with a return address inside a library that is no longer mapped, so no suppression
// can name it (the address is attributed to whatever is mapped there later, or to nothing). Kept
// loaded, the blocks stay reachable from the driver's globals and are not reported (Mesa 22.3.6);
// should a Mesa version drop those pointers, the report now names swrast_dri.so, which
// tests/sanitizers/lsan.supp suppresses. Nothing else changes: Mesa's own dlopen of the driver
// finds it already loaded.
#include <dlfcn.h>

namespace {

struct KeepGlDriverLoaded {
  KeepGlDriverLoaded() { dlopen(MSISLAB_GL_DRIVER, RTLD_NOW | RTLD_GLOBAL | RTLD_NODELETE); }
};
const KeepGlDriverLoaded keep_gl_driver_loaded;

}  // namespace
