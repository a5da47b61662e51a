#include "metrology/fft.hpp"

#include <fftw3.h>

#include <mutex>
#include <stdexcept>

#include "topomill/interrupt.hpp"

namespace topomill {

namespace {
std::mutex& planner_lock() {
  static std::mutex m;
  return m;
}

// Owns a plan; destroyed under the lock too (fftw_destroy_plan touches the planner's state).
struct Plan {
  fftw_plan plan;
  explicit Plan(fftw_plan p) : plan(p) {
    if (!plan) throw std::runtime_error("FFTW could not make a plan");
  }
  ~Plan() {
    std::lock_guard<std::mutex> hold(planner_lock());
    fftw_destroy_plan(plan);
  }
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;
};

static_assert(sizeof(std::complex<double>) == sizeof(fftw_complex),
              "std::complex<double> is laid out as fftw_complex");
}  // namespace

std::vector<std::complex<double>> fft_forward(const std::vector<double>& field, std::size_t nx,
                                              std::size_t ny) {
  if (field.size() != nx * ny) throw std::invalid_argument("fft_forward: size is not nx ny");
  throw_if_interrupted();         // between transforms: one is not interrupted (FFTW has no hook)
  std::vector<double> in(field);  // the planner takes a writable array
  std::vector<std::complex<double>> out(ny * (nx / 2 + 1));
  fftw_plan p;
  {
    std::lock_guard<std::mutex> hold(planner_lock());
    p = fftw_plan_dft_r2c_2d(static_cast<int>(ny), static_cast<int>(nx), in.data(),
                             reinterpret_cast<fftw_complex*>(out.data()), FFTW_ESTIMATE);
  }
  const Plan plan(p);
  fftw_execute(plan.plan);
  return out;
}

std::vector<double> fft_inverse(const std::vector<std::complex<double>>& half, std::size_t nx,
                                std::size_t ny) {
  if (half.size() != ny * (nx / 2 + 1))
    throw std::invalid_argument("fft_inverse: size is not ny (nx / 2 + 1)");
  throw_if_interrupted();
  std::vector<std::complex<double>> in(half);  // the c2r transform overwrites its input
  std::vector<double> out(nx * ny);
  fftw_plan p;
  {
    std::lock_guard<std::mutex> hold(planner_lock());
    p = fftw_plan_dft_c2r_2d(static_cast<int>(ny), static_cast<int>(nx),
                             reinterpret_cast<fftw_complex*>(in.data()), out.data(), FFTW_ESTIMATE);
  }
  const Plan plan(p);
  fftw_execute(plan.plan);
  return out;
}

std::vector<std::complex<double>> fft_rows(const std::vector<double>& rows_data, std::size_t n,
                                           std::size_t rows) {
  if (rows_data.size() != n * rows) throw std::invalid_argument("fft_rows: size is not n rows");
  throw_if_interrupted();
  std::vector<double> in(rows_data);
  const std::size_t m = n / 2 + 1;
  std::vector<std::complex<double>> out(rows * m);
  const int len = static_cast<int>(n);
  fftw_plan p;
  {
    std::lock_guard<std::mutex> hold(planner_lock());
    p = fftw_plan_many_dft_r2c(1, &len, static_cast<int>(rows), in.data(), nullptr, 1,
                               static_cast<int>(n), reinterpret_cast<fftw_complex*>(out.data()),
                               nullptr, 1, static_cast<int>(m), FFTW_ESTIMATE);
  }
  const Plan plan(p);
  fftw_execute(plan.plan);
  return out;
}

std::size_t fft_size(std::size_t n) {
  for (std::size_t m = std::max<std::size_t>(n, 1);; ++m) {
    std::size_t r = m;
    for (std::size_t f : {2, 3, 5})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

}  // namespace topomill
