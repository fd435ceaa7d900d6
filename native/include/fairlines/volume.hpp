// Trivariate NURBS volumes V(s,t,r) (Sederberg & Parry 1986; Yoon 2007): free-form deformation lattices.
#pragma once

#include <array>

#include <Eigen/Core>

namespace fairlines {

class NurbsVolume {
 public:
  /// degrees         {ps, pt, pr}, each >= 1
  /// knots           three knot vectors, lengths n_a + p_a + 1
  /// counts          {ns, nt, nr} control points per direction
  /// control_points  (ns * nt * nr) x 3, row (i * nt + j) * nr + k holds b_ijk (metres)
  /// weights         ns * nt * nr positive values (h_ijk), or empty (all 1)
  NurbsVolume(std::array<int, 3> degrees, std::array<Eigen::VectorXd, 3> knots,
              std::array<int, 3> counts, Eigen::MatrixXd control_points,
              Eigen::VectorXd weights = Eigen::VectorXd());

  const std::array<int, 3>& degrees() const { return degrees_; }
  const std::array<Eigen::VectorXd, 3>& knots() const { return knots_; }
  const std::array<int, 3>& counts() const { return counts_; }
  const Eigen::MatrixXd& control_points() const { return points_; }
  const Eigen::VectorXd& weights() const { return weights_; }

  /// Points at m parameter triples: m x 3.
  Eigen::MatrixXd evaluate(const Eigen::VectorXd& s, const Eigen::VectorXd& t,
                           const Eigen::VectorXd& r) const;
  /// Point and first partial derivatives at m parameter triples, stacked: rows 4k .. 4k+3
  /// hold V, dV/ds, dV/dt, dV/dr at triple k (metres per unit parameter); the rational
  /// quotient rule is applied. This is the Jacobian of a free-form deformation.
  Eigen::MatrixXd derivatives(const Eigen::VectorXd& s, const Eigen::VectorXd& t,
                              const Eigen::VectorXd& r) const;

 private:
  std::array<int, 3> degrees_;
  std::array<Eigen::VectorXd, 3> knots_;
  std::array<int, 3> counts_;
  Eigen::MatrixXd points_;
  Eigen::VectorXd weights_;
};

}  // namespace fairlines
