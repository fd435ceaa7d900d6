// Structured surface grids on NURBS surfaces: point distributions laid out in arc length,
// algebraic grids by parametric transfinite interpolation of boundary distributions, grid
// control that leaves the surface where it is (knot insertion, rational reparameterisation
// by weights), and a grid quality report. See docs/meshing.md for the maths.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "fairlines/curve.hpp"
#include "fairlines/surface.hpp"

namespace fairlines {

/// How points are spaced along a line.
enum class Spacing {
  Uniform,       ///< equal spacings
  Sinh,          ///< one-sided x = sinh(B xi) / sinh(B): clustered at the end whose spacing is given
  Tanh,          ///< one-sided x = 1 + tanh(B (xi - 1)) / tanh(B): clustered at the end whose spacing is given
  TanhTwoSided,  ///< Vinokur (1983) two-sided tanh with the first and the last spacing given
  Geometric,     ///< spacings grow by a constant ratio from the first spacing
};

struct Distribution {
  Spacing kind = Spacing::Uniform;
  int points = 21;
  double first = 0.0;
  double last = 0.0;
  double max_ratio = 1.2;

  /// Each field with its name and meaning: f(name, member pointer, doc).
  template <typename F>
  static void fields(F&& f) {
    f("kind", &Distribution::kind, "Spacing: uniform, sinh, tanh, tanh_two_sided, geometric");
    f("points", &Distribution::points, "number of points (>= 2); geometric: 0 = the fewest within max_ratio");
    f("first", &Distribution::first, "first spacing (m); sinh / tanh: 0 when the last end is clustered");
    f("last", &Distribution::last, "last spacing (m): tanh_two_sided, sinh, tanh");
    f("max_ratio", &Distribution::max_ratio, "geometric: largest ratio of neighbouring spacings (> 1)");
  }
};

/// Positions (metres, from 0 to `length`, increasing) of the points of `d` along a line of
/// `length` metres. End spacings are met to round-off (the stretching parameters are solved
/// for the discrete spacings, not for the end slopes). Throws InvalidInput for bad options,
/// InfeasibleFormParameters when the spacings cannot be met (e.g. a one-sided first spacing
/// not below the uniform one, or a Geometric ratio above max_ratio), ConvergenceError never
/// on valid input.
Eigen::VectorXd distribute(const Distribution& d, double length);

/// Parameters of the points at arc lengths `s` (metres from the start, increasing, within
/// [0, the curve's length]) along a curve: the arc length tabulated by Gauss-Legendre on 16
/// pieces of every knot span, then Newton on s(t) kept inside the table's bracket (to 1e-12
/// of the length). Throws InvalidInput for s outside or not increasing.
Eigen::VectorXd parameters_at_arc_length(const NurbsCurve& curve, const Eigen::VectorXd& s);

/// A structured grid: point (i, j) at row i * nj + j.
struct StructuredGrid {
  int ni = 0, nj = 0;       ///< points along u, along v
  Eigen::MatrixXd points;   ///< (ni * nj) x 3, metres
  Eigen::MatrixXd params;   ///< (ni * nj) x 2, (u, v) of every point on the surface
};

/// Grid on the whole surface: `du` laid out in arc length along the boundaries v = v0 and
/// v = v1, `dv` along u = u0 and u = u1; interior parameters by transfinite interpolation
/// in the parameter plane (each grid line joins the matching boundary points). A boundary of
/// zero length (a pole) takes the distribution of the opposite one. Every point is on the
/// surface. Throws as distribute().
StructuredGrid surface_grid(const NurbsSurface& surface, const Distribution& du, const Distribution& dv);

/// Grid at given parameters: ni = len(us), nj = len(vs). Throws InvalidInput for parameters
/// outside the domain or not increasing.
StructuredGrid parameter_grid(const NurbsSurface& surface, const Eigen::VectorXd& us, const Eigen::VectorXd& vs);

/// Parameters of a knot-line grid in one direction: every non-empty knot span cut into
/// `per_span` equal parts (per_span >= 1). Inserting knots adds grid lines where they go.
Eigen::VectorXd knot_line_parameters(const NurbsSurface& surface, Direction dir, int per_span);

/// The same surface with knots inserted so that a knot-line grid clusters at parameter `at`:
/// `count` knots at at +- spacing * growth^k (k = 0, 1, ...), inside the domain. No point
/// of the surface moves (Boehm knot insertion). Throws InvalidInput for bad values.
NurbsSurface cluster_by_knots(const NurbsSurface& surface, Direction dir, double at, double spacing, int count,
                              double growth = 1.5);

/// The same surface reparameterised by the Moebius map t = a + (b - a) sigma / (sigma + r (1 -
/// sigma)), r = sqrt(ratio), on [a, b] the domain in `dir`: knots mapped by the inverse,
/// weights multiplied by prod_k (r + (1 - r) sigma_{i+k}) (Lee & Lucian 1991). Control points
/// are unchanged and no point of the surface moves, yet a uniform grid in the new parameter
/// has d t / d sigma growing from 1 / r at the start to r at the end: `ratio` is the ratio of
/// the last to the first spacing on a surface of uniform speed (> 1 clusters at the start).
/// Throws InvalidInput unless 1e-3 <= ratio <= 1e3.
NurbsSurface cluster_by_weights(const NurbsSurface& surface, Direction dir, double ratio);

/// Quality of a structured grid (degenerate cells at poles are skipped for angles and ratios).
struct GridQuality {
  double first_min = 0, first_max = 0;  ///< first spacing along i-lines (u direction), min / max over lines (m)
  double last_min = 0, last_max = 0;    ///< last spacing along i-lines (m)
  double first_min_j = 0, first_max_j = 0, last_min_j = 0, last_max_j = 0;  ///< the same along j-lines
  double max_stretching = 0;         ///< max ratio of neighbouring spacings along any grid line (>= 1)
  double max_orthogonality_deg = 0;  ///< max |corner angle - 90| over all cells
  double mean_orthogonality_deg = 0;
  double max_skewness = 0;           ///< equiangle skewness max((t_max - 90) / 90, (90 - t_min) / 90)
  double max_aspect_ratio = 0;       ///< longest / shortest side of a cell
  long degenerate_cells = 0;         ///< cells with a side shorter than 1e-9 x the grid size
};

/// points (ni * nj) x 3, row i * nj + j. Throws InvalidInput for a shape mismatch or ni, nj < 2.
GridQuality grid_quality(const Eigen::MatrixXd& points, int ni, int nj);

}  // namespace fairlines
