#include "rotbeam/energy.hpp"

#include "rotbeam/detail/quadratic_form.hpp"

namespace rotbeam {

EnergyTerms evaluate_energy(const ForeshorteningBeam& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                            const Eigen::Ref<const Eigen::VectorXd>& qd, ForeshorteningWorkspace& ws) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n, np = mi.pairs;
  const double L = model.length, rh = model.hub_radius, m = model.mass, w = model.omega;
  evaluate_mass(model, q, ws);

  EnergyTerms e;
  e.t2 = 0.5 * detail::quadratic_form(ws.mass, qd);

  // ∫ (qᵀISP q)² dξ = qᵀ Z (q ⊗ q).
  double* u = ws.q_pairs.data();
  for (int p = 0; p < np; ++p) {
    const int j = mi.pair_first[p], l = mi.pair_second[p];
    u[p] = (j == l ? 1.0 : 2.0) * q[j] * q[l];
  }
  double quartic_isp = 0.0;
  for (int i = 0; i < n; ++i) {
    const double* zi = ws.z.data() + static_cast<std::size_t>(i) * np;
    double s = 0.0;
    for (int p = 0; p < np; ++p) s += zi[p] * u[p];
    quartic_isp += q[i] * s;
  }
  // ∫ x² + y² dm with x = r_h + ξL − qᵀISP q/(2L), y = Sᵀq.
  const double x2 = rh * rh + rh * L + L * L / 3.0 - (rh * detail::quadratic_form(mi.isp_mean, q) + L * detail::quadratic_form(mi.isp_xi, q)) / L +
                    quartic_isp / (4.0 * L * L);
  e.spin_inertia = m * (x2 + q.squaredNorm());

  // ∫ x ẏ dm and ∫ y ẋ dm with B[i,k,j] = ∫ ISP_ik S_j.
  double qqv = 0.0, qvq = 0.0;  // Σ q_i q_k B[i,k,j] q̇_j and Σ q_i q̇_k B[i,k,j] q_j
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const double* b = mi.isp_s.data() + static_cast<std::size_t>(i * n + k) * n;
      double bv = 0.0, bq = 0.0;
      for (int j = 0; j < n; ++j) {
        bv += b[j] * qd[j];
        bq += b[j] * q[j];
      }
      qqv += q[i] * q[k] * bv;
      qvq += q[i] * qd[k] * bq;
    }
  const double x_ydot = m * ((rh * mi.s_mean + L * mi.s_xi).dot(qd) - qqv / (2.0 * L));
  const double y_xdot = -m * qvq / L;
  e.relative_momentum = x_ydot - y_xdot;

  // The switched-off rotation terms leave the Lagrangian, and with them their share of H_z = ∂T/∂ω.
  const double s0 = model.centrifugal ? 1.0 : 0.0, s1 = model.coriolis ? 1.0 : 0.0;
  e.t0 = s0 * 0.5 * w * w * e.spin_inertia;
  e.t1 = s1 * w * e.relative_momentum;
  e.angular_momentum = s0 * w * e.spin_inertia + s1 * e.relative_momentum;

  // U = ½ (EI/L³) [ Σ r_i⁴ q_i² + ∫ (qᵀ P q)²/(4L²) ].
  double quartic_p = 0.0;
  for (int p = 0; p < np; ++p) {
    const double* row = mi.p_p.data() + static_cast<std::size_t>(p) * np;
    double s = 0.0;
    for (int r = 0; r < np; ++r) s += row[r] * u[r];
    quartic_p += u[p] * s;
  }
  e.potential = 0.5 * model.bending_stiffness / (L * L * L) *
                (mi.r4.dot(q.cwiseAbs2()) + quartic_p / (4.0 * L * L));
  e.kinetic = e.t0 + e.t1 + e.t2;
  e.jacobi = e.t2 - e.t0 + e.potential;
  return e;
}

double angular_momentum_rate(const ForeshorteningBeam& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                             const Eigen::Ref<const Eigen::VectorXd>& qd,
                             const Eigen::Ref<const Eigen::VectorXd>& qdd, ForeshorteningWorkspace& ws) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n, np = mi.pairs;
  const double L = model.length, rh = model.hub_radius, m = model.mass, w = model.omega;
  // ∇J·q̇ = m [ −2 q̇ᵀ(r_h ∫ISP + L ∫ξISP) q / L + ∇Q4·q̇/(4L²) + 2 q·q̇ ], Q4 = ∫(qᵀISP q)² dξ,
  // ∇Q4 = 4 ∫ (qᵀISP q) ISP q, contracted through Z (ws.z) like the centrifugal force.
  evaluate_mass(model, q, ws);
  double* u = ws.q_pairs.data();
  for (int p = 0; p < np; ++p) {
    const int j = mi.pair_first[p], l = mi.pair_second[p];
    u[p] = (j == l ? 1.0 : 2.0) * q[j] * q[l];
  }
  double cubic_v = 0.0;  // Σ_i q̇_i ∫ (qᵀISP q)(ISP q)_i
  for (int i = 0; i < n; ++i) {
    const double* zi = ws.z.data() + static_cast<std::size_t>(i) * np;
    double s = 0.0;
    for (int p = 0; p < np; ++p) s += zi[p] * u[p];
    cubic_v += qd[i] * s;
  }
  const double grad_j_v = m * (-2.0 * (rh * detail::bilinear_form(mi.isp_mean, qd, q) +
                                       L * detail::bilinear_form(mi.isp_xi, qd, q)) / L +
                               cubic_v / (L * L) + 2.0 * q.dot(qd));
  // p(q)·q̇ = m [ (r_h s̄ + L s̄_ξ)·q̇ − B(q,q,q̇)/(2L) + B(q,q̇,q)/L ], B(a,b,c) = Σ a_i b_k c_j ∫ISP_ik S_j.
  // d/dt: B(q,q,q̇)' = 2B(q̇,q,q̇) + B(q,q,q̈);  B(q,q̇,q)' = B(q̇,q̇,q) + B(q,q̈,q) + B(q,q̇,q̇), and
  // B(q,q̇,q̇) = B(q̇,q,q̇) (ISP is symmetric).
  double b_vqv = 0.0, b_qqa = 0.0, b_vvq = 0.0, b_qaq = 0.0;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const double* b = mi.isp_s.data() + static_cast<std::size_t>(i * n + k) * n;
      double bq = 0.0, bv = 0.0, ba = 0.0;
      for (int j = 0; j < n; ++j) {
        bq += b[j] * q[j];
        bv += b[j] * qd[j];
        ba += b[j] * qdd[j];
      }
      b_vqv += qd[i] * q[k] * bv;
      b_qqa += q[i] * q[k] * ba;
      b_vvq += qd[i] * qd[k] * bq;
      b_qaq += q[i] * qdd[k] * bq;
    }
  const double dp = m * ((rh * mi.s_mean + L * mi.s_xi).dot(qdd) - (2.0 * b_vqv + b_qqa) / (2.0 * L) +
                         (b_vvq + b_qaq + b_vqv) / L);
  return (model.centrifugal ? w * grad_j_v : 0.0) + (model.coriolis ? dp : 0.0);
}

}  // namespace rotbeam
