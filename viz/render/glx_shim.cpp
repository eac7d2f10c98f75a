// GL entry points for a program that renders through OSMesa with Debian's X-only VTK (no X server).
//
// Debian's VTK 9.1 uses the system GLEW, built for GLX. glewInit() looks every GL function up
// through glXGetProcAddressARB (libGLX, which knows nothing without an X display) and then
// initialises GLX extensions, which needs an X display. These definitions, compiled into the
// executable and exported (ENABLE_EXPORTS), take the place of libGLX's and libGLEW's for the whole
// process:
//  - glXGetProcAddress[ARB] answer with OSMesa's functions, so GLEW's function pointers are Mesa's;
//    GLX functions themselves are reported missing (there is no GLX here);
//  - glewInit() runs GLEW's own, then treats "GLX 1.2 not supported" / "no GLX display" as success:
//    both are returned only after every GL function pointer has been loaded, and VTK's generic
//    window never uses GLX. (Left as failure, VTK logs "GLEW could not be initialized" and retries
//    at every render.)
// Compiled into each executable by cleave_viz_executable() (viz/CMakeLists.txt), never into the
// static library, where the linker would drop it. OSMesa must precede VTK on the link line so
// that the GL 1.x symbols VTK and GLEW call directly resolve to OSMesa's library too.
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <cstring>

extern "C" {

// Marker: HeadlessContext refuses to start (with a message that says why) in a program without it.
__attribute__((visibility("default"))) extern const int cleave_viz_gl_shim;
const int cleave_viz_gl_shim = 1;

using CleaveGlProc = void (*)();

__attribute__((visibility("default"))) CleaveGlProc glXGetProcAddressARB(const unsigned char* name) {
  const char* n = reinterpret_cast<const char*>(name);
  if (!n || std::strncmp(n, "glX", 3) == 0) return nullptr;
  return reinterpret_cast<CleaveGlProc>(OSMesaGetProcAddress(n));
}

__attribute__((visibility("default"))) CleaveGlProc glXGetProcAddress(const unsigned char* name) {
  return glXGetProcAddressARB(name);
}

__attribute__((visibility("default"))) GLenum glewInit() {
  constexpr GLenum kGlxVersion11Only = 3;  // GLEW_ERROR_GLX_VERSION_11_ONLY
  constexpr GLenum kNoGlxDisplay = 4;      // GLEW_ERROR_NO_GLX_DISPLAY
  using Init = GLenum (*)();
  static const Init real = reinterpret_cast<Init>(dlsym(RTLD_NEXT, "glewInit"));
  if (!real) return 1;  // GLEW_ERROR_NO_GL_VERSION
  const GLenum result = real();
  return result == kGlxVersion11Only || result == kNoGlxDisplay ? 0 : result;
}

}  // extern "C"
