#include "rotbeam/dynamics.hpp"

namespace rotbeam {

Workspace::Workspace(int size)
    : n(size),
      mass(size, size),
      mass_llt(size),
      gyroscopic(size),
      foreshortening(size),
      centrifugal(size),
      bending(size),
      psi(size),
      z(static_cast<std::size_t>(size) * size * (size + 1) / 2),
      q_pairs(size * (size + 1) / 2),
      v_pairs(size * (size + 1) / 2),
      p_contract(size * (size + 1) / 2),
      isp_cubic(size),
      scratch(size),
      scratch2(size) {}

namespace {

// u_p = a_j a_l for the packed pair p = {j, l}, doubled off the diagonal, so that
// Σ_{j,l} T_{jl} a_j a_l = Σ_p T_p u_p for a symmetric T.
void packed_outer(const ModalIntegrals& mi, const double* a, double* u) {
  for (int p = 0; p < mi.pairs; ++p) {
    const int j = mi.pair_first[p], l = mi.pair_second[p];
    u[p] = (j == l ? 1.0 : 2.0) * a[j] * a[l];
  }
}

}  // namespace

void evaluate_mass(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q, Workspace& ws) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n, np = mi.pairs;
  const double* qv = q.data();
  // Z[i][p] = Σ_k q_k ∫ ISP_ik ISP_p  (the only O(n⁴) contraction).
  double* z = ws.z.data();
  std::fill(ws.z.begin(), ws.z.end(), 0.0);
  for (int i = 0; i < n; ++i) {
    double* zi = z + static_cast<std::size_t>(i) * np;
    for (int k = 0; k < n; ++k) {
      const double qk = qv[k];
      const double* a = mi.isp_isp.data() + static_cast<std::size_t>(i * n + k) * np;
      for (int p = 0; p < np; ++p) zi[p] += qk * a[p];
    }
  }
  // M_ij = m δ_ij + (ρA/L) Σ_l Z[i][(j,l)] q_l   (lower triangle, mirrored).
  const double c1 = model.mass_per_length / model.length;
  for (int i = 0; i < n; ++i) {
    const double* zi = z + static_cast<std::size_t>(i) * np;
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (int l = 0; l < n; ++l) sum += zi[mi.pair(j, l)] * qv[l];
      const double mij = c1 * sum + (i == j ? model.mass : 0.0);
      ws.mass(i, j) = mij;
      ws.mass(j, i) = mij;
    }
  }
}

void evaluate_dynamics(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& qd, Workspace& ws) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n, np = mi.pairs;
  evaluate_mass(model, q, ws);
  ws.mass_llt.compute(ws.mass);

  const double* qv = q.data();
  const double* vv = qd.data();
  packed_outer(mi, qv, ws.q_pairs.data());
  packed_outer(mi, vv, ws.v_pairs.data());

  // ∫ ISP q (qᵀ ISP q) and ∫ ISP q (q̇ᵀ ISP q̇) from Z.
  const double* z = ws.z.data();
  for (int i = 0; i < n; ++i) {
    const double* zi = z + static_cast<std::size_t>(i) * np;
    double cubic = 0.0, fore = 0.0;
    for (int p = 0; p < np; ++p) {
      cubic += zi[p] * ws.q_pairs[p];
      fore += zi[p] * ws.v_pairs[p];
    }
    ws.isp_cubic[i] = cubic;
    ws.foreshortening[i] = fore;
  }
  const double c1 = model.mass_per_length / model.length;
  ws.foreshortening *= c1;  // D(q,q̇) q̇ = (ρA/L) ∫ ISP q (q̇ᵀ ISP q̇)

  // 2ω G(q) q̇ with G_ij = ρA Σ_k q_k (∫ISP_ik S_j − ∫ISP_jk S_i).
  ws.gyroscopic.setZero();
  const double* b = mi.isp_s.data();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const double* bik = b + static_cast<std::size_t>(i * n + k) * n;
      double forward = 0.0;
      for (int j = 0; j < n; ++j) forward += bik[j] * vv[j];
      ws.gyroscopic[i] += qv[k] * forward;                   // Σ_kj B[i,k,j] q_k q̇_j
      const double back = vv[i] * qv[k];
      for (int j = 0; j < n; ++j) ws.gyroscopic[j] -= back * bik[j];  // −Σ_ik B[i,k,j] q̇_i q_k
    }
  ws.gyroscopic *= 2.0 * model.omega * model.mass_per_length;

  // K_ω q = m ω² [ (r_h/L) ∫ISP q + ∫ξ ISP q − ∫ISP q (qᵀISP q)/(2L²) − q ].
  const double L = model.length;
  ws.centrifugal.noalias() = (model.hub_radius / L) * (mi.isp_mean * q);
  ws.centrifugal.noalias() += mi.isp_xi * q;
  ws.centrifugal -= ws.isp_cubic / (2.0 * L * L);
  ws.centrifugal -= q;
  ws.centrifugal *= model.mass * model.omega * model.omega;

  // K_b q = (EI/L³) [ r⁴ ⊙ q + ∫ P q (qᵀ P q)/(2L²) ].
  const double* pp = mi.p_p.data();
  for (int p = 0; p < np; ++p) {
    const double* row = pp + static_cast<std::size_t>(p) * np;
    double sum = 0.0;
    for (int r = 0; r < np; ++r) sum += row[r] * ws.q_pairs[r];
    ws.p_contract[p] = sum;
  }
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += ws.p_contract[mi.pair(i, j)] * qv[j];
    ws.bending[i] = mi.r4[i] * qv[i] + sum / (2.0 * L * L);
  }
  ws.bending *= model.bending_stiffness / (L * L * L);

  ws.psi = ws.gyroscopic + ws.foreshortening + ws.centrifugal + ws.bending;
}

void acceleration(const Model& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                  const Eigen::Ref<const Eigen::VectorXd>& qd, const Eigen::VectorXd* generalized_force,
                  Workspace& ws, Eigen::Ref<Eigen::VectorXd> qdd) {
  evaluate_dynamics(model, q, qd, ws);
  if (generalized_force)
    qdd = *generalized_force - ws.psi;
  else
    qdd = -ws.psi;
  ws.mass_llt.solveInPlace(qdd);
}

Eigen::MatrixXd linear_stiffness(const Model& model) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n;
  const double L = model.length;
  Eigen::MatrixXd k = model.mass * model.omega * model.omega *
                      ((model.hub_radius / L) * mi.isp_mean + mi.isp_xi - Eigen::MatrixXd::Identity(n, n));
  k.diagonal() += (model.bending_stiffness / (L * L * L)) * mi.r4;
  return 0.5 * (k + k.transpose());
}

}  // namespace rotbeam
