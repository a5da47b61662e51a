#include "io/cairo_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <stdexcept>

#include "io/atomic_file.hpp"

namespace topomill {

Canvas::Canvas(int w, int h)
    : surface(cairo_image_surface_create(CAIRO_FORMAT_RGB24, w, h), cairo_surface_destroy),
      cr(cairo_create(surface.get()), cairo_destroy) {
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  cairo_select_font_face(cr.get(), "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL,
                         CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr.get(), 13);
  cairo_set_source_rgb(cr.get(), 0, 0, 0);
}

void Canvas::text(double x, double y, const std::string& s, double ax, double ay,
                  bool vertical) const {
  cairo_text_extents_t e;
  cairo_text_extents(cr.get(), s.c_str(), &e);
  cairo_save(cr.get());
  cairo_translate(cr.get(), x, y);
  if (vertical) cairo_rotate(cr.get(), -M_PI / 2);
  cairo_move_to(cr.get(), -e.x_advance * ax, e.height * (1 - ay));
  cairo_show_text(cr.get(), s.c_str());
  cairo_restore(cr.get());
}

void Canvas::write(const std::string& path) const {
  cairo_surface_flush(surface.get());
  write_atomically(path, [&](std::ostream& out) {
    // cairo is C: an exception (a stop request, a full disk) waits here until it has returned.
    struct Sink {
      std::ostream& out;
      std::exception_ptr failed;
    } sink{out, nullptr};
    const auto put = [](void* closure, const unsigned char* data, unsigned int length) {
      auto* s = static_cast<Sink*>(closure);
      try {
        s->out.write(reinterpret_cast<const char*>(data), length);
        return CAIRO_STATUS_SUCCESS;
      } catch (...) {
        s->failed = std::current_exception();
        return CAIRO_STATUS_WRITE_ERROR;
      }
    };
    const cairo_status_t status = cairo_surface_write_to_png_stream(surface.get(), put, &sink);
    if (sink.failed) std::rethrow_exception(sink.failed);
    if (status != CAIRO_STATUS_SUCCESS) throw std::runtime_error("cannot write PNG '" + path + "'");
  });
}

void palette(cairo_t* cr, std::size_t i) {
  static const double c[][3] = {{0.00, 0.45, 0.70}, {0.84, 0.37, 0.00}, {0.00, 0.62, 0.45},
                                {0.80, 0.47, 0.65}, {0.90, 0.62, 0.00}, {0.34, 0.71, 0.91},
                                {0.94, 0.89, 0.26}, {0.0, 0.0, 0.0}};
  const auto& k = c[i % 8];
  cairo_set_source_rgb(cr, k[0], k[1], k[2]);
}

void viridis(double t, double rgb[3]) {
  static const double stops[][3] = {
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int k = std::min(3, static_cast<int>(t));
  const double w = t - k;
  for (int i = 0; i < 3; ++i) rgb[i] = ((1 - w) * stops[k][i] + w * stops[k + 1][i]) / 255.0;
}

std::string number(double v) {
  // Whole numbers up to a million in full (spindle speeds, node counts: 12500, not 1.25e+04).
  constexpr double kWhole = 1e6;
  char buf[32];
  if (std::abs(v) < kWhole && v == std::round(v))
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

std::vector<double> ticks(double lo, double hi, bool log, int intervals) {
  std::vector<double> out;
  if (log) {
    for (double p = std::floor(std::log10(lo)); p <= std::ceil(std::log10(hi)); ++p)
      for (double m : {1.0, 2.0, 5.0}) {
        const double v = m * std::pow(10.0, p);
        if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) out.push_back(v);
      }
    if (out.size() > 9) {  // many decades: powers of ten only
      std::vector<double> decades;
      for (double v : out)
        if (std::abs(std::log10(v) - std::round(std::log10(v))) < 1e-9) decades.push_back(v);
      out = decades;
    }
    return out;
  }
  // The largest 1-2-5 step that leaves at least `intervals` of them: 5 to 12 ticks for 5.
  const double raw = (hi - lo) / intervals;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  double step = p;
  for (double m : {2.0, 5.0})
    if (m * p <= raw) step = m * p;
  for (double v = std::ceil(lo / step) * step; v <= hi + step * 1e-9; v += step)
    out.push_back(std::abs(v) < step * 1e-9 ? 0.0 : v);
  return out;
}

CairoSurface map_image(const HeightMap& map, double offset, double scale, double lo, double hi) {
  const Grid& g = map.grid;
  // Every k-th node where a side exceeds 2048: a picture needs no more, and a fine grid's full
  // image would cost its own gigabytes (and cairo stops at 32767 pixels).
  const std::size_t k = std::max<std::size_t>(1, (std::max(g.nx, g.ny) + 2047) / 2048);
  const std::size_t w = (g.nx + k - 1) / k, h = (g.ny + k - 1) / k;
  CairoSurface img(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, static_cast<int>(w), static_cast<int>(h)),
      cairo_surface_destroy);
  cairo_surface_flush(img.get());
  unsigned char* data = cairo_image_surface_get_data(img.get());
  const int stride = cairo_image_surface_get_stride(img.get());
  for (std::size_t b = 0; b < h; ++b) {
    auto* row = reinterpret_cast<std::uint32_t*>(data + (h - 1 - b) * stride);
    for (std::size_t a = 0; a < w; ++a) {
      const std::size_t i = a * k, j = b * k;
      const double z = map.at(i, j);
      double rgb[3] = {0.6, 0.6, 0.6};
      if (std::isfinite(z)) viridis(((z - offset) * scale - lo) / (hi - lo), rgb);
      auto byte = [](double c) { return static_cast<std::uint32_t>(std::lround(c * 255)); };
      row[a] = byte(rgb[0]) << 16 | byte(rgb[1]) << 8 | byte(rgb[2]);
    }
  }
  cairo_surface_mark_dirty(img.get());
  return img;
}

namespace {
// The image drawn over the rectangle (x, y, w, h), scaled as a whole.
void draw_image(cairo_t* cr, cairo_surface_t* image, double x, double y, double w, double h) {
  const int iw = cairo_image_surface_get_width(image), ih = cairo_image_surface_get_height(image);
  cairo_save(cr);
  cairo_rectangle(cr, x, y, w, h);
  cairo_clip(cr);
  cairo_translate(cr, x, y);
  cairo_scale(cr, w / iw, h / ih);
  cairo_set_source_surface(cr, image, 0, 0);
  // Nearest node below a node a pixel, smooth above: each node keeps its own colour.
  cairo_pattern_set_filter(cairo_get_source(cr),
                           w >= iw ? CAIRO_FILTER_NEAREST : CAIRO_FILTER_GOOD);
  cairo_pattern_set_extend(cairo_get_source(cr), CAIRO_EXTEND_PAD);
  cairo_paint(cr);
  cairo_restore(cr);
}
}  // namespace

void draw_map(const Canvas& cv, const HeightMap& map, double offset, double lo, double hi, double x,
              double y, double w, double h) {
  cairo_t* cr = *cv;
  const auto image = map_image(map, offset, 1e3, lo, hi);
  draw_image(cr, image.get(), x, y, w, h);
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, x, y, w, h);
  cairo_stroke(cr);
  const Grid& g = map.grid;
  const double xw = std::max(1e-12, (g.nx - 1) * g.dx), yw = std::max(1e-12, (g.ny - 1) * g.dy);
  for (double v : ticks(g.x0, g.x0 + xw, false)) {
    const double px = x + (v - g.x0) / xw * w;
    cairo_move_to(cr, px, y + h), cairo_line_to(cr, px, y + h + 5), cairo_stroke(cr);
    cv.text(px, y + h + 8, number(v), 0.5, 0);
  }
  for (double v : ticks(g.y0, g.y0 + yw, false)) {
    const double py = y + h - (v - g.y0) / yw * h;
    cairo_move_to(cr, x - 5, py), cairo_line_to(cr, x, py), cairo_stroke(cr);
    cv.text(x - 8, py, number(v), 1, 0.5);
  }
}

void colour_bar(const Canvas& cv, double x, double y, double w, double h, double lo, double hi,
                const std::string& label) {
  cairo_t* cr = *cv;
  for (int py = 0; py < static_cast<int>(h); ++py) {
    double rgb[3];
    viridis(1.0 - py / std::max(1.0, h - 1), rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
    cairo_rectangle(cr, x, y + py, w, 1.5);
    cairo_fill(cr);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, x, y, w, h);
  cairo_stroke(cr);
  double widest = 0;
  for (double v : ticks(lo, hi, false, 5)) {
    const double py = y + h - (v - lo) / (hi - lo) * h;
    cairo_move_to(cr, x + w, py), cairo_line_to(cr, x + w + 4, py), cairo_stroke(cr);
    cv.text(x + w + 7, py, number(v), 0, 0.5);
    cairo_text_extents_t e;
    cairo_text_extents(cr, number(v).c_str(), &e);
    widest = std::max(widest, e.x_advance);
  }
  cv.text(x + w + 12 + widest, y + h / 2, label, 0.5, 0, true);
}

}  // namespace topomill
