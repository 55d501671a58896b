#include "engine/design/discrepancy_model.hpp"

#include <Eigen/Dense>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace softarm::engine {

void DiscrepancyModel::add(const std::vector<double>& u, const std::vector<double>& g_accurate,
                           const std::vector<double>& g_search) {
  if (g_accurate.size() != g_search.size()) throw std::logic_error("DiscrepancyModel: constraint counts differ");
  if (!points_.empty() && (u.size() != points_.front().u.size() || g_search.size() != points_.front().delta.size()))
    throw std::logic_error("DiscrepancyModel: another design space");
  Point p{u, {}};
  for (std::size_t i = 0; i < g_search.size(); ++i) p.delta.push_back(g_accurate[i] - g_search[i]);
  points_.push_back(std::move(p));
  fit();
}

void DiscrepancyModel::fit() {
  const Point& c = points_.back();
  const std::size_t n = c.u.size(), m = c.delta.size(), k = points_.size() - 1;
  slope_.assign(m, std::vector<double>(n, 0.0));
  if (k == 0) return;
  Eigen::MatrixXd D(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(n));
  Eigen::MatrixXd Delta(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(m));
  for (std::size_t j = 0; j < k; ++j) {
    for (std::size_t v = 0; v < n; ++v) D(j, v) = points_[j].u[v] - c.u[v];
    for (std::size_t i = 0; i < m; ++i) Delta(j, i) = points_[j].delta[i] - c.delta[i];
  }
  // Minimum-norm interpolation b = Dᵀ (D Dᵀ)⁻¹ Δ; a tiny ridge keeps a repeated or collinear
  // design from making D Dᵀ singular (the fit then averages the designs it cannot tell apart).
  Eigen::MatrixXd G = D * D.transpose();
  G.diagonal().array() += 1e-10 * std::max(1.0, G.trace());
  const Eigen::MatrixXd B = D.transpose() * G.ldlt().solve(Delta);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t v = 0; v < n; ++v) slope_[i][v] = B(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(i));
}

std::vector<double> DiscrepancyModel::at(const std::vector<double>& u) const {
  if (points_.empty()) return {};
  const Point& c = points_.back();
  std::vector<double> out = c.delta;
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t v = 0; v < u.size() && v < c.u.size(); ++v) out[i] += slope_[i][v] * (u[v] - c.u[v]);
  return out;
}

std::string DiscrepancyModel::describe(const std::vector<std::string>& names) const {
  if (points_.empty()) return "none";
  std::ostringstream s;
  s << std::fixed << std::setprecision(3) << "g shifted at the centre by";
  for (std::size_t i = 0; i < names.size() && i < points_.back().delta.size(); ++i)
    s << (i ? ", " : " ") << names[i] << " " << std::showpos << points_.back().delta[i] << std::noshowpos;
  s << "; linear term from " << points_.size() - 1 << " other verified design" << (points_.size() == 2 ? "" : "s");
  return s.str();
}

}  // namespace softarm::engine
