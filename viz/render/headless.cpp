// Headless rendering: the OSMesa context driving a vtkGenericOpenGLRenderWindow, and PNG/JPEG files.
// How and why: /work/shared/reference/headless-vtk.md and viz/CMakeLists.txt (link order,
// glXGetProcAddress shim). The pictures drawn with it: frame2d.cpp, particles3d.cpp, plot.cpp.
#include "viz/render/headless.hpp"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkImageData.h>
#include <vtkImageReader2.h>
#include <vtkJPEGReader.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

// After the VTK headers: osmesa.h brings in GL/gl.h (VTK's GLEW header must not follow it).
#include <GL/osmesa.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <stdexcept>

#include "viz/render/drawing.hpp"

// Defined by viz/render/glx_shim.cpp, which cleave_viz_executable() compiles into the program.
extern "C" const int cleave_viz_gl_shim __attribute__((weak));

namespace cleave::viz {

using detail::check_image;
using detail::to_vtk;

namespace {
std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }
}  // namespace

// --- files -------------------------------------------------------------------------------------

void write_png(const std::filesystem::path& file, const Image& image) {
  check_image(image, "write_png");
  if (image.width == 0 || image.height == 0)
    throw std::invalid_argument("write_png: empty image for " + quoted(file));
  auto data = to_vtk(image);
  vtkNew<vtkPNGWriter> writer;
  writer->SetFileName(file.string().c_str());
  writer->SetInputData(data);
  writer->Write();
  if (writer->GetErrorCode() != vtkErrorCode::NoError)
    throw std::runtime_error("cannot write PNG " + quoted(file) + ": " +
                             vtkErrorCode::GetStringFromErrorCode(writer->GetErrorCode()));
}

Image read_image(const std::filesystem::path& file) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec))
    throw std::runtime_error("cannot read image " + quoted(file) + ": no such file");
  std::string ext = file.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
  vtkSmartPointer<vtkImageReader2> reader;
  if (ext == ".png")
    reader = vtkSmartPointer<vtkPNGReader>::New();
  else if (ext == ".jpg" || ext == ".jpeg")
    reader = vtkSmartPointer<vtkJPEGReader>::New();
  else
    throw std::runtime_error("cannot read image " + quoted(file) + ": not .png, .jpg or .jpeg");
  const std::string name = file.string();
  if (!reader->CanReadFile(name.c_str()))
    throw std::runtime_error("cannot read image " + quoted(file) + ": not a valid " + ext.substr(1) + " file");
  reader->SetFileName(name.c_str());
  reader->Update();
  if (reader->GetErrorCode() != vtkErrorCode::NoError)
    throw std::runtime_error("cannot read image " + quoted(file) + ": " +
                             vtkErrorCode::GetStringFromErrorCode(reader->GetErrorCode()));
  vtkImageData* data = reader->GetOutput();
  vtkDataArray* scalars = data ? data->GetPointData()->GetScalars() : nullptr;
  int dims[3] = {0, 0, 0};
  if (data) data->GetDimensions(dims);
  if (!scalars || dims[0] <= 0 || dims[1] <= 0)
    throw std::runtime_error("cannot read image " + quoted(file) + ": no pixels");
  const int nc = scalars->GetNumberOfComponents();
  const int type = scalars->GetDataType();
  if (type != VTK_UNSIGNED_CHAR && type != VTK_UNSIGNED_SHORT)
    throw std::runtime_error("cannot read image " + quoted(file) + ": unsupported sample type");
  Image out;
  out.width = dims[0];
  out.height = dims[1];
  out.rgb.resize(static_cast<size_t>(out.width) * out.height * 3);
  auto sample = [&](vtkIdType p, int c) -> uint8_t {
    if (type == VTK_UNSIGNED_CHAR) return static_cast<const uint8_t*>(scalars->GetVoidPointer(0))[p * nc + c];
    return static_cast<uint8_t>(static_cast<const uint16_t*>(scalars->GetVoidPointer(0))[p * nc + c] >> 8);
  };
  for (int j = 0; j < out.height; ++j) {
    const int src_row = out.height - 1 - j;  // VTK row 0 is the bottom
    for (int i = 0; i < out.width; ++i) {
      const vtkIdType p = static_cast<vtkIdType>(src_row) * out.width + i;
      uint8_t* d = &out.rgb[(static_cast<size_t>(j) * out.width + i) * 3];
      if (nc >= 3) {
        d[0] = sample(p, 0);
        d[1] = sample(p, 1);
        d[2] = sample(p, 2);
      } else {
        d[0] = d[1] = d[2] = sample(p, 0);
      }
    }
  }
  return out;
}

// --- context -----------------------------------------------------------------------------------

struct HeadlessContext::Impl {
  int width = 0, height = 0;
  OSMesaContext context = nullptr;
  std::vector<unsigned char> buffer;  // RGBA, what OSMesa draws the default framebuffer into
  vtkSmartPointer<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkCallbackCommand> on_make_current, on_is_current, on_supports_gl;

  bool bind() {
    return OSMesaMakeCurrent(context, buffer.data(), GL_UNSIGNED_BYTE, width, height) == GL_TRUE;
  }

  static void make_current_cb(vtkObject*, unsigned long, void* client, void*) {
    static_cast<Impl*>(client)->bind();
  }
  static void is_current_cb(vtkObject*, unsigned long, void* client, void* call) {
    *static_cast<bool*>(call) = OSMesaGetCurrentContext() == static_cast<Impl*>(client)->context;
  }
  static void supports_gl_cb(vtkObject*, unsigned long, void*, void* call) { *static_cast<int*>(call) = 1; }
};

namespace {
void check_size(int width, int height) {
  GLint max_w = 0, max_h = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_w);
  OSMesaGetIntegerv(OSMESA_MAX_HEIGHT, &max_h);
  if (width <= 0 || height <= 0 || (max_w > 0 && width > max_w) || (max_h > 0 && height > max_h))
    throw std::invalid_argument("HeadlessContext: size " + std::to_string(width) + "x" + std::to_string(height) +
                                " is not between 1x1 and " + std::to_string(max_w) + "x" + std::to_string(max_h));
}
}  // namespace

HeadlessContext::HeadlessContext(int width, int height) : impl_(std::make_unique<Impl>()) {
  if (&cleave_viz_gl_shim == nullptr)
    throw std::runtime_error(
        "HeadlessContext: this program lacks the GL shim (viz/render/glx_shim.cpp); build it with "
        "cleave_viz_executable() in CMake");
  check_size(width, height);
  auto& m = *impl_;
  m.width = width;
  m.height = height;
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         24,
                         OSMESA_STENCIL_BITS,
                         8,
                         OSMESA_ACCUM_BITS,
                         0,
                         OSMESA_PROFILE,
                         OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION,
                         3,
                         OSMESA_CONTEXT_MINOR_VERSION,
                         2,
                         0};
  m.context = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!m.context) throw std::runtime_error("HeadlessContext: OSMesa could not create a 3.2 core-profile context");
  m.buffer.assign(static_cast<size_t>(width) * height * 4, 0);
  if (!m.bind()) {
    OSMesaDestroyContext(m.context);
    throw std::runtime_error("HeadlessContext: OSMesaMakeCurrent failed");
  }
  m.window = vtkSmartPointer<vtkGenericOpenGLRenderWindow>::New();
  m.on_make_current->SetCallback(&Impl::make_current_cb);
  m.on_make_current->SetClientData(impl_.get());
  m.on_is_current->SetCallback(&Impl::is_current_cb);
  m.on_is_current->SetClientData(impl_.get());
  m.on_supports_gl->SetCallback(&Impl::supports_gl_cb);
  m.window->AddObserver(vtkCommand::WindowMakeCurrentEvent, m.on_make_current);
  m.window->AddObserver(vtkCommand::WindowIsCurrentEvent, m.on_is_current);
  m.window->AddObserver(vtkCommand::WindowSupportsOpenGLEvent, m.on_supports_gl);
  m.window->SetSize(width, height);
  m.window->SetOwnContext(0);
  m.window->SetIsCurrent(true);
  m.window->SetReadyForRendering(true);
  m.window->SetIsDirect(1);
  m.window->SetMultiSamples(0);  // exact colours; llvmpipe multisampling costs more than it shows
  m.window->SetNumberOfLayers(2);
}

HeadlessContext::~HeadlessContext() {
  if (!impl_) return;  // moved from
  auto& m = *impl_;
  if (m.window) {
    m.bind();
    m.window->Finalize();  // frees the renderers' GL resources in this context
    m.window->RemoveAllObservers();
    m.window = nullptr;  // destructor runs with this context still current
  }
  if (OSMesaGetCurrentContext() == m.context) OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
  OSMesaDestroyContext(m.context);
}

HeadlessContext::HeadlessContext(HeadlessContext&&) noexcept = default;
HeadlessContext& HeadlessContext::operator=(HeadlessContext&& other) noexcept {
  if (this != &other) {
    HeadlessContext old(std::move(*this));  // destroys the current one
    impl_ = std::move(other.impl_);
  }
  return *this;
}

int HeadlessContext::width() const { return impl_->width; }
int HeadlessContext::height() const { return impl_->height; }

void HeadlessContext::resize(int width, int height) {
  check_size(width, height);
  auto& m = *impl_;
  if (width == m.width && height == m.height) return;
  m.width = width;
  m.height = height;
  m.buffer.assign(static_cast<size_t>(width) * height * 4, 0);
  if (!m.bind()) throw std::runtime_error("HeadlessContext::resize: OSMesaMakeCurrent failed");
  m.window->SetSize(width, height);
}

void HeadlessContext::make_current() {
  if (!impl_->bind()) throw std::runtime_error("HeadlessContext: OSMesaMakeCurrent failed");
}

vtkRenderWindow* HeadlessContext::window() { return impl_->window; }

Image HeadlessContext::capture() {
  auto& m = *impl_;
  make_current();
  m.window->Render();
  vtkNew<vtkUnsignedCharArray> pixels;
  if (!m.window->GetPixelData(0, 0, m.width - 1, m.height - 1, /*front=*/0, pixels, /*right=*/0))
    throw std::runtime_error("HeadlessContext::capture: reading the pixels back failed");
  Image out;
  out.width = m.width;
  out.height = m.height;
  const size_t row = static_cast<size_t>(m.width) * 3;
  if (static_cast<size_t>(pixels->GetNumberOfValues()) != row * m.height)
    throw std::runtime_error("HeadlessContext::capture: unexpected pixel count");
  out.rgb.resize(row * m.height);
  const uint8_t* src = pixels->GetPointer(0);
  for (int j = 0; j < m.height; ++j) std::memcpy(&out.rgb[row * j], src + row * (m.height - 1 - j), row);
  return out;
}

std::string HeadlessContext::gl_info() {
  make_current();
  auto str = [](GLenum e) {
    const auto* s = reinterpret_cast<const char*>(glGetString(e));
    return std::string(s ? s : "?");
  };
  return "OpenGL vendor: " + str(GL_VENDOR) + "; renderer: " + str(GL_RENDERER) + "; version: " + str(GL_VERSION);
}

}  // namespace cleave::viz
