#pragma once
// FFTW 3 for the renderer (private to framework/src/render): owned buffers, plans made with FFTW_ESTIMATE (the
// same plan, hence the same rounding, on every run: FFTW_MEASURE would choose by timing and could change the
// last bits of an image between runs) under one mutex (the planner is not thread-safe; execution is).
#include <fftw3.h>

#include <complex>
#include <cstddef>
#include <memory>

namespace radchain::render::detail {

struct FftwFree {
  void operator()(void* p) const { fftw_free(p); }
};
using RealBuffer = std::unique_ptr<double[], FftwFree>;
using ComplexBuffer = std::unique_ptr<fftw_complex[], FftwFree>;
RealBuffer real_buffer(std::size_t count);
ComplexBuffer complex_buffer(std::size_t count);

class Plan {
 public:
  Plan() = default;
  Plan(const Plan&) = delete;
  Plan& operator=(const Plan&) = delete;
  Plan(Plan&& other) noexcept : plan_(other.plan_) { other.plan_ = nullptr; }
  ~Plan();
  // 2-D real → half complex (rows × cols real in, rows × (cols/2 + 1) complex out) and back (unnormalised).
  static Plan r2c_2d(int rows, int cols, double* in, fftw_complex* out);
  static Plan c2r_2d(int rows, int cols, fftw_complex* in, double* out);
  static Plan r2c_1d(int n, double* in, fftw_complex* out);
  void execute() const { fftw_execute(plan_); }

 private:
  explicit Plan(fftw_plan plan) : plan_(plan) {}
  fftw_plan plan_ = nullptr;
};

// The smallest size ≥ n whose only prime factors are 2, 3, 5 and 7 (FFTW's fast codelets).
int fft_friendly_size(int n);

}  // namespace radchain::render::detail
