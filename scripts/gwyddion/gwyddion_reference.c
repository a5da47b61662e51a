/* The ISO 25178-2 parameters of a Gwyddion Simple Field file as Gwyddion's own library
 * (libgwyprocess, Debian's libgwyddion20-dev) computes what it computes: scripts/gwyddion-check
 * builds this and sets its numbers beside topomill measure's. Not part of the build or of CI.
 *
 * From Gwyddion directly: Sa, Sq, Ssk, Sku (gwy_data_field_get_stats; its kurtosis is the excess,
 * 3 is added), Sp, Sv, Sz (min, max, mean), Sdr (gwy_data_field_get_surface_area), the material
 * ratio curve (gwy_data_field_cdh), the 2D ACF (gwy_data_field_area_2dacf over half the map each
 * way) and the angular spectrum (gwy_data_field_2dpsdf with a Hann window,
 * gwy_data_field_psdf_to_angular_spectrum). Gwyddion 2.62's library gives no Sal, Str or Std
 * itself: they are read from its ACF and angular spectrum here by ISO 25178-2's definitions
 * (the ACF's first fall to s along 720 rays; the spectrum's largest value), so that a difference
 * from topomill's is the ACF's or the spectrum's, not the reading's.
 *
 * Prints "name value" lines, heights in um, Sdr in %, Sal in mm, Std in deg.
 */
#include <libprocess/gwyprocess.h>
#include <libprocess/stats.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static GwyDataField* read_gsf(const char* path) {
  FILE* f = fopen(path, "rb");
  if (!f) {
    fprintf(stderr, "%s: cannot open\n", path);
    exit(2);
  }
  char line[4096];
  int xres = 0, yres = 0;
  double xreal = 0, yreal = 0;
  if (!fgets(line, sizeof line, f) || strncmp(line, "Gwyddion Simple Field 1.0", 25) != 0) {
    fprintf(stderr, "%s: not a Gwyddion Simple Field\n", path);
    exit(2);
  }
  long header_end = 0;
  for (;;) {
    int c = fgetc(f);
    if (c == EOF) exit(2);
    if (c == '\0') {
      header_end = ftell(f);
      break;
    }
    ungetc(c, f);
    if (!fgets(line, sizeof line, f)) exit(2);
    sscanf(line, "XRes = %d", &xres);
    sscanf(line, "YRes = %d", &yres);
    sscanf(line, "XReal = %lf", &xreal);
    sscanf(line, "YReal = %lf", &yreal);
  }
  /* NUL padding to a multiple of 4 bytes (one NUL at least, read above). */
  while (header_end % 4 != 0) fgetc(f), header_end++;
  if (xres <= 0 || yres <= 0 || !(xreal > 0) || !(yreal > 0)) exit(2);
  GwyDataField* field = gwy_data_field_new(xres, yres, xreal, yreal, FALSE);
  double* d = gwy_data_field_get_data(field);
  for (int k = 0; k < xres * yres; ++k) {
    float v;
    if (fread(&v, 4, 1, f) != 1) exit(2);
    d[k] = v;
  }
  fclose(f);
  gwy_data_field_invalidate(field);
  return field;
}

/* The material ratio (0..1) at height c from the cumulative height distribution cdh (fraction of
 * points at or below each of its nstats heights from min to max). */
static double ratio_at(GwyDataLine* cdh, double lo, double hi, double c) {
  const double* p = gwy_data_line_get_data(cdh);
  int n = gwy_data_line_get_res(cdh);
  double u = (c - lo) / (hi - lo) * (n - 1);
  if (u <= 0) return 1 - p[0];
  if (u >= n - 1) return 1 - p[n - 1];
  int k = (int)u;
  double t = u - k;
  return 1 - (p[k] + t * (p[k + 1] - p[k]));
}

/* Its inverse by bisection: the height at material ratio mr. */
static double height_at(GwyDataLine* cdh, double lo, double hi, double mr) {
  double a = lo, b = hi;
  for (int i = 0; i < 200; ++i) {
    double m = 0.5 * (a + b);
    if (ratio_at(cdh, lo, hi, m) > mr)
      a = m;
    else
      b = m;
  }
  return 0.5 * (a + b);
}

int main(int argc, char** argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: gwyddion_reference FILE.gsf\n");
    return 2;
  }
  gwy_process_type_init();
  GwyDataField* f = read_gsf(argv[1]);
  const int xres = gwy_data_field_get_xres(f), yres = gwy_data_field_get_yres(f);
  const double dx = gwy_data_field_get_dx(f), dy = gwy_data_field_get_dy(f);
  double avg, ra, rms, skew, kurt, lo, hi;
  gwy_data_field_get_stats(f, &avg, &ra, &rms, &skew, &kurt);
  gwy_data_field_get_min_max(f, &lo, &hi);
  printf("Sa %.10g\nSq %.10g\nSsk %.10g\nSku %.10g\n", ra * 1e6, rms * 1e6, skew, kurt + 3);
  printf("Sp %.10g\nSv %.10g\nSz %.10g\n", (hi - avg) * 1e6, (avg - lo) * 1e6, (hi - lo) * 1e6);
  const double flat = gwy_data_field_get_xreal(f) * gwy_data_field_get_yreal(f);
  printf("Sdr_gwyddion %.10g\n", (gwy_data_field_get_surface_area(f) / flat - 1) * 100);

  /* Material ratio: Smr(c = mean), Smc(10 %), Sxp(2.5 %, 50 %). */
  GwyDataLine* cdh = gwy_data_line_new(1, 1.0, FALSE);
  const int nstats = 100000;
  gwy_data_field_cdh(f, cdh, nstats);
  printf("Smr %.10g\n", 100 * ratio_at(cdh, lo, hi, avg));
  printf("Smc %.10g\n", (height_at(cdh, lo, hi, 0.10) - avg) * 1e6);
  printf("Sxp %.10g\n", (height_at(cdh, lo, hi, 0.025) - height_at(cdh, lo, hi, 0.5)) * 1e6);

  /* Heights about their mean (ISO's reference plane): Gwyddion's 2D ACF does not take the mean
   * off itself (its GUI levels first). */
  gwy_data_field_add(f, -avg);
  /* ACF over half the map each way; the zero lag at its centre (not always its largest value:
   * on a periodic surface a lag of one period, from fewer pairs, can come out a little higher). */
  GwyDataField* acf = gwy_data_field_new(1, 1, 1.0, 1.0, FALSE);
  const int hx = xres / 2, hy = yres / 2;
  gwy_data_field_area_2dacf(f, acf, 0, 0, xres, yres, hx, hy);
  const int ax = gwy_data_field_get_xres(acf), ay = gwy_data_field_get_yres(acf);
  const double* a = gwy_data_field_get_data(acf);
  const int ci = (ax - 1) / 2, cj = (ay - 1) / 2, centre = cj * ax + ci;
  const double zero = a[centre];
  const double s = 0.2;
  double fastest = INFINITY, slowest = 0;
  for (int r = 0; r < 720; ++r) {
    const double th = M_PI * r / 720, c = cos(th), sn = sin(th), step = 0.25 * fmin(dx, dy);
    double prev = 1, found = INFINITY;
    for (double d = step;; d += step) {
      const double u = ci + d * c / dx, v = cj + d * sn / dy;
      if (u < 0 || v < 0 || u > ax - 1 || v > ay - 1 || fabs(u - ci) > hx || fabs(v - cj) > hy)
        break;
      int i = (int)floor(u), j = (int)floor(v);
      if (i > ax - 2) i = ax - 2;
      if (j > ay - 2) j = ay - 2;
      const double tu = u - i, tv = v - j;
      const double val = ((1 - tv) * ((1 - tu) * a[j * ax + i] + tu * a[j * ax + i + 1]) +
                          tv * ((1 - tu) * a[(j + 1) * ax + i] + tu * a[(j + 1) * ax + i + 1])) /
                         zero;
      if (val <= s) {
        found = d - step * (val - s) / (val - prev);
        break;
      }
      prev = val;
    }
    if (found < fastest) fastest = found;
    if (found > slowest) slowest = found;
  }
  if (isfinite(fastest)) {
    printf("Sal %.10g\n", fastest * 1e3);
    printf("Str %.10g\n", isfinite(slowest) ? fastest / slowest : 0.0);
  }

  /* Texture direction from Gwyddion's angular spectrum of its Hann-windowed PSD. */
  GwyDataField* psdf = gwy_data_field_new(1, 1, 1.0, 1.0, FALSE);
  gwy_data_field_2dpsdf(f, psdf, GWY_WINDOWING_HANN, 0);
  GwyDataLine* ang = gwy_data_field_psdf_to_angular_spectrum(psdf, 720);
  const double* p = gwy_data_line_get_data(ang);
  const int n = gwy_data_line_get_res(ang);
  int best = 0;
  for (int k = 0; k < n; ++k)
    if (p[k] > p[best]) best = k;
  const double angle =
      gwy_data_line_get_offset(ang) + (best + 0.5) * gwy_data_line_get_real(ang) / n;
  printf("Std %.10g\n", fmod(fmod(angle * 180 / M_PI, 180) + 180, 180));
  return 0;
}
