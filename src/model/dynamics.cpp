#include "rotbeam/dynamics.hpp"

#include <type_traits>
#include <utility>

namespace rotbeam {

ForeshorteningWorkspace::ForeshorteningWorkspace(int size)
    : BeamWorkspace(size),
      gyroscopic(size),
      foreshortening(size),
      centrifugal(size),
      bending(size),
      damping(Eigen::VectorXd::Zero(size)),
      z(static_cast<std::size_t>(size) * size * (size + 1) / 2),
      q_pairs(size * (size + 1) / 2),
      v_pairs(size * (size + 1) / 2),
      p_contract(size * (size + 1) / 2),
      isp_cubic(size),
      dpsi_dq(size, size),
      dpsi_dv(size, size),
      pair_scratch(size * (size + 1) / 2),
      square_scratch(size * size) {}

namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

// The contractions below are written once as templates on the mode count: N > 0 fixes n at compile
// time (the loops unroll; used for n ≤ 8, the common case), N = 0 takes n from the model.
// Packed pair index of {j, l}, j ≤ l, in row-major upper-triangle order.
template <int N>
inline int packed(int n, int j, int l) {
  if (j > l) std::swap(j, l);
  return j * n - j * (j - 1) / 2 + (l - j);
}

// u_p = a_j a_l for the packed pair p = {j, l}, doubled off the diagonal, so that
// Σ_{j,l} T_{jl} a_j a_l = Σ_p T_p u_p for a symmetric T.
template <int N>
void packed_outer(int n_runtime, const double* a, double* u) {
  const int n = N > 0 ? N : n_runtime;
  int p = 0;
  for (int j = 0; j < n; ++j) {
    u[p++] = a[j] * a[j];
    for (int l = j + 1; l < n; ++l) u[p++] = 2.0 * a[j] * a[l];
  }
}

template <int N>
void mass_kernel(const ForeshorteningBeam& model, const double* qv, ForeshorteningWorkspace& ws) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = N > 0 ? N : mi.n;
  const int np = n * (n + 1) / 2;
  // Z[i][p] = Σ_k q_k ∫ ISP_ik ISP_p  (the only O(n⁴) contraction).
  double* z = ws.z.data();
  for (int i = 0; i < n; ++i) {
    double* zi = z + static_cast<std::size_t>(i) * np;
    const double* a = mi.isp_isp.data() + static_cast<std::size_t>(i * n) * np;
    for (int p = 0; p < np; ++p) zi[p] = qv[0] * a[p];
    for (int k = 1; k < n; ++k) {
      const double qk = qv[k];
      const double* ak = a + static_cast<std::size_t>(k) * np;
      for (int p = 0; p < np; ++p) zi[p] += qk * ak[p];
    }
  }
  // M_ij = m δ_ij + (ρA/L) Σ_l Z[i][(j,l)] q_l   (lower triangle, mirrored).
  const double c1 = model.mass_per_length / model.length;
  for (int i = 0; i < n; ++i) {
    const double* zi = z + static_cast<std::size_t>(i) * np;
    for (int j = 0; j <= i; ++j) {
      double sum = 0.0;
      for (int l = 0; l < n; ++l) sum += zi[packed<N>(n, j, l)] * qv[l];
      const double mij = c1 * sum + (i == j ? model.mass : 0.0);
      ws.mass(i, j) = mij;
      ws.mass(j, i) = mij;
    }
  }
}

template <int N>
void force_kernel(const ForeshorteningBeam& model, const double* qv, const double* vv, ForeshorteningWorkspace& ws) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = N > 0 ? N : mi.n;
  const int np = n * (n + 1) / 2;
  packed_outer<N>(n, qv, ws.q_pairs.data());
  packed_outer<N>(n, vv, ws.v_pairs.data());
  const double* qp = ws.q_pairs.data();
  const double* vp = ws.v_pairs.data();

  // ∫ ISP q (qᵀ ISP q) and ∫ ISP q (q̇ᵀ ISP q̇) from Z. With n from the model (n > 8) as Eigen's
  // matrix–vector products: a plain dot-product loop is one chain of dependent additions (the
  // compiler may not reorder them), which at n = 20 bounds it by the adder's latency.
  const double* z = ws.z.data();
  const double c1 = model.mass_per_length / model.length;
  if constexpr (N == 0) {
    const Eigen::Map<const RowMatrix> zm(z, n, np);
    ws.isp_cubic.noalias() = zm * ws.q_pairs;
    ws.foreshortening.noalias() = c1 * (zm * ws.v_pairs);  // D(q,q̇) q̇ = (ρA/L) ∫ ISP q (q̇ᵀ ISP q̇)
  } else {
    for (int i = 0; i < n; ++i) {
      const double* zi = z + static_cast<std::size_t>(i) * np;
      double cubic = 0.0, fore = 0.0;
      for (int p = 0; p < np; ++p) {
        cubic += zi[p] * qp[p];
        fore += zi[p] * vp[p];
      }
      ws.isp_cubic[i] = cubic;
      ws.foreshortening[i] = c1 * fore;  // D(q,q̇) q̇ = (ρA/L) ∫ ISP q (q̇ᵀ ISP q̇)
    }
  }

  // 2ω G(q) q̇ with G_ij = ρA Σ_k q_k (∫ISP_ik S_j − ∫ISP_jk S_i).
  double* gyro = ws.gyroscopic.data();
  for (int i = 0; i < n; ++i) gyro[i] = 0.0;
  const double* b = mi.isp_s.data();
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      const double* bik = b + static_cast<std::size_t>(i * n + k) * n;
      double forward = 0.0;
      for (int j = 0; j < n; ++j) forward += bik[j] * vv[j];
      gyro[i] += qv[k] * forward;                   // Σ_kj B[i,k,j] q_k q̇_j
      const double back = vv[i] * qv[k];
      for (int j = 0; j < n; ++j) gyro[j] -= back * bik[j];  // −Σ_ik B[i,k,j] q̇_i q_k
    }
  const double g2 = model.coriolis ? 2.0 * model.omega * model.mass_per_length : 0.0;
  for (int i = 0; i < n; ++i) gyro[i] *= g2;

  // K_ω q = m ω² [ (r_h/L) ∫ISP q + ∫ξ ISP q − ∫ISP q (qᵀISP q)/(2L²) − q ].
  const double L = model.length;
  const double rh_l = model.hub_radius / L, cw = model.centrifugal ? model.mass * model.omega * model.omega : 0.0;
  const double* im = mi.isp_mean.data();  // column-major, symmetric
  const double* ix = mi.isp_xi.data();
  for (int i = 0; i < n; ++i) {
    double lin = 0.0;
    for (int j = 0; j < n; ++j) lin += (rh_l * im[j * n + i] + ix[j * n + i]) * qv[j];
    ws.centrifugal[i] = cw * (lin - ws.isp_cubic[i] / (2.0 * L * L) - qv[i]);
  }

  // K_b q = (EI/L³) [ r⁴ ⊙ q + ∫ P q (qᵀ P q)/(2L²) ].
  const double* pp = mi.p_p.data();
  if constexpr (N == 0) {
    ws.p_contract.noalias() = Eigen::Map<const RowMatrix>(pp, np, np) * ws.q_pairs;
  } else {
    for (int p = 0; p < np; ++p) {
      const double* row = pp + static_cast<std::size_t>(p) * np;
      double sum = 0.0;
      for (int r = 0; r < np; ++r) sum += row[r] * qp[r];
      ws.p_contract[p] = sum;
    }
  }
  const double cb = model.bending_stiffness / (L * L * L);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (int j = 0; j < n; ++j) sum += ws.p_contract[packed<N>(n, i, j)] * qv[j];
    ws.bending[i] = cb * (mi.r4[i] * qv[i] + sum / (2.0 * L * L));
    ws.psi[i] = gyro[i] + ws.foreshortening[i] + ws.centrifugal[i] + ws.bending[i];
  }
}

template <class Fn>
void dispatch(int n, Fn&& fn) {
  switch (n) {
    case 1: return fn(std::integral_constant<int, 1>{});
    case 2: return fn(std::integral_constant<int, 2>{});
    case 3: return fn(std::integral_constant<int, 3>{});
    case 4: return fn(std::integral_constant<int, 4>{});
    case 5: return fn(std::integral_constant<int, 5>{});
    case 6: return fn(std::integral_constant<int, 6>{});
    case 7: return fn(std::integral_constant<int, 7>{});
    case 8: return fn(std::integral_constant<int, 8>{});
    default: return fn(std::integral_constant<int, 0>{});
  }
}

}  // namespace

void evaluate_mass(const ForeshorteningBeam& model, const Eigen::Ref<const Eigen::VectorXd>& q, ForeshorteningWorkspace& ws) {
  dispatch(model.n, [&](auto dim) { mass_kernel<decltype(dim)::value>(model, q.data(), ws); });
}

void evaluate_dynamics(const ForeshorteningBeam& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                       const Eigen::Ref<const Eigen::VectorXd>& qd, ForeshorteningWorkspace& ws) {
  dispatch(model.n, [&](auto dim) {
    constexpr int N = decltype(dim)::value;
    mass_kernel<N>(model, q.data(), ws);
    ws.mass_llt.compute(ws.mass);
    force_kernel<N>(model, q.data(), qd.data(), ws);
  });
  if (model.damped()) {
    ws.damping.noalias() = model.damping * qd;
    ws.psi += ws.damping;
  }
}

void free_flight_jacobian(const ForeshorteningBeam& model, const Eigen::Ref<const Eigen::VectorXd>& q,
                          const Eigen::Ref<const Eigen::VectorXd>& qd, ForeshorteningWorkspace& ws,
                          Eigen::Ref<Eigen::VectorXd> qdd, Eigen::Ref<Eigen::MatrixXd> jq, Eigen::Ref<Eigen::MatrixXd> jqd) {
  evaluate_dynamics(model, q, qd, ws);  // M, Ψ, the factor, Z and the packed q q, q̇ q̇
  qdd = -ws.psi;
  ws.mass_llt.solveInPlace(qdd);
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n, np = mi.pairs;
  const double L = model.length;
  const double c1 = model.mass_per_length / L;
  const Eigen::Map<const RowMatrix> t(mi.isp_isp.data(), n * n, np);  // T[(i,k)][(j,l)] = ∫ISP_ik ISP_jl
  const Eigen::Map<const RowMatrix> z(ws.z.data(), n, np);           // Z[i][(j,l)] = Σ_k q_k T[(i,k)][(j,l)]
  const auto zz = [&](int i, int j, int l) { return z(i, mi.pair(j, l)); };
  Eigen::MatrixXd& dq = ws.dpsi_dq;
  Eigen::MatrixXd& dv = ws.dpsi_dv;

  // D(q, q̇) q̇ = c1 Σ_k q_k Σ_p T[(i,k)][p] (q̇q̇)_p:  ∂/∂q_k = c1 (T q̇q̇)_(i,k),  ∂/∂q̇_j = 2 c1 Σ_l Z[i][(j,l)] q̇_l.
  ws.square_scratch.noalias() = t * ws.v_pairs;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) dq(i, k) = c1 * ws.square_scratch[i * n + k];
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      double s = 0.0;
      for (int l = 0; l < n; ++l) s += zz(i, j, l) * qd[l];
      dv(i, j) = 2.0 * c1 * s;
    }

  // 2ω G(q) q̇ = g2 [Σ_kj B[i,k,j] q_k q̇_j − Σ_i'k B[i',k,i] q̇_i' q_k], B = ∫ISP S.
  const double g2 = model.coriolis ? 2.0 * model.omega * model.mass_per_length : 0.0;
  const auto b = [&](int i, int k, int j) { return mi.isp_s[static_cast<std::size_t>(i * n + k) * n + j]; };
  if (g2 != 0.0)
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < n; ++k) {
        double by_q = 0.0, by_v = 0.0;
        for (int j = 0; j < n; ++j) {
          by_q += (b(i, k, j) - b(j, k, i)) * qd[j];  // ∂/∂q_k
          by_v += (b(i, j, k) - b(k, j, i)) * q[j];   // ∂/∂q̇_k
        }
        dq(i, k) += g2 * by_q;
        dv(i, k) += g2 * by_v;
      }

  // K_ω(q) q = cw [(r_h/L) ∫ISP q + ∫ξ ISP q − c(q)/(2L²) − q], c_i = Σ_p Z[i][p] (qq)_p:
  // ∂c_i/∂q_m = (T qq)_(i,m) + 2 Σ_l Z[i][(m,l)] q_l.
  const double cw = model.centrifugal ? model.mass * model.omega * model.omega : 0.0;
  ws.square_scratch.noalias() = t * ws.q_pairs;
  const double rh_l = model.hub_radius / L;
  if (cw != 0.0)
    for (int i = 0; i < n; ++i)
      for (int m = 0; m < n; ++m) {
        double s = 0.0;
        for (int l = 0; l < n; ++l) s += zz(i, m, l) * q[l];
        const double dcubic = ws.square_scratch[i * n + m] + 2.0 * s;
        dq(i, m) += cw * (rh_l * mi.isp_mean(i, m) + mi.isp_xi(i, m) - dcubic / (2.0 * L * L) - (i == m ? 1.0 : 0.0));
      }

  // K_b(q) q = cb [r⁴ ⊙ q + Σ_j Pc_(i,j) q_j/(2L²)], Pc = PP qq:
  // ∂/∂q_m = cb [r⁴_i δ_im + (Pc_(i,m) + 2 Σ_jb PP[(i,j)][(m,b)] q_j q_b)/(2L²)].
  const double cb = model.bending_stiffness / (L * L * L);
  const Eigen::Map<const RowMatrix> pp(mi.p_p.data(), np, np);
  for (int i = 0; i < n; ++i)
    for (int m = 0; m < n; ++m) {
      double r = 0.0;
      for (int j = 0; j < n; ++j) {
        double s = 0.0;
        for (int bb = 0; bb < n; ++bb) s += pp(mi.pair(i, j), mi.pair(m, bb)) * q[bb];
        r += s * q[j];
      }
      dq(i, m) += cb * ((i == m ? mi.r4[i] : 0.0) + (ws.p_contract[mi.pair(i, m)] + 2.0 * r) / (2.0 * L * L));
    }

  if (model.damped()) dv += model.damping;

  // (∂M/∂q_k a)_i = c1 [Σ_p T[(i,k)][p] u_p + Σ_j a_j Z[i][(j,k)]], u = the packed symmetric a ⊗ q, a = q̈.
  Eigen::VectorXd& u = ws.pair_scratch;
  for (int j = 0; j < n; ++j) {
    u[mi.pair(j, j)] = qdd[j] * q[j];
    for (int l = j + 1; l < n; ++l) u[mi.pair(j, l)] = qdd[j] * q[l] + qdd[l] * q[j];
  }
  ws.square_scratch.noalias() = t * u;
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < n; ++k) {
      double s = 0.0;
      for (int j = 0; j < n; ++j) s += qdd[j] * zz(i, j, k);
      dq(i, k) += c1 * (ws.square_scratch[i * n + k] + s);
    }

  jq = -dq;
  ws.mass_llt.solveColumnsInPlace(jq);
  jqd = -dv;
  ws.mass_llt.solveColumnsInPlace(jqd);
}

Eigen::MatrixXd linear_stiffness(const ForeshorteningBeam& model) {
  const ModalIntegrals& mi = *model.integrals;
  const int n = mi.n;
  const double L = model.length;
  const double w2 = model.centrifugal ? model.omega * model.omega : 0.0;
  Eigen::MatrixXd k = model.mass * w2 *
                      ((model.hub_radius / L) * mi.isp_mean + mi.isp_xi - Eigen::MatrixXd::Identity(n, n));
  k.diagonal() += (model.bending_stiffness / (L * L * L)) * mi.r4;
  return 0.5 * (k + k.transpose());
}

}  // namespace rotbeam
