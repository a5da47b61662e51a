// Height maps between numpy and the metrology code: reading and writing the four formats,
// measuring (form, filters, ISO 25178-2 parameters) and comparing, as `measure` and `compare`
// do. A map crosses as (z, dx, dy, x0, y0): z of shape (ny, nx), x fastest, in mm, NaN where a
// point is missing.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <functional>

#include "analysis_options.hpp"
#include "calls.hpp"
#include "compare.hpp"
#include "metrology/read_surface.hpp"
#include "metrology/roughness_report.hpp"
#include "metrology/write_surface.hpp"

namespace topomill::python {

namespace {

using Heights = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The fewest valid points `topomill measure` and `compare` take.
constexpr std::size_t kLeastToMeasure = 4, kLeastToCompare = 16;

// How a map is given to the calls below, and how they hand one back.
struct MapArgs {
  Heights z;
  double dx = 0, dy = 0, x0 = 0, y0 = 0;
  std::string source;
};

Surface to_surface(const MapArgs& a) {
  if (a.z.ndim() != 2)
    throw InputError(SourceRef{a.source}, "z",
                     "expected a 2-D array of heights (ny, nx), got " + std::to_string(a.z.ndim()) +
                         " dimensions");
  if (a.z.shape(0) < 1 || a.z.shape(1) < 1)
    throw InputError(SourceRef{a.source}, "z", "expected at least one row and one column");
  for (const double d : {a.dx, a.dy})
    if (!(std::isfinite(d) && d > 0))
      throw InputError(SourceRef{a.source}, "dx",
                       "expected positive finite spacings, got " + format_number(d));
  Surface s;
  s.source = a.source;
  s.map = HeightMap(Grid{static_cast<std::size_t>(a.z.shape(1)),
                         static_cast<std::size_t>(a.z.shape(0)), a.x0, a.y0, a.dx, a.dy});
  const double* z = a.z.data();
  bool missing = false;
  for (std::size_t i = 0; i < s.map.z.size(); ++i) missing = missing || !std::isfinite(z[i]);
  if (missing) s.valid.assign(s.map.z.size(), 1);
  for (std::size_t i = 0; i < s.map.z.size(); ++i) {
    // Infinity is no height: missing, like NaN, rather than a value that poisons every sum.
    if (std::isfinite(z[i]))
      s.map.z[i] = z[i];
    else
      s.valid[i] = 0;
  }
  return s;
}

py::tuple to_python(const Surface& s) {
  const Grid& g = s.map.grid;
  Heights z({static_cast<py::ssize_t>(g.ny), static_cast<py::ssize_t>(g.nx)});
  double* out = z.mutable_data();
  for (std::size_t i = 0; i < s.map.z.size(); ++i) out[i] = s.is_valid(i) ? s.map.z[i] : NAN;
  return py::make_tuple(z, g.dx, g.dy, g.x0, g.y0);
}

// The command line's analysis options, filled from keyword arguments and checked by the same
// code; an error names the keyword ("filter_s") where the command line names "--filter-s".
cli::AnalysisOptions analysis_options(const py::dict& o, const std::string& call) {
  cli::AnalysisOptions a;
  a.form_text = o["form"].cast<std::string>();
  a.lambda_s = o["filter_s"].cast<double>(), a.lambda_c = o["filter_l"].cast<double>();
  a.parameters = o["parameters"].cast<std::string>();
  a.s = o["acf_threshold"].cast<double>();
  a.volume_p = o["volume_p"].cast<double>(), a.volume_q = o["volume_q"].cast<double>();
  a.sxp_p = o["sxp_p"].cast<double>(), a.sxp_q = o["sxp_q"].cast<double>();
  a.smr_c = o["smr_c"].cast<double>(), a.smc_mr = o["smc_mr"].cast<double>();
  with_python_names([&] { a.check(); }, call);
  return a;
}

void check_finite(const ParameterValues& v, const std::string& source) {
  if (const std::string name = first_non_finite(v); !name.empty())
    throw InputError(SourceRef{source}, "",
                     name +
                         " is not finite for these heights (their squares or slopes overflow "
                         "double precision): expected heights and spacings of a real surface");
}

// What compare returns, as the package's Comparison takes it.
py::dict comparison_dict(const Comparison& c, const std::string& processing) {
  const Registration& r = c.registration;
  py::dict reg;
  reg["tx"] = r.tx, reg["ty"] = r.ty, reg["angle"] = r.angle, reg["offset"] = r.offset;
  reg["correlation"] = r.correlation, reg["rms"] = r.rms, reg["overlap"] = r.overlap;
  reg["iterations"] = r.iterations, reg["converged"] = r.converged;
  auto lay = [](const Lay& l) {
    py::dict d;
    d["std_deg"] = l.std_deg, d["lay_deg"] = l.lay_deg, d["across_mm"] = l.across_mm;
    d["along_mm"] = l.along_mm, d["x_mm"] = l.x_mm, d["y_mm"] = l.y_mm;
    return d;
  };
  py::dict out;
  out["registration"] = reg;
  out["interpolation"] = c.interpolation;
  out["sim"] = to_python(c.sim_overlap), out["aligned"] = to_python(c.aligned);
  out["difference"] = to_python(c.difference);
  out["sim_parameters"] = reported_parameters(c.sim_parameters);
  out["meas_parameters"] = reported_parameters(c.meas_parameters);
  out["sim_lay"] = lay(c.sim_lay), out["meas_lay"] = lay(c.meas_lay);
  out["overlap_share"] = c.overlap_share;
  out["processing"] = processing;
  return out;
}

// A map given for `call`, with at least `least` valid points.
Surface with_points(const MapArgs& given, std::size_t least, const char* call) {
  Surface s = to_surface(given);
  if (s.valid_count() < least)
    throw InputError(SourceRef{given.source}, "z",
                     "the map has " + std::to_string(s.valid_count()) +
                         " valid points: expected at least " + std::to_string(least) + " to " +
                         call);
  return s;
}

}  // namespace

void bind_surface(py::module_& m) {
  py::class_<MapArgs>(m, "MapArgs")
      .def(py::init<Heights, double, double, double, double, std::string>(), py::arg("z"),
           py::arg("dx"), py::arg("dy"), py::arg("x0"), py::arg("y0"), py::arg("source"));

  m.def("read_surface", [](const std::string& path, double spacing) {
    Surface s;
    interruptible([&] { with_python_names([&] { s = read_surface(path, spacing); }, "read()"); },
                  ErrorKind::Input);
    return to_python(s);
  });

  m.def("write_surface",
        [](const std::string& path, const MapArgs& map, const std::string& description) {
          interruptible(
              [&] {
                check_surface_format(path, "path");
                write_surface(path, to_surface(map), "path", description);
              },
              ErrorKind::Input);
        });

  m.def("measure", [](const MapArgs& map, const py::dict& options) {
    const cli::AnalysisOptions a = analysis_options(options, "measure()");
    Surface s;
    ParameterValues values;
    interruptible(
        [&] {
          s = a.process(with_points(map, kLeastToMeasure, "measure"));
          values = compute_parameters(s, a.names, a.settings);
          check_finite(values, map.source);
        },
        ErrorKind::Input);
    return py::make_tuple(to_python(s), reported_parameters(values), undefined_parameters(values),
                          a.processing());
  });

  m.def("compare", [](const MapArgs& sim_map, const MapArgs& meas_map, const py::dict& options,
                      bool rotation, double max_shift) {
    const cli::AnalysisOptions a = analysis_options(options, "compare()");
    if (!(std::isfinite(max_shift) && max_shift >= 0 && max_shift <= 1e6))
      throw InputError(
          SourceRef{"compare()"}, "max_shift",
          "expected a length from 0 to 1e6 mm (0: any shift), got " + format_number(max_shift));
    Comparison c;
    interruptible(
        [&] {
          auto load = [&](const MapArgs& given) {
            Surface s = a.process(with_points(given, kLeastToCompare, "compare"));
            s.source = given.source;
            return s;
          };
          CompareSettings settings;
          settings.names = a.names;
          settings.parameters = a.settings;
          settings.registration.rotation = rotation;
          settings.registration.max_shift = max_shift;
          c = compare_surfaces(load(sim_map), load(meas_map), settings);
        },
        ErrorKind::Input);
    return comparison_dict(c, a.processing());
  });
}

}  // namespace topomill::python
