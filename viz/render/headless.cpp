// Headless rendering: OSMesa context + vtkGenericOpenGLRenderWindow, and the frame/particle/plot
// pictures drawn with it. How and why: /work/shared/reference/headless-vtk.md and
// viz/CMakeLists.txt (link order, glXGetProcAddress shim).
#include "viz/render/headless.hpp"

#include <vtkActor.h>
#include <vtkAxis.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkChart.h>
#include <vtkChartXY.h>
#include <vtkCommand.h>
#include <vtkContextActor.h>
#include <vtkContextScene.h>
#include <vtkCoordinate.h>
#include <vtkCubeSource.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkGlyph3DMapper.h>
#include <vtkImageData.h>
#include <vtkJPEGReader.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGReader.h>
#include <vtkPNGWriter.h>
#include <vtkPlaneSource.h>
#include <vtkPlot.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkTexture.h>
#include <vtkUnsignedCharArray.h>

// After the VTK headers: osmesa.h brings in GL/gl.h (VTK's GLEW header must not follow it).
#include <GL/osmesa.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>
#include <utility>

// Defined by viz/render/glx_shim.cpp, which cleave_viz_executable() compiles into the program.
extern "C" const int cleave_viz_gl_shim __attribute__((weak));

namespace cleave::viz {

namespace {

std::string quoted(const std::filesystem::path& p) { return "'" + p.string() + "'"; }

void check_image(const Image& image, const char* what) {
  if (image.width < 0 || image.height < 0 ||
      image.rgb.size() != static_cast<size_t>(image.width) * static_cast<size_t>(image.height) * 3)
    throw std::invalid_argument(std::string(what) + ": image of " + std::to_string(image.width) + "x" +
                                std::to_string(image.height) + " pixels holds " +
                                std::to_string(image.rgb.size()) + " bytes, not 3 per pixel");
}

// Image (top row first) -> vtkImageData (row 0 at the bottom), 3 unsigned chars per point.
vtkSmartPointer<vtkImageData> to_vtk(const Image& image) {
  auto data = vtkSmartPointer<vtkImageData>::New();
  data->SetDimensions(image.width, image.height, 1);
  data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* dst = static_cast<uint8_t*>(data->GetScalarPointer());
  const size_t row = static_cast<size_t>(image.width) * 3;
  for (int j = 0; j < image.height; ++j)
    std::memcpy(dst + row * j, image.rgb.data() + row * (image.height - 1 - j), row);
  return data;
}

double luminance(const std::array<double, 3>& c) { return 0.299 * c[0] + 0.587 * c[1] + 0.114 * c[2]; }

std::array<double, 3> text_colour_on(const std::array<double, 3>& background) {
  return luminance(background) > 0.5 ? std::array<double, 3>{0.05, 0.05, 0.05}
                                      : std::array<double, 3>{0.95, 0.95, 0.95};
}

std::string format_label(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

// Pixel layout shared by the 2D frame and the 3D view: bands for title and colour bar.
struct Layout {
  int width = 0, height = 0;
  int margin = 0;
  int title_font = 0, label_font = 0;
  int title_band = 0;  // pixels at the top
  int cbar_band = 0;   // pixels at the right
  int bar_width = 0, label_width = 0, cbar_title_width = 0;
};

Layout make_layout(int width, int height, bool title_band, const ColorBar& cb) {
  Layout l;
  l.width = width;
  l.height = height;
  const int small = std::min(width, height);
  l.margin = std::max(4, static_cast<int>(std::lround(0.02 * small)));
  l.title_font = std::clamp(static_cast<int>(std::lround(0.04 * height)), 10, 72);
  l.label_font = std::max(9, static_cast<int>(std::lround(0.62 * l.title_font)));
  l.title_band = title_band ? static_cast<int>(std::lround(1.8 * l.title_font)) : 0;
  if (cb.show) {
    l.bar_width = std::max(8, static_cast<int>(std::lround(0.035 * height)));
    size_t chars = std::max(format_label(cb.min).size(), format_label(cb.max).size());
    if (cb.log) chars = std::max<size_t>(chars, 6);
    chars = std::max<size_t>(chars, 4);
    l.label_width = static_cast<int>(std::lround((chars + 1) * 0.62 * l.label_font)) + 4;
    l.cbar_title_width = cb.title.empty() ? 0 : static_cast<int>(std::lround(1.6 * l.label_font));
    l.cbar_band = 2 * l.margin + l.bar_width + l.label_width + l.cbar_title_width;
  }
  return l;
}

vtkSmartPointer<vtkLookupTable> make_lookup_table(const ColorBar& cb) {
  auto lut = vtkSmartPointer<vtkLookupTable>::New();
  double lo = cb.min, hi = cb.max;
  if (cb.log) {
    if (hi <= 0) hi = 1;
    if (lo <= 0 || lo >= hi) lo = hi * 1e-6;
  } else if (!(hi > lo)) {
    hi = lo + (lo == 0 ? 1 : std::abs(lo) * 1e-6);
  }
  if (cb.table.empty()) {
    lut->SetNumberOfTableValues(256);
    lut->SetHueRange(0.667, 0.0);
    lut->SetRange(lo, hi);
    if (cb.log) lut->SetScaleToLog10();
    lut->Build();
  } else {
    const auto n = static_cast<vtkIdType>(std::max<size_t>(cb.table.size(), 1));
    lut->SetNumberOfTableValues(n);
    for (vtkIdType i = 0; i < n; ++i) {
      const auto& c = cb.table[std::min<size_t>(static_cast<size_t>(i), cb.table.size() - 1)];
      lut->SetTableValue(i, c[0] / 255.0, c[1] / 255.0, c[2] / 255.0, 1.0);
    }
    lut->SetRange(lo, hi);
    if (cb.log) lut->SetScaleToLog10();
  }
  return lut;
}

// Adds renderers to the context's window for one picture and takes them out again afterwards, with
// the context current, so their GL resources are freed in the right context.
class Scene {
 public:
  explicit Scene(HeadlessContext& context) : context_(context) { context_.make_current(); }
  ~Scene() {
    context_.make_current();
    for (auto& r : renderers_) context_.window()->RemoveRenderer(r);
  }
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // layer 0 renderers clear their viewport to the background; layer 1 draws over everything.
  vtkRenderer* add(int layer, const std::array<double, 3>& background) {
    auto r = vtkSmartPointer<vtkRenderer>::New();
    r->SetBackground(background[0], background[1], background[2]);
    r->SetLayer(layer);
    if (layer > 0) r->PreserveColorBufferOn();
    r->InteractiveOff();
    if (context_.window()->GetNumberOfLayers() < layer + 1) context_.window()->SetNumberOfLayers(layer + 1);
    context_.window()->AddRenderer(r);
    renderers_.push_back(r);
    return r;
  }

 private:
  HeadlessContext& context_;
  std::vector<vtkSmartPointer<vtkRenderer>> renderers_;
};

void configure_text(vtkTextProperty* p, int size, const std::array<double, 3>& colour) {
  p->SetFontFamilyToArial();
  p->SetFontSize(size);
  p->SetColor(colour[0], colour[1], colour[2]);
  p->SetBold(false);
  p->SetItalic(false);
  p->SetShadow(false);
}

// Title (centred) and time stamp (right) in the top band, colour bar in the right band, all in the
// full-window overlay renderer `ren`.
void add_annotations(vtkRenderer* ren, const Layout& l, const std::string& title, const std::string& time_stamp,
                     const ColorBar& cb, const std::array<double, 3>& background) {
  const auto fg = text_colour_on(background);
  const double band_mid = l.height - 0.5 * l.title_band;
  if (!title.empty()) {
    vtkNew<vtkTextActor> t;
    t->SetInput(title.c_str());
    configure_text(t->GetTextProperty(), l.title_font, fg);
    t->GetTextProperty()->SetJustificationToCentered();
    t->GetTextProperty()->SetVerticalJustificationToCentered();
    t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    t->SetPosition(0.5 * l.width, band_mid);
    ren->AddActor2D(t);
  }
  if (!time_stamp.empty()) {
    vtkNew<vtkTextActor> t;
    t->SetInput(time_stamp.c_str());
    configure_text(t->GetTextProperty(), std::max(9, static_cast<int>(std::lround(0.8 * l.title_font))), fg);
    t->GetTextProperty()->SetJustificationToRight();
    t->GetTextProperty()->SetVerticalJustificationToCentered();
    t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    t->SetPosition(l.width - l.margin, band_mid);
    ren->AddActor2D(t);
  }
  if (cb.show) {
    // Bar and tick labels in the right band, from just above the bottom margin to just below the
    // title band (half a label of room at both ends for the end labels).
    const double bottom = l.margin + 0.6 * l.label_font;
    const double top = l.height - l.title_band - l.margin - 0.6 * l.label_font;
    const double x = l.width - l.cbar_band + l.margin;
    const double w = l.bar_width + l.label_width;
    vtkNew<vtkScalarBarActor> bar;
    bar->SetLookupTable(make_lookup_table(cb));
    bar->SetOrientationToVertical();
    bar->SetTextPositionToSucceedScalarBar();
    bar->SetMaximumNumberOfColors(std::max<int>(256, static_cast<int>(cb.table.size())));
    bar->SetNumberOfLabels(5);
    bar->SetLabelFormat("%.3g");
    bar->UnconstrainedFontSizeOn();
    bar->SetBarRatio(l.bar_width / w);
    bar->SetTextPad(2);
    bar->DrawFrameOff();
    bar->DrawBackgroundOff();
    bar->DrawAnnotationsOff();
    bar->SetTitle(" ");
    configure_text(bar->GetLabelTextProperty(), l.label_font, fg);
    configure_text(bar->GetTitleTextProperty(), 1, fg);
    bar->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
    bar->GetPositionCoordinate()->SetValue(x, bottom);
    bar->GetPosition2Coordinate()->SetCoordinateSystemToDisplay();
    bar->GetPosition2Coordinate()->SetReferenceCoordinate(nullptr);
    bar->GetPosition2Coordinate()->SetValue(x + w, top);
    ren->AddActor2D(bar);
    if (!cb.title.empty()) {
      vtkNew<vtkTextActor> t;
      t->SetInput(cb.title.c_str());
      configure_text(t->GetTextProperty(), l.label_font, fg);
      t->GetTextProperty()->SetJustificationToCentered();
      t->GetTextProperty()->SetVerticalJustificationToCentered();
      t->GetTextProperty()->SetOrientation(90);
      t->GetPositionCoordinate()->SetCoordinateSystemToDisplay();
      t->SetPosition(l.width - l.margin - 0.5 * l.cbar_title_width, 0.5 * (bottom + top));
      ren->AddActor2D(t);
    }
  }
}

void set_viewport_pixels(vtkRenderer* ren, int W, int H, int x, int y_bottom, int w, int h) {
  ren->SetViewport(static_cast<double>(x) / W, static_cast<double>(y_bottom) / H, static_cast<double>(x + w) / W,
                   static_cast<double>(y_bottom + h) / H);
}

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

// --- 2D frames ---------------------------------------------------------------------------------

namespace {
bool has_title_band(const std::string& title, const std::string& time_stamp) {
  return !title.empty() || !time_stamp.empty();
}
}  // namespace

PixelRect frame_2d_field_viewport(int width, int height, const Frame2D& f) {
  if (!(f.x1 > f.x0) || !(f.y1 > f.y0))
    throw std::invalid_argument("Frame2D: empty model window [" + std::to_string(f.x0) + ", " + std::to_string(f.x1) +
                                "] x [" + std::to_string(f.y0) + ", " + std::to_string(f.y1) + "]");
  const Layout l = make_layout(width, height, has_title_band(f.title, f.time_stamp), f.colorbar);
  const int ax = l.margin, ay = l.title_band + l.margin;
  const int aw = std::max(1, width - l.cbar_band - 2 * l.margin);
  const int ah = std::max(1, height - l.title_band - 2 * l.margin);
  const double aspect = (f.x1 - f.x0) / (f.y1 - f.y0);
  double w = aw, h = aw / aspect;
  if (h > ah) {
    h = ah;
    w = ah * aspect;
  }
  PixelRect r;
  r.width = std::max(1, static_cast<int>(std::lround(w)));
  r.height = std::max(1, static_cast<int>(std::lround(h)));
  r.x = ax + (aw - r.width) / 2;
  r.y = ay + (ah - r.height) / 2;
  return r;
}

Image render_frame_2d(HeadlessContext& context, const Frame2D& f) {
  if (!f.field.rgb.empty() || f.field.width != 0 || f.field.height != 0) check_image(f.field, "Frame2D field");
  const int W = context.width(), H = context.height();
  const PixelRect vp = frame_2d_field_viewport(W, H, f);
  const Layout l = make_layout(W, H, has_title_band(f.title, f.time_stamp), f.colorbar);

  Scene scene(context);
  scene.add(0, f.background);  // clears the whole window
  vtkRenderer* field = scene.add(0, f.background);
  set_viewport_pixels(field, W, H, vp.x, H - vp.y - vp.height, vp.width, vp.height);
  vtkRenderer* annotations = scene.add(1, f.background);

  const double extent = std::max(f.x1 - f.x0, f.y1 - f.y0);
  if (f.field.width > 0 && f.field.height > 0) {
    vtkNew<vtkPlaneSource> plane;
    plane->SetOrigin(f.x0, f.y0, 0);
    plane->SetPoint1(f.x1, f.y0, 0);
    plane->SetPoint2(f.x0, f.y1, 0);
    vtkNew<vtkTexture> texture;
    texture->SetInputData(to_vtk(f.field));
    texture->InterpolateOff();
    texture->RepeatOff();
    texture->EdgeClampOn();
    texture->MipmapOff();
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(plane->GetOutputPort());
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->SetTexture(texture);
    actor->GetProperty()->LightingOff();
    actor->GetProperty()->SetColor(1, 1, 1);
    actor->GetProperty()->SetAmbient(0);
    actor->GetProperty()->SetDiffuse(1);
    field->AddActor(actor);
  }

  // Overlays: one actor per (colour, width).
  std::map<std::tuple<double, double, double, double>, vtkSmartPointer<vtkPolyData>> groups;
  const double dz = 1e-3 * extent;
  for (const auto& line : f.overlays) {
    if (line.points.size() < 2) continue;
    auto key = std::make_tuple(line.colour[0], line.colour[1], line.colour[2], line.width);
    auto& pd = groups[key];
    if (!pd) {
      pd = vtkSmartPointer<vtkPolyData>::New();
      pd->SetPoints(vtkSmartPointer<vtkPoints>::New());
      pd->SetLines(vtkSmartPointer<vtkCellArray>::New());
    }
    vtkPoints* pts = pd->GetPoints();
    vtkCellArray* cells = pd->GetLines();
    cells->InsertNextCell(static_cast<vtkIdType>(line.points.size()));
    for (const auto& p : line.points) cells->InsertCellPoint(pts->InsertNextPoint(p[0], p[1], dz));
  }
  for (const auto& [key, pd] : groups) {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(pd);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    auto* prop = actor->GetProperty();
    prop->LightingOff();
    prop->SetColor(std::get<0>(key), std::get<1>(key), std::get<2>(key));
    prop->SetAmbient(0);
    prop->SetDiffuse(1);
    prop->SetLineWidth(static_cast<float>(std::get<3>(key)));
    field->AddActor(actor);
  }

  vtkCamera* cam = field->GetActiveCamera();
  cam->ParallelProjectionOn();
  const double cx = 0.5 * (f.x0 + f.x1), cy = 0.5 * (f.y0 + f.y1);
  cam->SetFocalPoint(cx, cy, 0);
  cam->SetPosition(cx, cy, 10 * extent);
  cam->SetViewUp(0, 1, 0);
  cam->SetParallelScale(0.5 * (f.y1 - f.y0));
  cam->SetClippingRange(5 * extent, 15 * extent);

  add_annotations(annotations, l, f.title, f.time_stamp, f.colorbar, f.background);
  return context.capture();
}

// --- 3D particles ------------------------------------------------------------------------------

Image render_particles_3d(HeadlessContext& context, const std::vector<std::array<double, 3>>& centres,
                          const std::vector<double>& edge, const std::vector<std::array<uint8_t, 3>>& colours,
                          const Camera3D& camera, const std::string& title, const std::string& time_stamp,
                          const ColorBar& colorbar, std::array<double, 3> background,
                          const std::vector<std::array<std::array<double, 3>, 3>>& crack_triangles) {
  if (edge.size() != centres.size() || colours.size() != centres.size())
    throw std::invalid_argument("render_particles_3d: " + std::to_string(centres.size()) + " centres, " +
                                std::to_string(edge.size()) + " edges, " + std::to_string(colours.size()) +
                                " colours");
  const std::string& preset = camera.preset;
  if (!camera.explicit_view && preset != "iso" && preset != "xy" && preset != "xz" && preset != "yz")
    throw std::invalid_argument("render_particles_3d: unknown camera preset '" + preset +
                                "' (iso, xy, xz, yz or an explicit view)");
  const int W = context.width(), H = context.height();
  const Layout l = make_layout(W, H, has_title_band(title, time_stamp), colorbar);

  Scene scene(context);
  scene.add(0, background);
  vtkRenderer* view = scene.add(0, background);
  set_viewport_pixels(view, W, H, 0, 0, std::max(1, W - l.cbar_band), std::max(1, H - l.title_band));
  vtkRenderer* annotations = scene.add(1, background);

  if (!centres.empty()) {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(static_cast<vtkIdType>(centres.size()));
    vtkNew<vtkDoubleArray> size;
    size->SetName("edge");
    size->SetNumberOfTuples(static_cast<vtkIdType>(centres.size()));
    vtkNew<vtkUnsignedCharArray> rgb;
    rgb->SetName("rgb");
    rgb->SetNumberOfComponents(3);
    rgb->SetNumberOfTuples(static_cast<vtkIdType>(centres.size()));
    for (size_t i = 0; i < centres.size(); ++i) {
      const auto id = static_cast<vtkIdType>(i);
      points->SetPoint(id, centres[i][0], centres[i][1], centres[i][2]);
      size->SetValue(id, edge[i]);
      for (int c = 0; c < 3; ++c) rgb->SetValue(3 * id + c, colours[i][c]);
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(points);
    pd->GetPointData()->AddArray(size);
    pd->GetPointData()->SetScalars(rgb);

    vtkNew<vtkCubeSource> cube;
    cube->SetXLength(1);
    cube->SetYLength(1);
    cube->SetZLength(1);
    vtkNew<vtkGlyph3DMapper> mapper;
    mapper->SetInputData(pd);
    mapper->SetSourceConnection(cube->GetOutputPort());
    mapper->SetScaleArray("edge");
    mapper->SetScaleModeToScaleByMagnitude();
    mapper->ScalingOn();
    mapper->OrientOff();
    mapper->ScalarVisibilityOn();
    mapper->SetScalarModeToUsePointData();
    mapper->SetColorModeToDirectScalars();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    // ambient + diffuse = 1: a face square to the headlight shows its colour exactly.
    actor->GetProperty()->SetAmbient(0.15);
    actor->GetProperty()->SetDiffuse(0.85);
    actor->GetProperty()->SetSpecular(0);
    view->AddActor(actor);
  }

  if (!crack_triangles.empty()) {
    vtkRenderer* cracks = scene.add(1, background);
    set_viewport_pixels(cracks, W, H, 0, 0, std::max(1, W - l.cbar_band), std::max(1, H - l.title_band));
    cracks->SetActiveCamera(view->GetActiveCamera());
    vtkNew<vtkPoints> pts;
    vtkNew<vtkCellArray> tris;
    for (const auto& t : crack_triangles) {
      tris->InsertNextCell(3);
      for (const auto& p : t) tris->InsertCellPoint(pts->InsertNextPoint(p[0], p[1], p[2]));
    }
    vtkNew<vtkPolyData> pd;
    pd->SetPoints(pts);
    pd->SetPolys(tris);
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(pd);
    mapper->ScalarVisibilityOff();
    vtkNew<vtkActor> actor;
    actor->SetMapper(mapper);
    actor->GetProperty()->SetColor(0.9, 0.1, 0.1);
    actor->GetProperty()->LightingOff();
    cracks->AddActor(actor);
  }

  vtkCamera* cam = view->GetActiveCamera();
  if (camera.explicit_view) {
    const auto& v = *camera.explicit_view;
    cam->ParallelProjectionOff();
    cam->SetPosition(v[0], v[1], v[2]);
    cam->SetFocalPoint(v[3], v[4], v[5]);
    cam->SetViewUp(v[6], v[7], v[8]);
    view->ResetCameraClippingRange();
  } else {
    double b[6] = {-0.5, 0.5, -0.5, 0.5, -0.5, 0.5};
    if (!centres.empty()) {
      b[0] = b[2] = b[4] = std::numeric_limits<double>::max();
      b[1] = b[3] = b[5] = std::numeric_limits<double>::lowest();
      for (size_t i = 0; i < centres.size(); ++i)
        for (int a = 0; a < 3; ++a) {
          b[2 * a] = std::min(b[2 * a], centres[i][a] - 0.5 * std::abs(edge[i]));
          b[2 * a + 1] = std::max(b[2 * a + 1], centres[i][a] + 0.5 * std::abs(edge[i]));
        }
    }
    const double c[3] = {0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5])};
    // "iso": azimuth 50 degrees from +x towards +y, elevation 30 degrees; not the symmetric
    // (1,1,1), under which the headlight shades the three visible faces of a cube alike.
    constexpr double az = 50 * 3.14159265358979 / 180, el = 30 * 3.14159265358979 / 180;
    double dir[3] = {std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el)}, up[3] = {0, 0, 1};
    if (preset == "xy") {
      dir[0] = 0, dir[1] = 0, dir[2] = 1;
      up[0] = 0, up[1] = 1, up[2] = 0;
    } else if (preset == "xz") {
      dir[0] = 0, dir[1] = -1, dir[2] = 0;
    } else if (preset == "yz") {
      dir[0] = 1, dir[1] = 0, dir[2] = 0;
    }
    cam->SetParallelProjection(preset != "iso");
    cam->SetFocalPoint(c[0], c[1], c[2]);
    cam->SetPosition(c[0] + dir[0], c[1] + dir[1], c[2] + dir[2]);
    cam->SetViewUp(up);
    view->ResetCamera(b);
    if (preset != "iso") {
      // ResetCamera fits the bounding sphere; fit the box's projection instead (tighter).
      const int ax_h = preset == "xy" ? 0 : (preset == "xz" ? 0 : 1);  // horizontal axis
      const int ax_v = preset == "xy" ? 1 : 2;                          // vertical axis
      const double hw = 0.5 * (b[2 * ax_h + 1] - b[2 * ax_h]), hh = 0.5 * (b[2 * ax_v + 1] - b[2 * ax_v]);
      const double vw = std::max(1, W - l.cbar_band), vh = std::max(1, H - l.title_band);
      const double scale = 1.08 * std::max(hh, hw * vh / vw);
      if (scale > 0) cam->SetParallelScale(scale);
    }
    view->ResetCameraClippingRange(b);
  }

  add_annotations(annotations, l, title, time_stamp, colorbar, background);
  return context.capture();
}

// --- plots -------------------------------------------------------------------------------------

Image render_plot(HeadlessContext& context, const std::vector<PlotSeries>& series, const std::string& title,
                  const std::string& xlabel, const std::string& ylabel) {
  for (const auto& s : series)
    if (s.x.size() != s.y.size())
      throw std::invalid_argument("render_plot: series '" + s.name + "' has " + std::to_string(s.x.size()) +
                                  " x and " + std::to_string(s.y.size()) + " y values");
  static constexpr std::array<std::array<unsigned char, 3>, 10> palette{{{31, 119, 180},
                                                                          {214, 39, 40},
                                                                          {44, 160, 44},
                                                                          {255, 127, 14},
                                                                          {148, 103, 189},
                                                                          {140, 86, 75},
                                                                          {227, 119, 194},
                                                                          {127, 127, 127},
                                                                          {188, 189, 34},
                                                                          {23, 190, 207}}};
  const int H = context.height();
  const int title_font = std::clamp(static_cast<int>(std::lround(0.04 * H)), 10, 72);
  const int label_font = std::max(9, static_cast<int>(std::lround(0.7 * title_font)));
  const std::array<double, 3> white{1, 1, 1};

  Scene scene(context);
  vtkRenderer* ren = scene.add(0, white);

  vtkNew<vtkChartXY> chart;
  chart->SetTitle(title);
  configure_text(chart->GetTitleProperties(), title_font, {0, 0, 0});
  for (int a : {vtkAxis::BOTTOM, vtkAxis::LEFT}) {
    vtkAxis* axis = chart->GetAxis(a);
    axis->SetTitle(a == vtkAxis::BOTTOM ? xlabel : ylabel);
    configure_text(axis->GetTitleProperties(), label_font, {0, 0, 0});
    configure_text(axis->GetLabelProperties(), std::max(8, label_font - 2), {0, 0, 0});
    if (a == vtkAxis::LEFT) axis->GetTitleProperties()->SetOrientation(90);
    axis->GetTitleProperties()->SetBold(true);
  }
  bool named = false;
  std::vector<vtkSmartPointer<vtkTable>> tables;
  for (size_t k = 0; k < series.size(); ++k) {
    const auto& s = series[k];
    named = named || !s.name.empty();
    vtkNew<vtkDoubleArray> x, y;
    x->SetName("x");
    y->SetName(s.name.empty() ? ("series " + std::to_string(k + 1)).c_str() : s.name.c_str());
    x->SetNumberOfTuples(static_cast<vtkIdType>(s.x.size()));
    y->SetNumberOfTuples(static_cast<vtkIdType>(s.y.size()));
    for (size_t i = 0; i < s.x.size(); ++i) {
      x->SetValue(static_cast<vtkIdType>(i), s.x[i]);
      y->SetValue(static_cast<vtkIdType>(i), s.y[i]);
    }
    auto table = vtkSmartPointer<vtkTable>::New();
    table->AddColumn(x);
    table->AddColumn(y);
    tables.push_back(table);
    vtkPlot* plot = chart->AddPlot(vtkChart::LINE);
    plot->SetInputData(table, 0, 1);
    const auto& c = palette[k % palette.size()];
    plot->SetColor(c[0], c[1], c[2], 255);
    plot->SetWidth(2.0);
    if (!s.name.empty()) plot->SetLabel(s.name);
  }
  chart->SetShowLegend(named);

  vtkNew<vtkContextScene> context_scene;
  context_scene->AddItem(chart);
  vtkNew<vtkContextActor> actor;
  actor->SetScene(context_scene);
  ren->AddActor(actor);
  context_scene->SetRenderer(ren);
  return context.capture();
}

}  // namespace cleave::viz
