#include "metrology/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <set>

#include "interrupt.hpp"
#include "metrology/autocorrelation.hpp"
#include "metrology/material_ratio.hpp"
#include "metrology/spectrum.hpp"
#include "topomill/error.hpp"
#include "topomill/params.hpp"

namespace topomill {

const std::vector<ParameterInfo>& parameter_catalogue() {
  static const std::vector<ParameterInfo> all = {
      {"Sa", "height", "um", "mean of |z - mean| over the valid points"},
      {"Sq", "height", "um", "root mean square of z - mean"},
      {"Sp", "height", "um", "highest z - mean"},
      {"Sv", "height", "um", "depth of the lowest point below the mean"},
      {"Sz", "height", "um", "Sp + Sv"},
      {"Ssk", "height", "1", "mean of (z - mean)^3 / Sq^3"},
      {"Sku", "height", "1", "mean of (z - mean)^4 / Sq^4"},
      {"Sal", "spatial", "mm",
       "the shortest lag at which the areal autocorrelation falls to s (acf_threshold), over 720 "
       "directions"},
      {"Str", "spatial", "1",
       "the shortest decay length to s over the longest; 0 when some direction does not fall to s "
       "within half the map (a lay running through it)"},
      {"Std", "spatial", "deg",
       "angle from +X (towards +Y) of the angular power spectrum's largest value: the direction "
       "the marks' waves run in, at right angles to the lay"},
      {"Sdq", "hybrid", "1", "root mean square gradient, forward differences"},
      {"Sdr", "hybrid", "%", "developed interfacial area ratio, two triangles per cell"},
      {"Sdr_gwyddion", "hybrid", "%",
       "developed interfacial area ratio as Gwyddion computes it (four triangles per cell)"},
      {"Smr", "functional", "%", "areal material ratio at height c (smr_c) above the mean plane"},
      {"Smc", "functional", "um",
       "height above the mean plane at material ratio mr (smc_mr): the inverse of Smr"},
      {"Sxp", "functional", "um", "Smc(p) - Smc(q) at p = sxp_p, q = sxp_q"},
      {"Sk", "functional", "um",
       "core height: the 40 % secant of the material ratio curve with the least gradient, its "
       "heights at 0 % and 100 %"},
      {"Spk", "functional", "um", "reduced peak height: 2 x the peaks' area above the core / Smr1"},
      {"Svk", "functional", "um",
       "reduced valley depth: 2 x the valleys' area below the core / (100 % - Smr2)"},
      {"Smr1", "functional", "%", "material ratio where the curve meets the core's top"},
      {"Smr2", "functional", "%", "material ratio where the curve meets the core's bottom"},
      {"Vm", "volume", "ml/m2", "material volume at p (volume_p)"},
      {"Vv", "volume", "ml/m2", "void volume at p (volume_p)"},
      {"Vmp", "volume", "ml/m2", "peak material volume: Vm(p)"},
      {"Vmc", "volume", "ml/m2", "core material volume: Vm(q) - Vm(p)"},
      {"Vvc", "volume", "ml/m2", "core void volume: Vv(p) - Vv(q)"},
      {"Vvv", "volume", "ml/m2", "valley void volume: Vv(q)"},
  };
  return all;
}

namespace {
const std::vector<std::string> kFamilies = {"height", "spatial", "hybrid", "functional", "volume"};

bool chosen(const std::vector<std::string>& names, const char* name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

// Whether any of `list` is among `names`.
bool any_chosen(const std::vector<std::string>& names, std::initializer_list<const char*> list) {
  return std::any_of(list.begin(), list.end(), [&](const char* n) { return chosen(names, n); });
}

// The parameters read off the material ratio curve.
constexpr std::initializer_list<const char*> kMaterialRatioFamily = {
    "Smr",  "Smc", "Sxp", "Sk",  "Spk", "Svk", "Smr1",
    "Smr2", "Vm",  "Vv",  "Vmp", "Vmc", "Vvc", "Vvv"};

std::string percent(double ratio) {
  return format_number(100 * ratio) + " %";
}
}  // namespace

std::string settings_problem(const ParameterSettings& s, std::string* key) {
  auto order = [&](double p, double q, const char* p_key, const char* q_key) {
    if (p < q) return std::string();
    *key = q_key;
    return std::string(q_key) + " " + percent(q) + " is not above " + p_key + " " + percent(p) +
           ": expected p < q";
  };
  std::string problem = order(s.volume_p, s.volume_q, "volume_p", "volume_q");
  if (problem.empty()) problem = order(s.sxp_p, s.sxp_q, "sxp_p", "sxp_q");
  return problem;
}

ParameterSettings parameter_settings(const Params& analysis) {
  ParameterSettings s;
  s.acf_threshold = analysis.number("acf_threshold");
  s.volume_p = analysis.number("volume_p") / 100, s.volume_q = analysis.number("volume_q") / 100;
  s.sxp_p = analysis.number("sxp_p") / 100, s.sxp_q = analysis.number("sxp_q") / 100;
  s.smr_c = analysis.number("smr_c") * 1e-3;
  s.smc_mr = analysis.number("smc_mr") / 100;
  std::string key;
  if (const std::string problem = settings_problem(s, &key); !problem.empty())
    throw InputError(analysis.where(key), "analysis." + key, problem);
  return s;
}

std::vector<std::string> parameter_words() {
  std::vector<std::string> w = {"default", "all"};
  w.insert(w.end(), kFamilies.begin(), kFamilies.end());
  for (const auto& p : parameter_catalogue()) w.push_back(p.name);
  return w;
}

std::vector<std::string> select_parameters(const std::vector<std::string>& words) {
  std::set<std::string> want;
  for (const auto& w : words)
    for (const auto& p : parameter_catalogue())
      if (w == "all" || w == p.name || w == p.family ||
          (w == "default" && (p.family == "height" || p.family == "hybrid")))
        want.insert(p.name);
  std::vector<std::string> names;
  for (const auto& p : parameter_catalogue())
    if (want.count(p.name)) names.push_back(p.name);
  return names;
}

namespace {
// Measured on a 2049 x 2049 map with --parameters all: 121 bytes a point (the ACF's field padded
// 1.5x each way, its spectrum and sums), about 55 more with missing points (each lag's pairs
// counted by a second transform).
constexpr double kAutocorrelationBytesPerPoint = 176;
// The material ratio curve: the valid heights sorted, and their running sums.
constexpr double kMaterialRatioBytesPerPoint = 16;
// Measured on quick.toml at a 0.3 um spacing (1001 x 995 nodes, summary.json's timing_s): the
// default parameters 0.16 us a point, with `all` (the autocorrelation's transforms) 1.06 us.
constexpr double kDefaultSecondsPerPoint = 0.16e-6;
constexpr double kAutocorrelationSecondsPerPoint = 1.06e-6;
}  // namespace

double parameter_bytes_per_point(const std::vector<std::string>& names) {
  if (any_chosen(names, {"Sal", "Str"})) return kAutocorrelationBytesPerPoint;
  if (any_chosen(names, kMaterialRatioFamily)) return kMaterialRatioBytesPerPoint;
  return 0;
}

double parameter_seconds_per_point(const std::vector<std::string>& names) {
  return any_chosen(names, {"Sal", "Str"}) ? kAutocorrelationSecondsPerPoint
                                           : kDefaultSecondsPerPoint;
}

ParameterValues compute_parameters(const Surface& surface, const std::vector<std::string>& names,
                                   const ParameterSettings& settings, const Roughness* height) {
  // Each value by name, then listed in catalogue order; what is not selected is not computed.
  std::vector<Roughness::Reported> found;
  ParameterValues out;
  auto put = [&](const char* name, double value, std::string method = "") {
    for (const auto& p : parameter_catalogue())
      if (p.name == name) found.push_back({name, value, p.unit, std::move(method)});
  };
  auto any = [&](std::initializer_list<const char*> list) { return any_chosen(names, list); };

  if (any({"Sa", "Sq", "Sp", "Sv", "Sz", "Ssk", "Sku", "Sdq", "Sdr", "Sdr_gwyddion"})) {
    const Roughness r = height ? *height : roughness(surface.map, surface.valid);
    for (auto& p : r.reported())
      if (chosen(names, p.name.c_str())) found.push_back(p);
    for (auto& u : r.undefined())
      if (chosen(names, u.first.c_str())) out.undefined.push_back(u);
  }

  throw_if_interrupted();  // between the families: each is one pass, or one FFT, over the map
  // The spatial parameters are areal: a profile (or a strip narrower than 4 nodes) has none.
  const Grid& g = surface.map.grid;
  const bool areal = g.nx >= 4 && g.ny >= 4;
  if (!areal)
    for (const char* n : {"Sal", "Str", "Std"})
      if (chosen(names, n))
        out.undefined.emplace_back(
            n, "the map is " + std::to_string(g.nx) + " x " + std::to_string(g.ny) +
                   " nodes: areal spatial parameters need 4 or more each way");
  if (areal && any({"Sal", "Str"})) {
    const Autocorrelation acf(surface);
    const AcfDecay d = acf_decay(acf, settings.acf_threshold);
    const std::string s = "s = " + format_number(settings.acf_threshold);
    for (const char* n : {"Sal", "Str"}) {
      if (!chosen(names, n)) continue;
      if (d.decays)
        put(n, std::string(n) == "Sal" ? d.Sal : d.Str, s);
      else
        out.undefined.emplace_back(n, acf.defined() ? "the autocorrelation does not fall to " + s +
                                                          " in any direction within half the map"
                                                    : "the surface has no height variation");
    }
  }
  throw_if_interrupted();
  if (areal && chosen(names, "Std")) {
    const PowerSpectrum psd(surface);
    put("Std", texture_direction(psd) * 180 / M_PI, "angular spectrum over 720 directions");
  }

  throw_if_interrupted();
  if (any(kMaterialRatioFamily)) {
    const MaterialRatioCurve curve(surface);
    const double p = settings.volume_p, q = settings.volume_q;
    const std::string at_p = "p = " + percent(p), at_pq = at_p + ", q = " + percent(q);
    // Heights in um from mm; volumes per area in ml/m2 = um^3 / um^2, also 1e3 x mm.
    put("Smr", 100 * curve.ratio(settings.smr_c),
        "c = " + format_number(settings.smr_c * 1e3) + " um above the mean plane");
    put("Smc", curve.height(settings.smc_mr) * 1e3, "mr = " + percent(settings.smc_mr));
    put("Sxp", (curve.height(settings.sxp_p) - curve.height(settings.sxp_q)) * 1e3,
        "p = " + percent(settings.sxp_p) + ", q = " + percent(settings.sxp_q));
    if (any({"Sk", "Spk", "Svk", "Smr1", "Smr2"})) {
      const MaterialRatioCurve::Core c = curve.core();
      put("Sk", c.Sk * 1e3), put("Spk", c.Spk * 1e3), put("Svk", c.Svk * 1e3);
      put("Smr1", 100 * c.Smr1), put("Smr2", 100 * c.Smr2);
    }
    put("Vm", curve.material_volume(p) * 1e3, at_p);
    put("Vv", curve.void_volume(p) * 1e3, at_p);
    put("Vmp", curve.material_volume(p) * 1e3, at_p);
    put("Vmc", (curve.material_volume(q) - curve.material_volume(p)) * 1e3, at_pq);
    put("Vvc", (curve.void_volume(p) - curve.void_volume(q)) * 1e3, at_pq);
    put("Vvv", curve.void_volume(q) * 1e3, "q = " + percent(q));
  }

  for (const auto& info : parameter_catalogue())
    for (const auto& r : found)
      if (r.name == info.name && chosen(names, r.name.c_str())) out.reported.push_back(r);
  return out;
}

}  // namespace topomill
