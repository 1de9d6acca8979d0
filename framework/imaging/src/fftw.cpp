#include "fftw.hpp"

#include <mutex>
#include <new>
#include <stdexcept>

namespace radchain::render::detail {

namespace {
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}
}  // namespace

RealBuffer real_buffer(std::size_t count) {
  auto* p = fftw_alloc_real(count);
  if (!p) throw std::bad_alloc();
  return RealBuffer(p);
}

ComplexBuffer complex_buffer(std::size_t count) {
  auto* p = fftw_alloc_complex(count);
  if (!p) throw std::bad_alloc();
  return ComplexBuffer(p);
}

Plan::~Plan() {
  if (!plan_) return;
  std::lock_guard lock(planner_mutex());
  fftw_destroy_plan(plan_);
}

Plan Plan::r2c_2d(int rows, int cols, double* in, fftw_complex* out) {
  std::lock_guard lock(planner_mutex());
  fftw_plan p = fftw_plan_dft_r2c_2d(rows, cols, in, out, FFTW_ESTIMATE);
  if (!p) throw std::runtime_error("FFTW could not plan a real-to-complex transform");
  return Plan(p);
}

Plan Plan::c2r_2d(int rows, int cols, fftw_complex* in, double* out) {
  std::lock_guard lock(planner_mutex());
  fftw_plan p = fftw_plan_dft_c2r_2d(rows, cols, in, out, FFTW_ESTIMATE);
  if (!p) throw std::runtime_error("FFTW could not plan a complex-to-real transform");
  return Plan(p);
}

Plan Plan::r2c_1d(int n, double* in, fftw_complex* out) {
  std::lock_guard lock(planner_mutex());
  fftw_plan p = fftw_plan_dft_r2c_1d(n, in, out, FFTW_ESTIMATE);
  if (!p) throw std::runtime_error("FFTW could not plan a real-to-complex transform");
  return Plan(p);
}

int fft_friendly_size(int n) {
  for (int m = n < 1 ? 1 : n;; ++m) {
    int r = m;
    for (int f : {2, 3, 5, 7})
      while (r % f == 0) r /= f;
    if (r == 1) return m;
  }
}

}  // namespace radchain::render::detail
