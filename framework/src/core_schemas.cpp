// Schemas of the core's own scene tables. Plugin tables carry their model's schema instead.
#include "metrology/parameters.hpp"
#include "scene.hpp"

namespace topomill {

namespace {
Schema scene_schema() {
  Schema s;
  s.add_string("name", "Title of the scene, copied into summary.json").with_default(std::string());
  return s;
}

Schema cutting_schema() {
  Schema s;
  s.add_number("spindle_speed",
               "Spindle speed ns (up to 1e6 rpm; the fastest spindles made turn 0.5e6)")
      .with_unit("rpm")
      .above(0)
      .at_most(1e6)
      .is_required();
  // Below 1 nm a pass lasts so many revolutions that the spindle angle's rounding moves the
  // edge by nanometres (and tooth_passage's solver slows 150-fold from 3e-9 to 1e-9 mm).
  s.add_number("feed_per_tooth", "Feed per tooth fz (at least 1 nm)")
      .with_unit("mm")
      .at_least(1e-6)
      .is_required();
  s.add_number("depth_of_cut", "Depth of cut ap, measured along the surface normal")
      .with_unit("mm")
      .above(0)
      .is_required();
  s.add_number(
       "stepover",
       "Step-over ae between adjacent passes (along X; along the surface for raster_across)")
      .with_unit("mm")
      .above(0)
      .is_required();
  s.add_choice("spindle_direction", {"cw", "ccw"},
               "Spindle rotation seen from above the tool: cw (M03, right-hand cutters) or ccw")
      .with_default(std::string("cw"));
  return s;
}

Schema runout_schema() {
  Schema s;
  s.add_number("offset",
               "Radial runout e: the tool's axis (and the ball centre) off the spindle axis, "
               "turning with the spindle")
      .with_unit("mm")
      .at_least(0)
      .at_most(1)
      .with_default(0.0);
  s.add_number("angle",
               "Direction of the offset from tooth 1 (its azimuth where the lag is zero), in the "
               "spindle's sense of turning")
      .with_unit("deg")
      .at_least(-360)
      .at_most(360)
      .with_default(0.0);
  // Wang et al. (2023) give each insert's runout as steps from the first: eps_r, eps_a.
  s.add_number("edge_radial_step",
               "Per-edge runout eps_r: edge K (0-based) is K eps_r farther from the axis")
      .with_unit("mm")
      .at_least(-1)
      .at_most(1)
      .with_default(0.0);
  s.add_number("edge_axial_step",
               "Per-edge runout eps_a: edge K (0-based) is K eps_a higher (shallower)")
      .with_unit("mm")
      .at_least(-1)
      .at_most(1)
      .with_default(0.0);
  return s;
}

Schema region_schema() {
  Schema s;
  s.add_number("lambda",
               "Inclination of the surface normal at the centre of the patch, from +Z towards +Y "
               "(give this or centre)")
      .with_unit("deg")
      .at_least(-90)
      .at_most(90);
  s.add_number_array("centre",
                     "The patch's centre in plan [x, y]: over the uncut surface point there (give "
                     "this or lambda; with cutter-location data, where the data cuts)")
      .with_unit("mm")
      .with_length(2);
  s.add_number_array("size", "Patch size [along X, along the surface in Y]")
      .with_unit("mm")
      .with_length(2)
      .above(0)
      .is_required();
  s.add_number("spacing", "Grid node spacing in X and Y").with_unit("mm").above(0).is_required();
  return s;
}

Schema analysis_schema() {
  Schema s;
  s.add_choice("form", {"nominal", "plane", "none"},
               "Form removal before the parameters: nominal = distance along the surface normal "
               "from the nominal cut surface (the paper's unrolling), plane = least-squares plane")
      .with_default(std::string("nominal"));
  s.add_string_array("parameters", parameter_words(),
                     "ISO 25178-2 parameters to report: default (height and hybrid), all, a family "
                     "(height, spatial, hybrid, functional, volume) or single names; "
                     "docs/metrology.md defines each")
      .with_default(std::vector<std::string>{"default"});
  // ISO 25178-3's defaults (s, p, q) and common ones for the rest; each settable.
  s.add_number("acf_threshold", "s: the autocorrelation's decay value for Sal and Str")
      .above(0)
      .below(1)
      .with_default(0.2);
  s.add_number("volume_p", "p: Vmp = Vm(p), Vvc = Vv(p) - Vv(q); Vm and Vv at p")
      .with_unit("%")
      .above(0)
      .below(100)
      .with_default(10.0);
  s.add_number("volume_q", "q: Vmc = Vm(q) - Vm(p), Vvv = Vv(q); above volume_p")
      .with_unit("%")
      .above(0)
      .below(100)
      .with_default(80.0);
  s.add_number("sxp_p", "p of Sxp = Smc(p) - Smc(q)")
      .with_unit("%")
      .above(0)
      .below(100)
      .with_default(2.5);
  s.add_number("sxp_q", "q of Sxp; above sxp_p")
      .with_unit("%")
      .above(0)
      .below(100)
      .with_default(50.0);
  s.add_number("smr_c", "c: the height above the mean plane at which Smr(c) is taken")
      .with_unit("um")
      .at_least(-1e6)
      .at_most(1e6)
      .with_default(0.0);
  s.add_number("smc_mr", "mr: the material ratio at which Smc(mr) is taken")
      .with_unit("%")
      .at_least(0)
      .at_most(100)
      .with_default(10.0);
  return s;
}

Schema output_schema() {
  Schema s;
  s.add_string("dir", "Output directory, relative to the working directory (--out overrides)")
      .with_default(std::string());
  s.add_string_array("formats", {"csv", "gsf", "x3p", "sdf", "vts", "png", "cl"},
                     "Files to write besides summary.json: height maps (raw and residual; png: "
                     "the residual as a heat map and a shaded 3D view); cl: the tool path as "
                     "cutter-location data (tool_path.csv, read by cl_file)")
      .with_default(std::vector<std::string>{"csv", "gsf", "x3p", "png"});
  return s;
}
}  // namespace

const std::vector<std::pair<std::string, Schema>>& core_schemas() {
  static const std::vector<std::pair<std::string, Schema>> all = {
      {"scene", scene_schema()},   {"cutting", cutting_schema()},   {"runout", runout_schema()},
      {"region", region_schema()}, {"analysis", analysis_schema()}, {"output", output_schema()}};
  return all;
}

const std::vector<std::string>& effect_tables() {
  static const std::vector<std::string> all = {"vibration", "deflection", "springback"};
  return all;
}

}  // namespace topomill
