// Reading instrument files and measuring them: the reference values agreed by independent
// implementations (tests/refdata/README.md), the openGPS samples, round trips through every
// writer, form removal and Gaussian filters against analytic surfaces, and corrupt files.
#include <zip.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <sstream>

#include "io/csv.hpp"
#include "io/gsf.hpp"
#include "io/sdf.hpp"
#include "io/vts.hpp"
#include "io/x3p.hpp"
#include "metrology/form_removal.hpp"
#include "metrology/gaussian_filter.hpp"
#include "metrology/read_surface.hpp"
#include "metrology/roughness.hpp"
#include "support/run_command.hpp"
#include "support/zip_files.hpp"
#include "topomill/error.hpp"

using namespace topomill;

namespace {
std::string refdata(const std::string& name) {
  return std::string(TOPOMILL_REFDATA_DIR) + "/" + name;
}

Surface analytic(std::size_t nx, std::size_t ny, double dx, double (*f)(double, double)) {
  Surface s;
  Grid g;
  g.nx = nx, g.ny = ny, g.dx = dx, g.dy = dx;
  s.map = HeightMap(g);
  for (std::size_t j = 0; j < ny; ++j)
    for (std::size_t i = 0; i < nx; ++i) s.map.at(i, j) = f(g.x(i), g.y(j));
  return s;
}

double max_abs(const Surface& s) {
  double m = 0;
  for (std::size_t i = 0; i < s.map.z.size(); ++i)
    if (s.is_valid(i)) m = std::max(m, std::abs(s.map.z[i]));
  return m;
}

}  // namespace

TEST_CASE("x3p-2.x3p gives the agreed reference values", "[metrology][refdata]") {
  const Surface s = read_x3p(refdata("surfacetopography/x3p-2.x3p"));
  REQUIRE(s.map.grid.nx == 650);
  REQUIRE(s.map.grid.ny == 650);
  CHECK(s.map.grid.dx == Approx(1.27656509837346e-07 * 1e3).epsilon(1e-12));
  CHECK(s.valid_count() == 650u * 650u);
  const Roughness r = roughness(s.map, s.valid);  // mm; the reference is in metres
  CHECK(r.mean * 1e-3 == Approx(-2.49182416930559e-09).epsilon(1e-9));
  CHECK(r.Sa * 1e-3 == Approx(6.19546556887485e-08).epsilon(1e-9));
  CHECK(r.Sq * 1e-3 == Approx(7.72803327359775e-08).epsilon(1e-9));
  CHECK(r.Sp * 1e-3 == Approx(2.42407337581538e-07).epsilon(1e-9));
  CHECK(r.Sv * 1e-3 == Approx(3.11928862418462e-07).epsilon(1e-9));
  CHECK(r.Sz * 1e-3 == Approx(5.543362e-07).epsilon(1e-9));
  CHECK(r.Ssk == Approx(-0.346788601267018).epsilon(1e-9));
  CHECK(r.Sku == Approx(2.94193373526491).epsilon(1e-9));
  CHECK(r.Sdq == Approx(0.0620740474978505).epsilon(1e-9));
  CHECK(r.Sdr == Approx(0.1920252626).epsilon(1e-9));  // two triangles per cell: see roughness.hpp
  CHECK(r.Sdr_gwyddion == Approx(0.1887367719).epsilon(1e-9));  // Gwyddion 2.62 on this file
}

TEST_CASE("the openGPS samples: validity bits, integer scaling, XML and binary alike",
          "[metrology]") {
  const Surface xml = read_x3p(refdata("opengps_samples/ISO5436-sample1.x3p"));
  const Surface bin = read_x3p(refdata("opengps_samples/ISO5436-sample4_bin.x3p"));
  for (const Surface* s : {&xml, &bin}) {
    REQUIRE(s->map.grid.nx == 4);
    REQUIRE(s->map.grid.ny == 4);
    CHECK(s->valid_count() == 15);
    CHECK(s->valid[7] == 0);  // README: point 7 is invalid
  }
  // int16 986 with Increment 0.001 and Offset -0.5: z = -0.5 + 0.986 m.
  CHECK(bin.map.z[0] == Approx((-0.5 + 0.001 * 986) * 1e3).epsilon(1e-12));
  for (std::size_t i = 0; i < 16; ++i)
    if (i != 7) CHECK(bin.map.z[i] == Approx(xml.map.z[i]).margin(0.5e-3 * 1e3 + 1e-9));
}

TEST_CASE("every writer round-trips through its reader", "[metrology][io]") {
  Surface s = analytic(23, 17, 0.004, [](double x, double y) {
    return 1e-3 * std::sin(40 * x) * std::cos(30 * y) + 0.2;
  });
  s.map.grid.x0 = -0.43, s.map.grid.y0 = 25.75;  // a run's origin, kept by x3p, gsf and CSV
  // Spacings apart, so that a writer that swaps them (or writes one for both) shows.
  const double dx = 0.004, dy = 0.0061;
  s.map.grid.dy = dy;
  const std::string dir = testing::temp_dir("roundtrip");
  std::filesystem::create_directories(dir);
  write_x3p(dir + "/a.x3p", s.map);
  write_sdf(dir + "/a.sdf", s.map);
  write_gsf(dir + "/a.gsf", s.map, {"t", "a scene; tool x (radius 5)", 0});
  write_csv(dir + "/a.csv", s.map, {"a title\non two lines", "a scene\rnamed with breaks", 0});
  Surface square = s;
  square.map.grid.dy = dx;
  write_csv(dir + "/square.csv", square.map, {"square", "a scene", 0});
  // The CSV's grid comes from its header, with or without a --spacing that agrees (one spacing:
  // a square grid's); line breaks in its title or scene do not break the header (they would be
  // read as rows).
  const Surface x = read_x3p(dir + "/a.x3p"), d = read_sdf(dir + "/a.sdf"),
                gs = read_gsf(dir + "/a.gsf"), c = read_csv(dir + "/a.csv", 0),
                c2 = read_csv(dir + "/square.csv", dx);
  CHECK(c.map.grid.x0 == s.map.grid.x0);
  CHECK(c.map.grid.y0 == s.map.grid.y0);
  CHECK(c2.map.z == c.map.z);
  CHECK_THROWS_WITH(read_csv(dir + "/a.csv", 0.005),
                    Catch::Contains("the file's header gives dx_mm = 0.004") &&
                        Catch::Contains("a.csv:6), not 0.005"));
  CHECK_THROWS_WITH(read_csv(dir + "/a.csv", dx),
                    Catch::Contains("the file's header gives dy_mm = 0.0061") &&
                        Catch::Contains("a.csv:7), not 0.004"));
  for (const Surface* r : {&x, &d, &gs, &c}) {
    REQUIRE(r->map.grid.nx == 23);
    REQUIRE(r->map.grid.ny == 17);
    CHECK(r->map.grid.dx == Approx(dx).epsilon(1e-10));
    CHECK(r->map.grid.dy == Approx(dy).epsilon(1e-10));
  }
  for (const Surface* r : {&x, &gs, &c}) {  // the formats that carry the origin
    CHECK(r->map.grid.x0 == Approx(s.map.grid.x0).epsilon(1e-12));
    CHECK(r->map.grid.y0 == Approx(s.map.grid.y0).epsilon(1e-12));
  }
  for (std::size_t i = 0; i < s.map.z.size(); ++i) {
    CHECK(x.map.z[i] == Approx(s.map.z[i]).epsilon(1e-15));  // float64, through metres
    CHECK(d.map.z[i] == Approx(s.map.z[i]).epsilon(1e-15));
    CHECK(gs.map.z[i] == Approx(s.map.z[i]).epsilon(1e-7));  // float32
    CHECK(c.map.z[i] == Approx(s.map.z[i]).epsilon(1e-15));  // shortest exact text, in um
  }
  write_vts(dir + "/a.vts", s.map);
  pugi::xml_document vts;
  REQUIRE(vts.load_file((dir + "/a.vts").c_str()));
  CHECK(
      std::string(vts.child("VTKFile").child("StructuredGrid").attribute("WholeExtent").value()) ==
      "0 22 0 16 0 0");
  {  // The points: x along the first index at dx, y along the second at dy.
    std::istringstream points(vts.child("VTKFile")
                                  .child("StructuredGrid")
                                  .child("Piece")
                                  .child("Points")
                                  .child("DataArray")
                                  .child_value());
    std::vector<double> p(3 * s.map.z.size());
    for (double& v : p) REQUIRE(points >> v);
    CHECK(p[3] - p[0] == Approx(dx).epsilon(1e-6));  // ten digits
    CHECK(p[3 * 23 + 1] - p[1] == Approx(dy).epsilon(1e-6));
    CHECK(p[3 * 23] == Approx(p[0]).epsilon(1e-15));
  }
  for (const auto& e : std::filesystem::directory_iterator(dir))
    CHECK(e.path().filename().string().find(".partial") == std::string::npos);
}

TEST_CASE("form removal takes planes, polynomials and arcs to zero", "[metrology][form]") {
  auto plane = analytic(30, 20, 0.01, [](double x, double y) { return 0.3 + 0.02 * x - 0.05 * y; });
  CHECK(max_abs(remove_form(plane, Form::parse("plane", "--form"))) < 1e-13);
  auto quad = analytic(30, 20, 0.01,
                       [](double x, double y) { return 0.1 * x * x - 0.2 * x * y + y * y * y; });
  CHECK(max_abs(remove_form(quad, Form::parse("poly:3", "--form"))) < 1e-12);
  CHECK(max_abs(remove_form(quad, Form::parse("plane", "--form"))) > 1e-4);
  auto convex = analytic(10, 40, 0.02, [](double, double y) {
    return std::sqrt(50.0 * 50.0 - (y + 10) * (y + 10)) - 60;
  });
  CHECK(max_abs(remove_form(convex, Form::parse("arc", "--form"))) < 1e-9);
  auto concave = analytic(10, 40, 0.02, [](double, double y) {
    return 25 - std::sqrt(20.0 * 20.0 - (y - 3) * (y - 3));
  });
  CHECK(max_abs(remove_form(concave, Form::parse("arc", "--form"))) < 1e-9);
  // Form removal leaves the roughness: a cosine over whole periods (orthogonal to a plane) on a
  // tilted plane measures as the cosine.
  auto sine = analytic(400, 5, 0.001, [](double x, double y) {
    return 2e-3 * std::cos(2 * M_PI * x / 0.1) + 0.01 * x + 0.004 * y;
  });
  CHECK(roughness(remove_form(sine, Form::parse("plane", "--form")).map).Sa ==
        Approx(2 * 2e-3 / M_PI).epsilon(0.01));
  CHECK_THROWS_AS(Form::parse("poly:9", "--form"), InputError);
}

TEST_CASE("the Gaussian filter passes 50 % at the cut-off, long waves whole, short waves not",
          "[metrology][filter]") {
  const double lc = 0.08;
  auto amplitude_after = [&](double wavelength, bool low_pass) {
    Surface s;
    Grid g;
    g.nx = 2001, g.ny = 3, g.dx = 0.0005, g.dy = 0.0005;
    s.map = HeightMap(g);
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        s.map.at(i, j) = std::sin(2 * M_PI * g.x(i) / wavelength);
    const Surface f = low_pass ? gaussian_lowpass(s, lc) : l_filter(s, lc);
    double a = 0;  // away from the ends, where the renormalised kernel is whole
    for (std::size_t i = 400; i < 1600; ++i) a = std::max(a, std::abs(f.map.at(i, 1)));
    return a;
  };
  CHECK(amplitude_after(lc, true) == Approx(0.5).epsilon(0.01));
  CHECK(amplitude_after(10 * lc, true) > 0.99);
  CHECK(amplitude_after(lc / 10, true) < 0.01);
  CHECK(amplitude_after(lc / 10, false) > 0.99);  // the L-filter keeps the roughness
  CHECK(amplitude_after(10 * lc, false) < 0.01);  // and removes the waviness
}

TEST_CASE("arc removal leaves a ripple's 2A / pi and a bump's height with its sign",
          "[metrology][form]") {
  // A convex arc (r 50 mm) carrying a ripple along the cylinder's axis (whole periods, so the
  // fitted circle cannot take any of it): Sa of a cosine of amplitude A is 2A / pi. The arc spans
  // 0.02 deg; four whole periods of 100 nodes.
  const double A = 1e-3;
  auto rippled = analytic(400, 41, 0.0005, [](double x, double y) {
    return std::sqrt(50.0 * 50.0 - (y - 0.1) * (y - 0.1)) - 50 +
           1e-3 * std::cos(2 * M_PI * x / 0.05);
  });
  const Surface r = remove_form(rippled, Form::parse("arc", "--form"));
  CHECK(roughness(r.map).Sa == Approx(2 * A / M_PI).epsilon(1e-3));
  // A bump 2 um high on one node of a concave arc stands out by +2 um (a fit that returned zeros,
  // or the residual with the wrong sign, gives 0 or -2 um).
  auto bumped = analytic(21, 41, 0.002, [](double, double y) {
    return 20 - std::sqrt(20.0 * 20.0 - (y + 0.3) * (y + 0.3));
  });
  bumped.map.at(10, 20) += 2e-3;
  const Surface b = remove_form(bumped, Form::parse("arc", "--form"));
  CHECK(b.map.at(10, 20) == Approx(2e-3).epsilon(0.01));  // the fit takes 0.3 % of it
  CHECK(std::abs(b.map.at(3, 5)) < 1e-5);
}

TEST_CASE("arc removal on a flat or tilted surface is plane removal (the arc's limit)",
          "[metrology][form]") {
  // Issue 18: a flat surface gave Sa 25 um with --form arc (a wrong circle of huge radius). The
  // line is the circle of infinite radius: a profile with no curvature along y must come out as
  // plane removal leaves it. The ripple runs along x, so no plane or arc can take any of it.
  for (const double tilt : {0.0, 0.05, -0.3}) {
    const Surface flat = analytic(
        40, 30, 0.01, [](double x, double) { return 3.0 + 0.5e-3 * std::sin(2 * M_PI * x / 0.1); });
    Surface tilted = flat;
    for (std::size_t j = 0; j < tilted.map.grid.ny; ++j)
      for (std::size_t i = 0; i < tilted.map.grid.nx; ++i)
        tilted.map.at(i, j) += tilt * tilted.map.grid.y(j);
    const Surface arc = remove_form(tilted, Form::parse("arc", "--form"));
    const Surface plane = remove_form(tilted, Form::parse("plane", "--form"));
    INFO("tilt " << tilt);
    // (Tilted, the arc measures distance along the normal: cos(atan(tilt)) of the vertical one.)
    const double normal = 1 / std::sqrt(1 + tilt * tilt);
    CHECK(roughness(arc.map).Sa == Approx(roughness(plane.map).Sa * normal).epsilon(1e-3));
  }
}

TEST_CASE("an L-filter longer than the map removes the mean, with a kernel no longer than it",
          "[metrology][filter]") {
  // Issue 18: the kernel was as long as the cut-off (3 GB at 1e6 mm on a 20 x 20 map).
  const Surface s = analytic(20, 20, 0.01, [](double x, double y) { return x * x - 3 * y; });
  double mean = 0;
  for (double z : s.map.z) mean += z / static_cast<double>(s.map.z.size());
  for (const double cutoff : {1e3, 1e6}) {
    const Surface f = l_filter(s, cutoff);
    for (std::size_t k = 0; k < s.map.z.size(); ++k)
      REQUIRE(f.map.z[k] == Approx(s.map.z[k] - mean).margin(1e-9));
  }
}

TEST_CASE("a Gaussian longer than a strip's short side is the Gaussian written out",
          "[metrology][filter]") {
  // ISO 16610-61's weighting function s(d) = exp(-pi (d / (alpha lc))^2) / (alpha lc), alpha =
  // sqrt(ln 2 / pi), over the points within one cut-off along each axis (the kernel's extent),
  // normalised over those that exist: summed here over the map, point by point. On 10 x 40 and
  // 40 x 10 maps, with a cut-off longer than the short side (0.25 mm) and than both (0.8 mm), so
  // that a kernel cut to the wrong axis' length shows.
  const double dx = 0.01;
  for (const auto& [nx, ny] : {std::pair<std::size_t, std::size_t>{10, 40}, {40, 10}}) {
    Surface s;
    Grid g;
    g.nx = nx, g.ny = ny, g.dx = dx, g.dy = dx;
    s.map = HeightMap(g);
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i)
        s.map.at(i, j) = std::sin(0.9 * static_cast<double>(i)) * std::cos(0.3 * j) + 0.02 * j;
    for (const double lc : {0.25, 0.8}) {
      const double alpha = std::sqrt(std::log(2.0) / M_PI);
      auto weight = [&](double d) {
        return std::abs(d) <= lc + 1e-12 ? std::exp(-M_PI * std::pow(d / (alpha * lc), 2)) : 0.0;
      };
      const Surface f = l_filter(s, lc);
      double worst = 0;
      for (std::size_t j = 0; j < ny; ++j)
        for (std::size_t i = 0; i < nx; ++i) {
          double sum = 0, norm = 0;
          for (std::size_t q = 0; q < ny; ++q)
            for (std::size_t p = 0; p < nx; ++p) {
              const double w = weight((static_cast<double>(p) - static_cast<double>(i)) * dx) *
                               weight((static_cast<double>(q) - static_cast<double>(j)) * dx);
              sum += w * s.map.at(p, q), norm += w;
            }
          worst = std::max(worst, std::abs(f.map.at(i, j) - (s.map.at(i, j) - sum / norm)));
        }
      INFO(nx << " x " << ny << ", cut-off " << lc << " mm");
      CHECK(worst < 1e-12);
    }
  }
}

TEST_CASE("the Gaussian filter along y is the filter along x of the transposed map",
          "[metrology][filter]") {
  // Two spacings and a map with no symmetry, so that a pass along the wrong axis, or with the
  // other axis' spacing, shows.
  Surface s;
  Grid g;
  g.nx = 61, g.ny = 47, g.dx = 0.001, g.dy = 0.0015;
  s.map = HeightMap(g);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i)
      s.map.at(i, j) = std::sin(0.37 * i + 0.05 * i * j) + 0.3 * std::cos(0.8 * j);
  Surface t;
  Grid tg;
  tg.nx = g.ny, tg.ny = g.nx, tg.dx = g.dy, tg.dy = g.dx;
  t.map = HeightMap(tg);
  for (std::size_t j = 0; j < g.ny; ++j)
    for (std::size_t i = 0; i < g.nx; ++i) t.map.at(j, i) = s.map.at(i, j);
  for (double cutoff : {0.008, 0.025}) {
    const Surface a = gaussian_lowpass(s, cutoff), b = gaussian_lowpass(t, cutoff);
    double worst = 0;
    for (std::size_t j = 0; j < g.ny; ++j)
      for (std::size_t i = 0; i < g.nx; ++i)
        worst = std::max(worst, std::abs(a.map.at(i, j) - b.map.at(j, i)));
    CHECK(worst < 1e-12);
  }
}

TEST_CASE("invalid points take no part in parameters, filters and fits", "[metrology][invalid]") {
  // What an invalid point holds (a reader's NaN, a huge spike) must change nothing: each result
  // equals the one computed over the valid points alone.
  auto base = analytic(40, 30, 0.002, [](double x, double y) {
    return 0.01 * x - 0.02 * y + 1e-3 * std::sin(200 * x) * std::cos(150 * y);
  });
  base.valid.assign(base.map.z.size(), 1);
  for (std::size_t k : {7u, 300u, 301u, 1111u}) base.valid[k] = 0;
  Surface nan = base, spike = base;
  for (std::size_t k = 0; k < base.map.z.size(); ++k)
    if (!base.valid[k]) nan.map.z[k] = NAN, spike.map.z[k] = 1e6;

  // Height parameters against sums written here over the valid points.
  const auto plane = remove_form(nan, Form::parse("plane", "--form"));
  double n = 0, mean = 0, sa = 0, sq = 0, hi = -INFINITY, lo = INFINITY;
  for (std::size_t k = 0; k < plane.map.z.size(); ++k)
    if (plane.is_valid(k)) n += 1, mean += plane.map.z[k];
  mean /= n;
  for (std::size_t k = 0; k < plane.map.z.size(); ++k)
    if (plane.is_valid(k)) {
      const double h = plane.map.z[k] - mean;
      sa += std::abs(h), sq += h * h, hi = std::max(hi, h), lo = std::min(lo, h);
    }
  const auto r = roughness(plane.map, plane.valid);
  CHECK(r.Sa == Approx(sa / n).epsilon(1e-12));
  CHECK(r.Sq == Approx(std::sqrt(sq / n)).epsilon(1e-12));
  CHECK(r.Sp == Approx(hi).epsilon(1e-12));
  CHECK(r.Sv == Approx(-lo).epsilon(1e-12));
  for (double v : {r.Ssk, r.Sku, r.Sdq, r.Sdr}) CHECK(std::isfinite(v));

  // Fits and filters: the NaN-holding and the spike-holding maps agree at every valid point.
  for (const char* form : {"plane", "poly:2", "arc"}) {
    const auto a = remove_form(nan, Form::parse(form, "--form")),
               b = remove_form(spike, Form::parse(form, "--form"));
    for (std::size_t k = 0; k < a.map.z.size(); ++k)
      if (a.is_valid(k)) REQUIRE(a.map.z[k] == Approx(b.map.z[k]).margin(1e-12));
  }
  for (double cutoff : {0.008, 0.02}) {
    const auto a = gaussian_lowpass(nan, cutoff), b = gaussian_lowpass(spike, cutoff);
    for (std::size_t k = 0; k < a.map.z.size(); ++k)
      if (a.is_valid(k)) {
        REQUIRE(std::isfinite(a.map.z[k]));
        REQUIRE(a.map.z[k] == Approx(b.map.z[k]).margin(1e-12));
      }
  }
}

TEST_CASE("corrupt and inconsistent files are refused with what is wrong", "[metrology][errors]") {
  const std::string dir = testing::temp_dir("corrupt");
  std::filesystem::create_directories(dir);
  const std::string good = refdata("surfacetopography/x3p-2.x3p");
  // Truncated zip.
  {
    std::ifstream in(good, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), {});
    std::ofstream(dir + "/trunc.x3p", std::ios::binary) << bytes.substr(0, bytes.size() / 2);
    CHECK_THROWS_WITH(read_x3p(dir + "/trunc.x3p"),
                      Catch::Contains("trunc.x3p: error: not a readable x3p"));
  }
  // main.xml changed under its checksum, and point data of the wrong size.
  std::string xml;
  {
    int e = 0;
    zip_t* z = zip_open(good.c_str(), ZIP_RDONLY, &e);
    REQUIRE(z);
    zip_stat_t st;
    zip_stat(z, "main.xml", 0, &st);
    xml.resize(st.size);
    zip_file_t* f = zip_fopen(z, "main.xml", 0);
    zip_fread(f, xml.data(), st.size);
    zip_fclose(f);
    zip_discard(z);
  }
  testing::write_zip(dir + "/md5.x3p",
                     {{"main.xml", xml + " "},
                      {"md5checksum.hex", "00000000000000000000000000000000 *main.xml\n"}});
  CHECK_THROWS_WITH(read_x3p(dir + "/md5.x3p"),
                    Catch::Contains("MD5 checksum of main.xml does not match"));
  testing::write_zip(dir + "/size.x3p",
                     {{"main.xml", xml}, {"bindata/data.bin", std::string(80, '\0')}});
  CHECK_THROWS_WITH(read_x3p(dir + "/size.x3p"),
                    Catch::Contains("does not match MD5ChecksumPointData") ||
                        Catch::Contains("holds 80 bytes: expected 3380000"));
  // sdf with too few points, and with a NaN.
  std::ofstream(dir + "/few.sdf") << "aISO-1.0\nNumPoints = 3\nNumProfiles = 2\nXscale = "
                                     "1e-6\nYscale = 1e-6\nZscale = 1e-6\n*\n1 2 3\n4 5\n*\n";
  CHECK_THROWS_WITH(read_sdf(dir + "/few.sdf"),
                    Catch::Contains("holds 5 points; the header says 6"));
  std::ofstream(dir + "/nan.sdf") << "aISO-1.0\nNumPoints = 2\nNumProfiles = 1\nXscale = "
                                     "1e-6\nYscale = 1e-6\nZscale = 1e-6\n*\n1 nan\n*\n";
  CHECK_THROWS_WITH(read_sdf(dir + "/nan.sdf"), Catch::Contains("point 1 is not finite"));
  std::ofstream(dir + "/short.gsf", std::ios::binary)
      << std::string("Gwyddion Simple Field 1.0\nXRes = 10\nYRes = 10\n") + std::string(3, '\0') +
             "abcd";
  CHECK_THROWS_WITH(read_gsf(dir + "/short.gsf"), Catch::Contains("truncated"));
  CHECK_THROWS_WITH(read_surface(dir + "/x.png"), Catch::Contains("unknown format '.png'"));
}

TEST_CASE("measure reports the parameters and refuses bad files with exit code 2",
          "[metrology][cli]") {
  const auto ok =
      testing::run_topomill("measure '" + refdata("surfacetopography/sdf-1.sdf") + "' --json");
  REQUIRE(ok.exit_code == 0);
  const auto j = nlohmann::json::parse(ok.out).at("roughness");
  // The reference values (refdata README), in um, round-trip exact to 13 digits.
  CHECK(j.at("Sa").at("value").get<double>() == Approx(1.15801275510204e-2).epsilon(1e-12));
  CHECK(j.at("Sa").at("unit") == "um");
  CHECK(j.at("Ssk").at("value").get<double>() == Approx(-0.64304606303356).epsilon(1e-12));
  CHECK(j.at("Ssk").at("unit") == "1");
  CHECK(j.at("Sdr").at("unit") == "%");
  CHECK(j.at("Sdr_gwyddion").at("method").get<std::string>().find("Gwyddion") == 0);
  const auto bad = testing::run_topomill("measure '" + refdata("surfacetopography/sdf-1.sdf") +
                                         "' --form poly:0");
  CHECK(bad.exit_code == 2);
  CHECK(bad.err.find("expected none, plane, poly:N") != std::string::npos);
  const std::string dir = testing::temp_dir("measure_bad");
  std::filesystem::create_directories(dir);
  std::ofstream(dir + "/bad.x3p") << "not a zip";
  const auto corrupt = testing::run_topomill("measure '" + dir + "/bad.x3p'");
  CHECK(corrupt.exit_code == 2);
  CHECK(corrupt.err.find("bad.x3p: error: not a readable x3p") != std::string::npos);
  CHECK_FALSE(corrupt.crashed);
}
