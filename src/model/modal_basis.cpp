#include "rotbeam/modal_basis.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rotbeam {

double cantilever_root(int i) {
  if (i < 1) throw std::invalid_argument("cantilever_root: index must be >= 1, got " + std::to_string(i));
  // f(r) = cos r + sech r has the same roots as cos r cosh r + 1 but stays O(1) for large r.
  double r = (2.0 * i - 1.0) * M_PI / 2.0;
  for (int it = 0; it < 100; ++it) {
    const double sech = 1.0 / std::cosh(r);
    const double f = std::cos(r) + sech;
    const double df = -std::sin(r) - sech * std::tanh(r);
    const double step = f / df;
    r -= step;
    if (std::abs(step) <= 4e-16 * r) break;
  }
  return r;
}

ModalBasis::ModalBasis(int n) {
  if (n < 1 || n > kMaxElasticaModes)
    throw std::invalid_argument("number of modes must be in 1.." + std::to_string(kMaxElasticaModes) + ", got " +
                                std::to_string(n));
  root_.resize(n);
  sigma_.resize(n);
  alpha_.resize(n);
  beta_.resize(n);
  for (int i = 0; i < n; ++i) {
    const double r = cantilever_root(i + 1);
    const double em = std::exp(-r), c = std::cos(r), s = std::sin(r);
    // σ = (sinh r − sin r)/(cosh r + cos r), written with e^{−r} so that it does not overflow.
    const double den = 1.0 + 2.0 * em * c + em * em;  // 2 e^{−r}(cosh r + cos r)
    const double sigma = (1.0 - em * em - 2.0 * em * s) / den;
    root_[i] = r;
    sigma_[i] = sigma;
    alpha_[i] = (em + c + s) / den;  // ½ e^{r}(1 − σ) without cancellation
    beta_[i] = 0.5 * (1.0 + sigma);
  }
}

double ModalBasis::shape(int i, double xi, int derivative) const {
  const double r = root_[i], sg = sigma_[i];
  const double grow = alpha_[i] * std::exp(-r * (1.0 - xi));  // from cosh − σ sinh, growing part
  const double decay = beta_[i] * std::exp(-r * xi);           // from cosh − σ sinh, decaying part
  const double c = std::cos(r * xi), s = std::sin(r * xi);
  const double rk = std::pow(r, derivative);
  switch (derivative) {
    case 0: return grow + decay - c + sg * s;
    case 1: return rk * (grow - decay + s + sg * c);
    case 2: return rk * (grow + decay + c - sg * s);
    case 3: return rk * (grow - decay - s - sg * c);
    case 4: return rk * (grow + decay - c + sg * s);
    default: throw std::invalid_argument("ModalBasis::shape: derivative order must be 0..4");
  }
}

void ModalBasis::evaluate(double xi, double* s_out, double* ds_out, double* d2s_out) const {
  const int n = size();
  for (int i = 0; i < n; ++i) {
    const double r = root_[i], sg = sigma_[i];
    const double grow = alpha_[i] * std::exp(-r * (1.0 - xi));
    const double decay = beta_[i] * std::exp(-r * xi);
    const double c = std::cos(r * xi), s = std::sin(r * xi);
    if (s_out) s_out[i] = grow + decay - c + sg * s;
    if (ds_out) ds_out[i] = r * (grow - decay + s + sg * c);
    if (d2s_out) d2s_out[i] = r * r * (grow + decay + c - sg * s);
  }
}

}  // namespace rotbeam
