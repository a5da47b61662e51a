// The drawing kit every picture shares (charts, heat maps, the 3D view): a white cairo canvas
// with DejaVu Sans, text placed by its anchor, the viridis colour scale, 1-2-5 ticks, and a
// height map as one image (one pixel per node, scaled as a whole: no seams between cells).
#pragma once

#include <cairo.h>

#include <memory>
#include <string>
#include <vector>

#include "topomill/types.hpp"

namespace topomill {

using CairoSurface = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using CairoContext = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

struct Canvas {
  CairoSurface surface;
  CairoContext cr;
  Canvas(int w, int h);
  cairo_t* operator*() const { return cr.get(); }
  // Text anchored at (x, y): ax, ay in [0, 1] pick which point of its box sits there.
  void text(double x, double y, const std::string& s, double ax = 0, double ay = 0,
            bool vertical = false) const;
  // Written atomically.
  void write(const std::string& path) const;
};

// Qualitative palette (Okabe-Ito), readable by colour-blind viewers: sets the source colour.
void palette(cairo_t* cr, std::size_t i);
// Viridis at t in [0, 1].
void viridis(double t, double rgb[3]);
// A tick label: 4 significant digits, no trailing zeros; a whole number below a million in full.
std::string number(double v);
// Ticks in [lo, hi]: on a linear axis the largest 1-2-5 step that leaves at least `intervals`
// steps (4: 4 to 10 ticks); on a log axis powers of ten (with 2 and 5 if few).
std::vector<double> ticks(double lo, double hi, bool log, int intervals = 4);

// The map's nodes as an image, pixel (i, ny-1-j) = node (i, j) so that y grows upwards, coloured
// by viridis over [lo, hi] of (z - offset) * scale. Non-finite nodes are grey. Above 2048 nodes
// a side, every k-th node.
CairoSurface map_image(const HeightMap& map, double offset, double scale, double lo, double hi);

// The map's heights (z - offset, in µm) coloured over [lo, hi] as one image over the rectangle
// (x, y, w, h), framed, with ticks at its nodes' own coordinates (mm) below and to the left.
void draw_map(const Canvas& cv, const HeightMap& map, double offset, double lo, double hi, double x,
              double y, double w, double h);

// A vertical colour bar at (x, y, w, h) for [lo, hi], at least five ticks on its right and its
// label beside them, upright.
void colour_bar(const Canvas& cv, double x, double y, double w, double h, double lo, double hi,
                const std::string& label);

}  // namespace topomill
