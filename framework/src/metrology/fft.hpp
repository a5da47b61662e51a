// Discrete Fourier transforms of real data through FFTW (double precision), unnormalised as FFTW's
// are: inverse(forward(x)) = n x. Plans are made with FFTW_ESTIMATE (no timing runs: the same
// plan, so the same bits, on every machine and run) under one process-wide lock, because FFTW's
// planner is not thread-safe; executing plans is.
#pragma once

#include <complex>
#include <cstddef>
#include <vector>

namespace topomill {

// A 2D field of ny rows of nx values, x fastest (HeightMap's layout), and its half spectrum:
// ny rows of nx / 2 + 1 coefficients (the rest follow from conjugate symmetry).
std::vector<std::complex<double>> fft_forward(const std::vector<double>& field, std::size_t nx,
                                              std::size_t ny);
std::vector<double> fft_inverse(const std::vector<std::complex<double>>& half, std::size_t nx,
                                std::size_t ny);

// Each of `rows` rows of n values transformed alone (1D): rows of n / 2 + 1 coefficients.
std::vector<std::complex<double>> fft_rows(const std::vector<double>& rows_data, std::size_t n,
                                           std::size_t rows);

// A size at least n whose only prime factors are 2, 3 and 5 (FFTW is fastest there).
std::size_t fft_size(std::size_t n);

}  // namespace topomill
