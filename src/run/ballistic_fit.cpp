// Ballistic limit: the Lambert-Jonas residual-velocity curve and its least-squares fit
// (Levenberg-Marquardt on a, p, v_bl, with standard uncertainties from the covariance).
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>

#include "krug/run/ballistic.hpp"

namespace krug::run {

namespace {

constexpr double nan = std::numeric_limits<double>::quiet_NaN();

// A k x k system (k <= 3) by Gaussian elimination with partial pivoting; false when singular.
using Matrix3 = std::array<std::array<double, 3>, 3>;
using Vector3 = std::array<double, 3>;
bool solve(Matrix3 m, Vector3 b, int k, Vector3& x) {
  for (int c = 0; c < k; ++c) {
    int pivot = c;
    for (int r = c + 1; r < k; ++r) {
      if (std::abs(m[r][c]) > std::abs(m[pivot][c])) pivot = r;
    }
    if (!(std::abs(m[pivot][c]) > 0.0)) return false;
    std::swap(m[c], m[pivot]);
    std::swap(b[c], b[pivot]);
    for (int r = c + 1; r < k; ++r) {
      const double f = m[r][c] / m[c][c];
      for (int q = c; q < k; ++q) m[r][q] -= f * m[c][q];
      b[r] -= f * b[c];
    }
  }
  for (int r = k - 1; r >= 0; --r) {
    double sum = b[r];
    for (int q = r + 1; q < k; ++q) sum -= m[r][q] * x[q];
    x[r] = sum / m[r][r];
  }
  return true;
}

}  // namespace

double lambert_jonas(double v_i, double a, double p, double v_bl) {
  if (v_i <= v_bl) return 0.0;
  return a * std::pow(std::pow(v_i, p) - std::pow(v_bl, p), 1.0 / p);
}

CurveFit fit_lambert_jonas(const std::vector<double>& v_i, const std::vector<double>& v_r, const CurveFitOptions& options) {
  CurveFit fit;
  fit.velocities = v_i;
  const std::size_t n = v_i.size();
  fit.points = static_cast<int>(n);
  const std::array<bool, 3> free = {options.free_a, options.free_p, options.free_v_bl};
  const int k = static_cast<int>(std::count(free.begin(), free.end(), true));
  fit.free_parameters = k;
  fit.a = options.a;
  fit.p = options.p;
  fit.v_bl = options.v_bl;
  if (v_r.size() != n) throw std::invalid_argument("fit_lambert_jonas: v_i and v_r differ in length");
  if (n < static_cast<std::size_t>(std::max(k, 1))) {
    fit.note = fmt::format("{} points for {} free parameters", n, k);
    return fit;
  }
  // Work in units of the largest speed, so that v^p stays near 1.
  const double scale = *std::max_element(v_i.begin(), v_i.end());
  const double lowest = *std::min_element(v_i.begin(), v_i.end());
  if (!(lowest > 0.0)) {
    fit.note = "a speed that is not positive";
    return fit;
  }
  std::vector<double> x(n), y(n);
  for (std::size_t i = 0; i < n; ++i) {
    x[i] = v_i[i] / scale;
    y[i] = v_r[i] / scale;
  }
  const double x_min = lowest / scale;
  std::array<double, 3> theta = {options.a, options.p, std::min(options.v_bl / scale, x_min * (1.0 - 1e-6))};
  auto feasible = [&](const std::array<double, 3>& t) {
    return t[0] > 0.0 && t[1] >= 0.5 && t[1] <= 50.0 && t[2] >= 0.0 && t[2] < x_min;
  };
  if (!feasible(theta)) {
    theta[2] = std::clamp(theta[2], 0.0, 0.999 * x_min);
    theta[1] = std::clamp(theta[1], 0.5, 50.0);
    if (!(theta[0] > 0.0)) theta[0] = 1.0;
  }
  // The start of a: linear least squares given p and v_bl.
  if (free[0]) {
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double g = lambert_jonas(x[i], 1.0, theta[1], theta[2]);
      num += g * y[i];
      den += g * g;
    }
    if (den > 0.0 && num > 0.0) theta[0] = num / den;
  }
  auto residuals = [&](const std::array<double, 3>& t, std::vector<double>& r) {
    r.resize(n);
    double sum = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      r[i] = y[i] - lambert_jonas(x[i], t[0], t[1], t[2]);
      sum += r[i] * r[i];
    }
    return sum;
  };
  // J^T J and J^T r in the free parameters (J: the model's derivatives, not the residual's).
  auto normal_equations = [&](const std::array<double, 3>& t, const std::vector<double>& r, Matrix3& A, Vector3& g) {
    A = Matrix3{};
    g = Vector3{};
    for (std::size_t i = 0; i < n; ++i) {
      const double a = t[0], p = t[1], b = t[2];
      const double u = std::pow(x[i], p) - std::pow(b, p);
      const double f = a * std::pow(u, 1.0 / p);
      const double d_a = std::pow(u, 1.0 / p);
      const double b_log = b > 0.0 ? std::pow(b, p) * std::log(b) : 0.0;
      const double d_p = f * (-std::log(u) / (p * p) + (std::pow(x[i], p) * std::log(x[i]) - b_log) / (p * u));
      const double d_b = b > 0.0 ? -a * std::pow(b, p - 1.0) * std::pow(u, 1.0 / p - 1.0) : 0.0;
      const std::array<double, 3> all = {d_a, d_p, d_b};
      Vector3 d{};
      int c = 0;
      for (std::size_t q = 0; q < 3; ++q) {
        if (free[q]) d[static_cast<std::size_t>(c++)] = all[q];
      }
      for (int q = 0; q < k; ++q) {
        g[q] += d[q] * r[i];
        for (int s = 0; s < k; ++s) A[q][s] += d[q] * d[s];
      }
    }
  };
  std::vector<double> r;
  double cost = residuals(theta, r);
  double lambda = 1e-3;
  bool converged = false;
  int iteration = 0;
  Matrix3 A;
  Vector3 g;
  for (; iteration < options.max_iterations && k > 0; ++iteration) {
    normal_equations(theta, r, A, g);
    bool accepted = false;
    for (int attempt = 0; attempt < 40; ++attempt) {
      Matrix3 M = A;
      for (int q = 0; q < k; ++q) M[q][q] += lambda * std::max(A[q][q], 1e-12);
      Vector3 delta{};
      std::array<double, 3> trial = theta;
      double step = 0.0;
      if (solve(M, g, k, delta)) {
        int c = 0;
        for (std::size_t q = 0; q < 3; ++q) {
          if (free[q]) {
            step += delta[static_cast<std::size_t>(c)] * delta[static_cast<std::size_t>(c)];
            trial[q] += delta[static_cast<std::size_t>(c++)];
          }
        }
      }
      std::vector<double> r_trial;
      const double cost_trial = step > 0.0 && feasible(trial) ? residuals(trial, r_trial) : std::numeric_limits<double>::infinity();
      if (std::isfinite(cost_trial) && cost_trial <= cost) {
        const double change = cost - cost_trial;
        theta = trial;
        r = r_trial;
        cost = cost_trial;
        lambda = std::max(lambda / 10.0, 1e-12);
        accepted = true;
        if (change <= 1e-14 * std::max(cost, 1e-300) || std::sqrt(step) < 1e-12) converged = true;
        break;
      }
      lambda *= 10.0;
      if (lambda > 1e16) break;
    }
    if (!accepted) {  // no step lowers the cost: a minimum (within the bounds)
      converged = true;
      break;
    }
    if (converged) break;
  }
  if (k == 0) converged = true;
  fit.iterations = iteration;
  fit.a = theta[0];
  fit.p = theta[1];
  fit.v_bl = theta[2] * scale;
  fit.residuals.resize(n);
  for (std::size_t i = 0; i < n; ++i) fit.residuals[i] = r[i] * scale;
  fit.rms = std::sqrt(cost / static_cast<double>(n)) * scale;
  if (!converged) {
    fit.note = fmt::format("did not converge in {} iterations", options.max_iterations);
    return fit;
  }
  // A minimum on a bound (v_bl at the lowest speed, p at 0.5 or 50) is no fit: the points do not
  // determine the parameter there, and the linearised uncertainties would be meaningless.
  if ((free[2] && theta[2] >= x_min * (1.0 - 1e-6)) || (free[1] && (theta[1] <= 0.5 + 1e-9 || theta[1] >= 50.0 - 1e-9))) {
    fit.note = fmt::format("the minimum lies on a bound (v_bl = {:.2f} m/s, p = {:.3g}): the points do not determine the "
                           "curve",
                           fit.v_bl, fit.p);
    return fit;
  }
  fit.valid = true;
  const std::array<double, 3> unit = {1.0, 1.0, scale};  // back to m/s for v_bl
  for (auto& row : fit.covariance) row.fill(0.0);
  if (static_cast<int>(n) > k && k > 0) {
    normal_equations(theta, r, A, g);
    const double s2 = cost / static_cast<double>(static_cast<int>(n) - k);
    Matrix3 inverse{};
    for (int col = 0; col < k; ++col) {
      Vector3 e{}, column{};
      e[static_cast<std::size_t>(col)] = 1.0;
      if (!solve(A, e, k, column)) {
        fit.valid = false;
        fit.note = "singular normal equations: the parameters are not determined by these points";
        return fit;
      }
      for (int row = 0; row < k; ++row) inverse[static_cast<std::size_t>(row)][static_cast<std::size_t>(col)] = column[static_cast<std::size_t>(row)];
    }
    std::size_t cq = 0;
    for (std::size_t q = 0; q < 3; ++q) {
      if (!free[q]) continue;
      std::size_t cs = 0;
      for (std::size_t s = 0; s < 3; ++s) {
        if (!free[s]) continue;
        fit.covariance[q][s] = s2 * inverse[cq][cs] * unit[q] * unit[s];
        ++cs;
      }
      ++cq;
    }
  } else if (k > 0) {
    for (auto& row : fit.covariance) row.fill(nan);
    fit.note = "as many points as free parameters: no uncertainties";
  }
  fit.sigma_a = free[0] ? std::sqrt(fit.covariance[0][0]) : 0.0;
  fit.sigma_p = free[1] ? std::sqrt(fit.covariance[1][1]) : 0.0;
  fit.sigma_v_bl = free[2] ? std::sqrt(fit.covariance[2][2]) : 0.0;
  return fit;
}

}  // namespace krug::run
