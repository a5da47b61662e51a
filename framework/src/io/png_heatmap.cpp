#include "png_heatmap.hpp"

#include <png.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <vector>

#include "io/atomic_file.hpp"

namespace topomill {

namespace {

// A 5x7 bitmap font for the few characters the labels use (rows top down, bit 4 = left column).
const std::map<char, std::array<unsigned char, 7>>& font() {
  static const std::map<char, std::array<unsigned char, 7>> f = {
      {'0', {0x0E, 0x11, 0x13, 0x15, 0x19, 0x11, 0x0E}},
      {'1', {0x04, 0x0C, 0x04, 0x04, 0x04, 0x04, 0x0E}},
      {'2', {0x0E, 0x11, 0x01, 0x02, 0x04, 0x08, 0x1F}},
      {'3', {0x1F, 0x02, 0x04, 0x02, 0x01, 0x11, 0x0E}},
      {'4', {0x02, 0x06, 0x0A, 0x12, 0x1F, 0x02, 0x02}},
      {'5', {0x1F, 0x10, 0x1E, 0x01, 0x01, 0x11, 0x0E}},
      {'6', {0x06, 0x08, 0x10, 0x1E, 0x11, 0x11, 0x0E}},
      {'7', {0x1F, 0x01, 0x02, 0x04, 0x08, 0x08, 0x08}},
      {'8', {0x0E, 0x11, 0x11, 0x0E, 0x11, 0x11, 0x0E}},
      {'9', {0x0E, 0x11, 0x11, 0x0F, 0x01, 0x02, 0x0C}},
      {'.', {0, 0, 0, 0, 0, 0x0C, 0x0C}},
      {'-', {0, 0, 0, 0x1F, 0, 0, 0}},
      {'e', {0, 0, 0x0E, 0x11, 0x1F, 0x10, 0x0E}},
      {'m', {0, 0, 0x1A, 0x15, 0x15, 0x11, 0x11}},
      {'x', {0, 0, 0x11, 0x0A, 0x04, 0x0A, 0x11}},
      {'s', {0, 0, 0x0E, 0x10, 0x0E, 0x01, 0x1E}},
      {'u', {0, 0, 0x11, 0x11, 0x11, 0x13, 0x0D}},
      {'h', {0x10, 0x10, 0x16, 0x19, 0x11, 0x11, 0x11}},
      {'y', {0, 0, 0x11, 0x11, 0x0F, 0x01, 0x0E}},
      {'z', {0, 0, 0x1F, 0x02, 0x04, 0x08, 0x1F}},
      {'(', {0x02, 0x04, 0x08, 0x08, 0x08, 0x04, 0x02}},
      {')', {0x08, 0x04, 0x02, 0x02, 0x02, 0x04, 0x08}},
      {' ', {0, 0, 0, 0, 0, 0, 0}},
  };
  return f;
}

constexpr int kScale = 2;             // glyph pixels per font pixel
constexpr int kAdvance = 6 * kScale;  // character width including spacing
constexpr int kGlyphHeight = 7 * kScale;

struct Canvas {
  int w, h;
  std::vector<unsigned char> rgb;
  Canvas(int w_, int h_) : w(w_), h(h_), rgb(static_cast<std::size_t>(w_) * h_ * 3, 255) {}
  void set(int x, int y, std::array<unsigned char, 3> c) {
    if (x < 0 || y < 0 || x >= w || y >= h) return;
    auto* p = &rgb[(static_cast<std::size_t>(y) * w + x) * 3];
    p[0] = c[0], p[1] = c[1], p[2] = c[2];
  }
  void text(int x, int y, const std::string& s) {
    for (char ch : s) {
      auto it = font().find(ch);
      if (it != font().end())
        for (int r = 0; r < 7; ++r)
          for (int c = 0; c < 5; ++c)
            if (it->second[r] & (0x10 >> c))
              for (int dy = 0; dy < kScale; ++dy)
                for (int dx = 0; dx < kScale; ++dx)
                  set(x + c * kScale + dx, y + r * kScale + dy, {0, 0, 0});
      x += kAdvance;
    }
  }
  int text_width(const std::string& s) const { return static_cast<int>(s.size()) * kAdvance; }
};

// Perceptually ordered dark-blue -> teal -> yellow ramp (viridis control points).
std::array<unsigned char, 3> colour(double t) {
  static const double stops[][3] = {
      {68, 1, 84}, {59, 82, 139}, {33, 145, 140}, {94, 201, 98}, {253, 231, 37}};
  t = std::clamp(t, 0.0, 1.0) * 4.0;
  const int k = std::min(3, static_cast<int>(t));
  const double w = t - k;
  std::array<unsigned char, 3> c{};
  for (int i = 0; i < 3; ++i)
    c[i] = static_cast<unsigned char>(std::lround((1 - w) * stops[k][i] + w * stops[k + 1][i]));
  return c;
}

// A "nice" tick step (1, 2 or 5 times a power of ten) giving about `count` ticks over `range`.
double nice_step(double range, int count) {
  if (!(range > 0)) return 1.0;
  const double raw = range / count;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * p >= raw) return m * p;
  return 10 * p;
}

std::string label(double v, double step) {
  char buf[32];
  const int digits = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::snprintf(buf, sizeof buf, "%.*f", digits, std::abs(v) < step * 1e-6 ? 0.0 : v);
  return buf;
}

}  // namespace

void write_png_heatmap(const std::string& path, const HeightMap& map, const HeatmapLabels& lab) {
  const Grid& g = map.grid;
  const double lx = g.dx * static_cast<double>(g.nx - 1), ly = g.dy * static_cast<double>(g.ny - 1);
  // The map keeps its aspect ratio, longest side 480 px.
  const double px = 480.0 / std::max(lx, ly);
  const int mw = std::max(1, static_cast<int>(std::lround(lx * px)));
  const int mh = std::max(1, static_cast<int>(std::lround(ly * px)));
  const int left = 70, top = 20, bottom = 60, bar_gap = 20, bar_w = 20, right = 110;
  Canvas cv(left + mw + bar_gap + bar_w + right, top + mh + bottom);

  double lo = INFINITY, hi = -INFINITY;
  for (double z : map.z) lo = std::min(lo, z * 1e3), hi = std::max(hi, z * 1e3);
  const double span = hi > lo ? hi - lo : 1.0;

  // Image rows run downwards; s grows upwards as on a plot.
  for (int py = 0; py < mh; ++py)
    for (int pxl = 0; pxl < mw; ++pxl) {
      const auto i = static_cast<std::size_t>(std::lround(pxl / px / g.dx));
      const auto j = static_cast<std::size_t>(std::lround((mh - 1 - py) / px / g.dy));
      const double z = map.at(std::min(i, g.nx - 1), std::min(j, g.ny - 1)) * 1e3;
      cv.set(left + pxl, top + py, colour((z - lo) / span));
    }

  // Axes with ticks and labels.
  const double sx = nice_step(lx, 5), sy = nice_step(ly, 5);
  for (double v = 0; v <= lx * (1 + 1e-9); v += sx) {
    const int x = left + static_cast<int>(std::lround(v * px));
    for (int k = 0; k < 6; ++k) cv.set(x, top + mh + k, {0, 0, 0});
    const std::string t = label(v, sx);
    cv.text(x - cv.text_width(t) / 2, top + mh + 9, t);
  }
  cv.text(left + mw / 2 - cv.text_width(lab.x) / 2, top + mh + 12 + kGlyphHeight, lab.x);
  for (double v = 0; v <= ly * (1 + 1e-9); v += sy) {
    const int y = top + mh - 1 - static_cast<int>(std::lround(v * px));
    for (int k = 0; k < 6; ++k) cv.set(left - 1 - k, y, {0, 0, 0});
    const std::string t = label(v, sy);
    cv.text(left - 9 - cv.text_width(t), y - kGlyphHeight / 2, t);
  }
  cv.text(4, top - 16 < 0 ? 0 : 2, lab.y);

  // Colour bar with its own ticks.
  const int bx = left + mw + bar_gap;
  for (int py = 0; py < mh; ++py)
    for (int k = 0; k < bar_w; ++k) cv.set(bx + k, top + py, colour(1.0 - py / double(mh - 1)));
  const double sz = nice_step(span, 5);
  for (double v = std::ceil(lo / sz) * sz; v <= hi + 1e-12; v += sz) {
    const int y = top + static_cast<int>(std::lround((hi - v) / span * (mh - 1)));
    for (int k = 0; k < 5; ++k) cv.set(bx + bar_w + k, y, {0, 0, 0});
    cv.text(bx + bar_w + 8, y - kGlyphHeight / 2, label(v, sz));
  }
  cv.text(bx, top + mh + 9, lab.z);

  write_atomically_to(path, [&](const std::string& tmp) {
    png_image image{};
    image.version = PNG_IMAGE_VERSION;
    image.width = static_cast<png_uint_32>(cv.w);
    image.height = static_cast<png_uint_32>(cv.h);
    image.format = PNG_FORMAT_RGB;
    if (!png_image_write_to_file(&image, tmp.c_str(), 0, cv.rgb.data(), 0, nullptr))
      throw std::runtime_error("cannot write PNG '" + path + "': " + image.message);
  });
}

}  // namespace topomill
