#include "solver/increment/global_increment.hpp"

#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>

#include <Eigen/Eigenvalues>

namespace xpl {

namespace {

/// Reproducible start vector entry in [−1, 1) for DOF `k` (splitmix64 of the index): every
/// mode, the highest included, has a share of it.
Real start_entry(std::uint64_t k) {
  std::uint64_t z = k + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  z ^= z >> 31;
  return static_cast<Real>(z >> 11) * (2.0 / 9007199254740992.0) - 1.0;
}

/// Serial dot product in storage order (the estimate must not depend on the thread count).
Real dot(const NodalVectors& a, const NodalVectors& b) {
  const Real* pa = a.data();
  const Real* pb = b.data();
  Real s = 0.0;
  for (Index k = 0; k < a.size(); ++k) s += pa[k] * pb[k];
  return s;
}

/// Largest eigenvalue of the symmetric tridiagonal matrix (diagonal `a`, off-diagonal `b`).
Real largest_ritz_value(const std::vector<Real>& a, const std::vector<Real>& b) {
  const auto k = static_cast<Eigen::Index>(a.size());
  if (k == 1) return a[0];
  Eigen::VectorXd diag = Eigen::Map<const Eigen::VectorXd>(a.data(), k);
  Eigen::VectorXd sub = Eigen::Map<const Eigen::VectorXd>(b.data(), k - 1);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver;
  solver.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
  return solver.eigenvalues()(k - 1);  // ascending order
}

/// (2/ω)·(√(1+ξ²)−ξ) with the damping ratio ξ that the linear bulk viscosity b1 gives the
/// highest mode. The element estimate assumes ξ = b1 at its frequency 2/Δt_e (undamped).
/// Where ω_max is r times higher, ξ = b1·ω·L/(2c_d)·(share of the mode's energy that is
/// volumetric, relative to a plane wave): r for a plane-wave-like mode, up to
/// r·3(1−ν)/(1+ν) for a dilatational one — and the top modes of the deficient meshes (single
/// elements, layers) are the more dilatational the larger r is. ξ = b1·r² follows the
/// stress test (tests/solver/test_stability.cpp) and stays below that bound for r ≤ 1.6.
Real global_increment(Real omega, Real element_dt, Real b1) {
  if (!(omega > 0.0)) return std::numeric_limits<Real>::infinity();
  const Real element_undamped = element_dt / (std::sqrt(1.0 + b1 * b1) - b1);
  const Real r = std::max(1.0, 0.5 * omega * element_undamped);
  const Real xi = b1 * r * r;
  return 2.0 / omega * (std::sqrt(1.0 + xi * xi) - xi);
}

}  // namespace

Real GlobalIncrementLimit::apply(const elements::Hex8rBlock& hex, const NodalVectors& position,
                                 const std::vector<Real>& inverse_mass, Real bulk_linear,
                                 const elements::IncrementLimit& limit) {
  const auto product = [&hex, &position](const NodalVectors& u, NodalVectors& y) {
    hex.add_stiffness_product(position, u, y);
  };
  return apply(product, position.rows(), inverse_mass, bulk_linear, limit);
}

Real GlobalIncrementLimit::apply(const StiffnessProduct& product, Index n_nodes,
                                 const std::vector<Real>& inverse_mass, Real bulk_linear,
                                 const elements::IncrementLimit& limit) {
  return apply(product, n_nodes, inverse_mass, bulk_linear, limit, {});
}

Real GlobalIncrementLimit::apply(const StiffnessProduct& product, Index n_nodes,
                                 const std::vector<Real>& inverse_mass, Real bulk_linear,
                                 const elements::IncrementLimit& limit, const Prepare& prepare) {
  const Real element_dt = limit.stable_dt;
  if (!std::isfinite(element_dt) || !(element_dt > 0.0) || limit.failed_element != NO_INDEX)
    return 1.0;
  ++m_since;
  const bool moved = m_last.element_dt > 0.0 && m_since >= MIN_INCREMENTS_BETWEEN &&
                     std::abs(element_dt / m_last.element_dt - 1.0) > RECALIBRATE_CHANGE;
  if (m_due || moved) {
    const auto start = std::chrono::steady_clock::now();
    FrequencyEstimate e;
    if (prepare) prepare();
    Real lambda =
        m_estimates ? largest_eigenvalue(product, n_nodes, inverse_mass, e.products) : 0.0;
    if (m_share) m_share(lambda, e.products);
    e.omega_max = std::sqrt(std::max(lambda, 0.0));
    e.global_dt = global_increment(e.omega_max, element_dt, bulk_linear);
    e.element_dt = element_dt;
    e.ratio = std::min(1.0, e.global_dt / GLOBAL_MARGIN / element_dt);
    e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    m_last = e;
    m_due = false;
    m_reported = false;
    m_since = 0;
  }
  return m_last.ratio;
}

bool GlobalIncrementLimit::take_new_estimate(FrequencyEstimate& out) {
  if (m_reported) return false;
  m_reported = true;
  out = m_last;
  return true;
}

Real GlobalIncrementLimit::largest_eigenvalue(const StiffnessProduct& product, Index n_nodes,
                                              const std::vector<Real>& inverse_mass,
                                              int& products) const {
  // Lanczos on S = D K D (symmetric, same spectrum as M⁻¹K); DOFs without mass drop out.
  // Boundary conditions are left out on purpose: constraints only lower the highest
  // frequency (interlacing), so the unconstrained operator bounds every support condition. Without
  // reorthogonalisation: the largest Ritz value converges first and from below, which is all the
  // estimate needs.
  const Index n = n_nodes;
  NodalVectors d = NodalVectors::Zero(n, 3), q(n, 3);
  for (int c = 0; c < 3; ++c)
    for (Index i = 0; i < n; ++i) {
      if (inverse_mass[i] > 0.0) d(i, c) = std::sqrt(inverse_mass[i]);
      q(i, c) = d(i, c) > 0.0 ? start_entry(static_cast<std::uint64_t>(c * n + i)) : 0.0;
    }
  const Real norm = std::sqrt(dot(q, q));
  if (!(norm > 0.0)) return 0.0;
  q /= norm;
  NodalVectors q_prev = NodalVectors::Zero(n, 3), w(n, 3);
  std::vector<Real> alpha, beta;
  Real theta = 0.0, beta_prev = 0.0;
  for (int j = 0; j < MAX_ITERATIONS; ++j) {
    w.setZero();
    product(d.cwiseProduct(q), w);
    ++products;
    w = d.cwiseProduct(w) - beta_prev * q_prev;
    const Real a = dot(q, w);
    w -= a * q;
    w -= dot(q, w) * q;  // local reorthogonalisation against round-off
    const Real b = std::sqrt(dot(w, w));
    alpha.push_back(a);
    const Real theta_new = largest_ritz_value(alpha, beta);
    const bool converged = j >= 2 && theta_new - theta <= TOLERANCE * theta_new;
    theta = std::max(theta, theta_new);
    if (converged || !(b > 1e-10 * theta)) break;  // converged, or an invariant subspace
    beta.push_back(b);
    q_prev = q;
    q = w / b;
    beta_prev = b;
  }
  return theta;
}

}  // namespace xpl
