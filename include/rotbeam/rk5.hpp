// Butcher's fifth-order, six-stage explicit Runge–Kutta method, exactly as in the thesis's
// Appendix B (uncODE.m), for the second-order system q̇ = v, v̇ = a(t, q, v):
//
//   c = (0, 1/4, 1/4, 1/2, 3/4, 1)
//   a21 = 1/4
//   a31 = 1/8,  a32 = 1/8
//   a42 = −1/2, a43 = 1
//   a51 = 3/16, a54 = 9/16
//   a61 = −3/7, a62 = 2/7, a63 = 12/7, a64 = −12/7, a65 = 8/7
//   b  = (7, 0, 32, 12, 32, 7)/90
//
// Fixed step, no error estimate. Stage storage is owned by the stepper (no allocation per step).
#pragma once

#include <Eigen/Core>
#include <array>

namespace rotbeam {

struct ButcherRk5 {
  static constexpr int stages = 6;
  static constexpr std::array<double, 6> c{0.0, 0.25, 0.25, 0.5, 0.75, 1.0};
  static constexpr double a[6][5] = {
      {0, 0, 0, 0, 0},
      {0.25, 0, 0, 0, 0},
      {0.125, 0.125, 0, 0, 0},
      {0, -0.5, 1.0, 0, 0},
      {3.0 / 16.0, 0, 0, 9.0 / 16.0, 0},
      {-3.0 / 7.0, 2.0 / 7.0, 12.0 / 7.0, -12.0 / 7.0, 8.0 / 7.0}};
  static constexpr std::array<double, 6> b{7.0 / 90.0, 0.0, 32.0 / 90.0, 12.0 / 90.0, 32.0 / 90.0, 7.0 / 90.0};
};

class Rk5Stepper {
public:
  explicit Rk5Stepper(int n) : stage_q_(n), stage_v_(n) {
    for (int s = 0; s < ButcherRk5::stages; ++s) {
      kq_[s].resize(n);
      kv_[s].resize(n);
    }
  }

  /// One step of size h from (t, q, v) into (q_out, v_out); `accel(t, q, v, a_out)` fills
  /// a_out = q̈. q_out/v_out may alias q/v. Returns the number of acceleration evaluations (6).
  template <class Acceleration>
  int step(Acceleration&& accel, double t, const Eigen::VectorXd& q, const Eigen::VectorXd& v, double h,
           Eigen::VectorXd& q_out, Eigen::VectorXd& v_out) {
    for (int s = 0; s < ButcherRk5::stages; ++s) {
      stage_q_ = q;
      stage_v_ = v;
      for (int j = 0; j < s; ++j) {
        const double aij = ButcherRk5::a[s][j];
        if (aij == 0.0) continue;
        stage_q_ += (h * aij) * kq_[j];
        stage_v_ += (h * aij) * kv_[j];
      }
      kq_[s] = stage_v_;
      accel(t + ButcherRk5::c[s] * h, stage_q_, stage_v_, kv_[s]);
    }
    for (int s = 0; s < ButcherRk5::stages; ++s) {
      const double bs = ButcherRk5::b[s];
      if (bs == 0.0) continue;
      if (s == 0) {
        q_out = q + (h * bs) * kq_[0];
        v_out = v + (h * bs) * kv_[0];
      } else {
        q_out += (h * bs) * kq_[s];
        v_out += (h * bs) * kv_[s];
      }
    }
    return ButcherRk5::stages;
  }

  /// h Σ b_s f(v_s) over the stage velocities v_s of the last step: the same RK5 quadrature of a
  /// quantity f(q̇) as if ∫f dt were integrated with the state (used for the damping work).
  template <class F>
  double stage_quadrature(F&& f, double h) const {
    double sum = 0.0;
    for (int s = 0; s < ButcherRk5::stages; ++s)
      if (ButcherRk5::b[s] != 0.0) sum += ButcherRk5::b[s] * f(kq_[s]);
    return h * sum;
  }

private:
  std::array<Eigen::VectorXd, ButcherRk5::stages> kq_, kv_;
  Eigen::VectorXd stage_q_, stage_v_;
};

}  // namespace rotbeam
