// Fair skinning (Kim & Hwangbo 2008, eq. 6-9): see fairlines/skinning.hpp.
#include "fairlines/skinning.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fairlines/basis.hpp"
#include "fairlines/errors.hpp"
#include "fairlines/knots.hpp"
#include "fairlines/qp.hpp"
#include "nurbs/checks.hpp"
#include "nurbs/arc_length.hpp"
#include "nurbs/gauss.hpp"
#include "nurbs/gram.hpp"

namespace fairlines {

namespace {

using detail::fail;

/// Value and first derivative of a curve at t, without allocation for non-rational curves.
class CurveProbe {
 public:
  /// weight > 0 measures length as ds (1 + weight |k|) (curvature-weighted arc length).
  explicit CurveProbe(const NurbsCurve& c, double weight = 0.0)
      : c_(c), weight_(weight), ders_(3, c.degree() + 1) {}
  /// Writes C(t) into p, C'(t) into d and C''(t) into dd (dim values each).
  void eval(double t, double* p, double* d, double* dd = nullptr) {
    const int deg = c_.degree(), dim = c_.dim();
    if (c_.is_rational() || dim > 8) {
      const Eigen::MatrixXd D = c_.derivatives(t, 2);
      for (int k = 0; k < dim; ++k) {
        p[k] = D(0, k), d[k] = D(1, k);
        if (dd) dd[k] = D(2, k);
      }
      return;
    }
    const Eigen::VectorXd& U = c_.knots();
    const int span = find_span(deg, U.data(), static_cast<int>(U.size()), t);
    basis_derivatives(span, t, deg, 2, U, ders_);
    const Eigen::MatrixXd& P = c_.control_points();
    for (int k = 0; k < dim; ++k) {
      p[k] = d[k] = 0.0;
      if (dd) dd[k] = 0.0;
    }
    for (int j = 0; j <= deg; ++j) {
      const int row = span - deg + j;
      for (int k = 0; k < dim; ++k) {
        p[k] += ders_(0, j) * P(row, k);
        d[k] += ders_(1, j) * P(row, k);
        if (dd) dd[k] += ders_(2, j) * P(row, k);
      }
    }
  }
  /// |C'(t)| (1 + weight |k(t)|).
  double speed(double t) {
    double p[8], d[8], dd[8];
    if (c_.dim() > 8) {
      const Eigen::MatrixXd D = c_.derivatives(t, 1);
      return D.row(1).norm();
    }
    eval(t, p, d, weight_ > 0 ? dd : nullptr);
    double s2 = 0;
    for (int k = 0; k < c_.dim(); ++k) s2 += d[k] * d[k];
    const double sp = std::sqrt(s2);
    if (!(weight_ > 0) || !(sp > 0)) return sp;
    // |C' x C''|^2 = |C'|^2 |C''|^2 - (C'.C'')^2, any dimension.
    double dd2 = 0, dot = 0;
    for (int k = 0; k < c_.dim(); ++k) dd2 += dd[k] * dd[k], dot += d[k] * dd[k];
    const double cross = std::sqrt(std::max(0.0, s2 * dd2 - dot * dot));
    return sp + weight_ * cross / s2;  // |C'| (1 + w |k|), |k| = |C' x C''| / |C'|^3
  }

 private:
  const NurbsCurve& c_;
  double weight_;
  Eigen::MatrixXd ders_;
};

constexpr int kArcGauss = 8;     // Gauss points per piece of the arc-length table
constexpr int kArcSplit = 4;     // pieces per knot span
constexpr int kArcNewtonGauss = 5;  // Gauss points of the one Newton step of the inversion

detail::ArcTable arc_table(CurveProbe& probe, const NurbsCurve& c) {
  const auto [t0, t1] = c.domain();
  return detail::arc_table([&](double t) { return probe.speed(t); }, c.knots(), t0, t1, kArcSplit, kArcGauss);
}

/// Parameter where the arc length from the start is (nearly) `target`: Hermite guess and one
/// Newton step, which removes most of the Hermite error where the speed varies fast.
double invert_arc(CurveProbe& probe, const detail::ArcTable& tab, double target) {
  return detail::invert_arc([&](double t) { return probe.speed(t); }, tab, target, 1, kArcNewtonGauss, 0.0);
}

/// A run of consecutive sections [first, last] over which one data column keeps `value`.
struct HeldRun {
  int first, last;
  double value;
};

/// Maximal runs of at least kMinHeldRun consecutive values of a column equal to within tol.
std::vector<HeldRun> find_runs(const Eigen::VectorXd& col, double tol) {
  const int q = static_cast<int>(col.size());
  std::vector<HeldRun> out;
  for (int d = 0; d < q;) {
    int e = d;
    while (e + 1 < q && std::abs(col[e + 1] - col[d]) <= tol) ++e;
    if (e - d + 1 >= kMinHeldRun) out.push_back({d, e, col[d]});
    d = e + 1;
  }
  return out;
}

/// True when every section already has degree degree_u, one and the same knot vector and (if
/// n_control is given) that many control points, non-rational.
bool shared_knot_vector(const std::vector<NurbsCurve>& sections, const SkinOptions& o) {
  const NurbsCurve& c0 = sections[0];
  if (c0.degree() != o.degree_u || (o.n_control > 0 && o.n_control != c0.n_control())) return false;
  const Eigen::VectorXd& U0 = c0.knots();
  for (const NurbsCurve& c : sections) {
    if (c.is_rational() || c.degree() != c0.degree() || c.knots().size() != U0.size()) return false;
    if ((c.knots() - U0).cwiseAbs().maxCoeff() > 1e-14 * std::max(1.0, U0.cwiseAbs().maxCoeff())) return false;
  }
  return true;
}

/// The section-resampling step of Kim & Hwangbo (2008): m points equally spaced by (optionally
/// curvature-weighted) arc length along every section (pts[d]: m x 3).
std::vector<Eigen::MatrixXd> resample_sections(const std::vector<NurbsCurve>& sections, const SkinOptions& o, int m) {
  const int q = static_cast<int>(sections.size());
  std::vector<Eigen::MatrixXd> pts(q);
  for (int d = 0; d < q; ++d) {
    try {
      pts[d] = equal_arc_length_points(sections[d], m, o.curvature_weight);
    } catch (const InvalidInput& e) {
      fail("sections[", d, "]: ", e.what());
    }
  }
  return pts;
}

/// The flat planes of SkinOptions::flats, checked, and the distance within which a set of
/// samples counts as lying in one (kFlatTolerance of the samples' extent).
class FlatPlanes {
 public:
  FlatPlanes(const SkinOptions& o, const std::vector<Eigen::MatrixXd>& pts) : flats_(o.flats) {
    double extent = 1.0;
    for (const Eigen::MatrixXd& p : pts) extent = std::max(extent, p.cwiseAbs().maxCoeff());
    tol_ = kFlatTolerance * extent;
    for (std::size_t f = 0; f < flats_.size(); ++f) {
      const auto [axis, value] = flats_[f];
      if (axis < 0 || axis > 2) fail("flats[", f, "] has axis ", axis, "; expected 0 (x), 1 (y) or 2 (z)");
      if (!std::isfinite(value)) fail("flats[", f, "] has value ", value, "; expected a finite coordinate (m)");
    }
  }
  bool empty() const { return flats_.empty(); }
  /// The value of the first plane normal to `axis` that coords[0..count) all lie in, or NaN.
  double value(int axis, const double* coords, int count) const {
    for (const auto& [a, c] : flats_) {
      if (a != axis) continue;
      bool all = true;
      for (int k = 0; k < count; ++k)
        if (!(std::abs(coords[k] - c) <= tol_)) { all = false; break; }
      if (all) return c;
    }
    return std::numeric_limits<double>::quiet_NaN();
  }

 private:
  const std::vector<std::pair<int, double>>& flats_;
  double tol_ = 0;
};

/// Collocation matrix Nu (m x n): the basis of knot vector Ku of degree p at m uniform parameters.
Eigen::MatrixXd collocation_matrix(const Eigen::VectorXd& Ku, int p, int n, int m) {
  Eigen::MatrixXd Nu(m, n);
  for (int k = 0; k < m; ++k) Nu.row(k) = basis_row(Ku, p, static_cast<double>(k) / (m - 1));
  return Nu;
}

/// Control points (n x cols) for the sample columns rhs (m x cols): interpolation when m == n,
/// else the end control points fixed to the end samples and the interior by least squares
/// (QR of the collocation matrix, factorised once for every column).
Eigen::MatrixXd fit_with_fixed_ends(const Eigen::MatrixXd& Nu, const Eigen::MatrixXd& rhs) {
  const int m = static_cast<int>(Nu.rows()), n = static_cast<int>(Nu.cols());
  Eigen::MatrixXd sol(n, rhs.cols());
  if (m == n) {
    sol = Nu.partialPivLu().solve(rhs);
    return sol;
  }
  sol.row(0) = rhs.row(0);
  sol.row(n - 1) = rhs.row(m - 1);
  const Eigen::MatrixXd A = Nu.block(1, 1, m - 2, n - 2);
  const Eigen::MatrixXd b = rhs.middleRows(1, m - 2) - Nu.block(1, 0, m - 2, 1) * sol.row(0) -
                            Nu.block(1, n - 1, m - 2, 1) * sol.row(n - 1);
  sol.middleRows(1, n - 2) = A.householderQr().solve(b);
  return sol;
}

/// For each interior control point j, the interior samples [first, last] strictly inside its
/// support (Ku[j], Ku[j + p + 1]); empty (first > last) when none. The same for every section.
std::vector<std::pair<int, int>> samples_in_supports(const Eigen::VectorXd& Ku, int p, int n, int m) {
  std::vector<std::pair<int, int>> inside(n, {1, 0});
  for (int j = 1; j < n - 1; ++j) {
    int first = m, last = -1;
    for (int k = 1; k < m - 1; ++k) {
      const double u = static_cast<double>(k) / (m - 1);
      if (u > Ku[j] && u < Ku[j + p + 1]) first = std::min(first, k), last = k;
    }
    inside[j] = {first, last};
  }
  return inside;
}

/// Control points whose whole support lies in a flat keep exactly to it; the others are the
/// least-squares fit with those fixed (normal equations of the free ones, one Cholesky
/// factorisation per distinct set of fixed points). Columns of sol are x, y, z per section.
void hold_flats(const Eigen::MatrixXd& Nu, const Eigen::MatrixXd& rhs, const FlatPlanes& flats,
                const std::vector<std::pair<int, int>>& inside, Eigen::MatrixXd& sol) {
  const int n = static_cast<int>(Nu.cols());
  if (n < 2) return;  // nothing between the ends to hold (and GCC knows fixed[n - 1] exists)
  const Eigen::MatrixXd M = Nu.transpose() * Nu;
  std::map<std::vector<char>, Eigen::LLT<Eigen::MatrixXd>> factors;
  for (int col = 0; col < rhs.cols(); ++col) {
    std::vector<char> fixed(n, 0);
    Eigen::VectorXd z = sol.col(col), held = Eigen::VectorXd::Zero(n);  // held: z where fixed
    fixed[0] = fixed[n - 1] = 1;
    held[0] = z[0], held[n - 1] = z[n - 1];
    bool any = false;
    for (int j = 1; j < n - 1; ++j) {
      const auto [first, last] = inside[j];
      if (first > last) continue;
      const double c = flats.value(col % 3, rhs.col(col).data() + first, last - first + 1);
      if (!std::isnan(c)) fixed[j] = 1, z[j] = held[j] = c, any = true;
    }
    if (!any) continue;
    std::vector<int> freev;
    for (int j = 0; j < n; ++j)
      if (!fixed[j]) freev.push_back(j);
    const int r = static_cast<int>(freev.size());
    if (r > 0) {
      auto it = factors.find(fixed);
      if (it == factors.end()) {
        Eigen::MatrixXd Mrr(r, r);
        for (int a = 0; a < r; ++a)
          for (int b = 0; b < r; ++b) Mrr(a, b) = M(freev[a], freev[b]);
        it = factors.emplace(fixed, Eigen::LLT<Eigen::MatrixXd>(Mrr)).first;
      }
      const Eigen::VectorXd g = Nu.transpose() * rhs.col(col) - M * held;
      Eigen::VectorXd gr(r);
      for (int a = 0; a < r; ++a) gr[a] = g[freev[a]];
      const Eigen::VectorXd zr = it->second.solve(gr);
      for (int a = 0; a < r; ++a) z[freev[a]] = zr[a];
    }
    sol.col(col) = z;
  }
}

/// The resampling and refitting steps of Kim & Hwangbo (2008): m points equally spaced along
/// every section, refitted with one common clamped uniform knot vector Ku of n control points
/// (ctrl[d]: n x 3). Returns the largest distance between the points and the fits (m).
double refit_sections(const std::vector<NurbsCurve>& sections, const SkinOptions& o, int n, int m, Eigen::VectorXd& Ku,
                      std::vector<Eigen::MatrixXd>& ctrl) {
  const int q = static_cast<int>(sections.size());
  const std::vector<Eigen::MatrixXd> pts = resample_sections(sections, o, m);
  const FlatPlanes flats(o, pts);
  Ku = clamped_uniform_knots(n, o.degree_u);
  const Eigen::MatrixXd Nu = collocation_matrix(Ku, o.degree_u, n, m);
  Eigen::MatrixXd rhs(m, 3 * q);  // the samples, x y z per section
  for (int d = 0; d < q; ++d) rhs.middleCols(3 * d, 3) = pts[d];
  Eigen::MatrixXd sol = fit_with_fixed_ends(Nu, rhs);
  if (m != n && !flats.empty()) hold_flats(Nu, rhs, flats, samples_in_supports(Ku, o.degree_u, n, m), sol);
  const Eigen::MatrixXd resid = Nu * sol - rhs;
  double fit_max = 0;
  ctrl.assign(q, Eigen::MatrixXd(n, 3));
  for (int d = 0; d < q; ++d) {
    ctrl[d] = sol.middleCols(3 * d, 3);
    for (int k = 0; k < m; ++k) fit_max = std::max(fit_max, resid.block(k, 3 * d, 1, 3).norm());
  }
  return fit_max;
}

}  // namespace

double arc_length(const NurbsCurve& curve) {
  CurveProbe probe(curve);
  return arc_table(probe, curve).s.back();
}

Eigen::MatrixXd equal_arc_length_points(const NurbsCurve& curve, int m, double curvature_weight) {
  if (m < 2) fail("m is ", m, "; expected at least 2 points");
  if (!(curvature_weight >= 0) || !std::isfinite(curvature_weight))
    fail("curvature_weight is ", curvature_weight, "; expected a finite value >= 0");
  double w = 0;
  if (curvature_weight > 0) w = curvature_weight * arc_length(curve);
  CurveProbe probe(curve, w);
  const detail::ArcTable tab = arc_table(probe, curve);
  const double L = tab.s.back();
  if (!(L > 0)) fail("curve has zero length; expected a curve of positive length");
  Eigen::MatrixXd out(m, curve.dim());
  std::vector<double> p(curve.dim()), d(curve.dim());
  for (int i = 0; i < m; ++i) {
    double t;
    if (i == 0) t = tab.t.front();
    else if (i == m - 1) t = tab.t.back();
    else t = invert_arc(probe, tab, L * i / (m - 1));
    if (curve.is_rational()) {
      out.row(i) = curve.evaluate(t).transpose();
    } else {
      probe.eval(t, p.data(), d.data());
      for (int k = 0; k < curve.dim(); ++k) out(i, k) = p[k];
    }
  }
  return out;
}

double curve_e2(const NurbsCurve& curve) {
  const auto& g = detail::gauss_rule(curve.degree() + 1);
  const Eigen::VectorXd& U = curve.knots();
  const auto [t0, t1] = curve.domain();
  double e = 0;
  for (Eigen::Index i = 0; i + 1 < U.size(); ++i) {
    const double a = std::max(U[i], t0), b = std::min(U[i + 1], t1);
    if (!(b > a)) continue;
    const double h = 0.5 * (b - a), m = 0.5 * (a + b);
    // Rational curves are not polynomial; use more points then.
    const int reps = curve.is_rational() ? 4 : 1;
    for (int r = 0; r < reps; ++r) {
      const double ra = a + (b - a) * r / reps, rb = a + (b - a) * (r + 1) / reps;
      const double hh = 0.5 * (rb - ra), mm = 0.5 * (ra + rb);
      for (std::size_t k = 0; k < g.x.size(); ++k) {
        const Eigen::MatrixXd D = curve.derivatives(mm + hh * g.x[k], 2);
        e += g.w[k] * hh * D.row(2).squaredNorm();
      }
    }
    (void)h;
    (void)m;
  }
  return e;
}

SkinMode parse_skin_mode(const std::string& name) {
  if (name == "interpolate") return SkinMode::Interpolate;
  if (name == "approximate") return SkinMode::Approximate;
  fail("mode is '", name, "'; expected 'interpolate' or 'approximate'");
}

SkinEnd parse_skin_end(const std::string& name) {
  if (name == "free") return SkinEnd::Free;
  if (name == "parallel") return SkinEnd::Parallel;
  if (name == "not_a_knot") return SkinEnd::NotAKnot;
  fail("end condition is '", name, "'; expected 'free', 'parallel' or 'not_a_knot'");
}

SkinParams parse_skin_params(const std::string& name) {
  if (name == "auto") return SkinParams::Auto;
  if (name == "station") return SkinParams::Station;
  if (name == "chord") return SkinParams::Chord;
  fail("params is '", name, "'; expected 'auto', 'station' or 'chord'");
}

const char* skin_mode_name(SkinMode mode) { return mode == SkinMode::Interpolate ? "interpolate" : "approximate"; }

const char* skin_end_name(SkinEnd end) {
  return end == SkinEnd::Free ? "free" : end == SkinEnd::Parallel ? "parallel" : "not_a_knot";
}

const char* skin_params_name(SkinParams params) {
  return params == SkinParams::Auto ? "auto" : (params == SkinParams::Station ? "station" : "chord");
}

// fair_skin in named steps. Notation: q sections d = 0..q-1, n control rows i per section
// (one knot vector Ku of degree_u), a data column 3 i + k holds coordinate k of row i through
// the sections; v (q) the sections' longitudinal parameters, Kv / pv the longitudinal knots and
// degree, nv their control count, Nv (q, nv) the basis at the sections, G the fairness Gram
// matrix e2 E2 + e3 h^2 E3, H the objective's Hessian, cs the constraint-row scale and lon
// (nv, 3 n) the longitudinal control columns.
namespace {

/// Largest control count of the sections; refuses fewer than 2 sections or non-3-D ones.
int check_sections(const std::vector<NurbsCurve>& sections) {
  const int q = static_cast<int>(sections.size());
  if (q < 2) fail("sections has ", q, " curves; expected at least 2");
  int largest = 0;
  for (int d = 0; d < q; ++d) {
    if (sections[d].dim() != 3)
      fail("sections[", d, "] is a ", sections[d].dim(), "-D curve; expected a 3-D curve (x, y, z)");
    largest = std::max(largest, sections[d].n_control());
  }
  return largest;
}

void check_degrees_and_weights(const SkinOptions& o) {
  detail::require_degree(o.degree_u, "degree_u");
  if (o.degree_v < 2) fail("degree_v is ", o.degree_v, "; expected an integer >= 2 (E2 needs C'')");
  if (o.n_control < 0) fail("n_control is ", o.n_control, "; expected 0 (automatic) or >= degree_u + 1");
  if (!(o.curvature_weight >= 0) || !std::isfinite(o.curvature_weight))
    fail("curvature_weight is ", o.curvature_weight, "; expected a finite value >= 0");
  if (!(o.e2 >= 0) || !(o.e3 >= 0) || !std::isfinite(o.e2) || !std::isfinite(o.e3) || !(o.e2 + o.e3 > 0))
    fail("fairness weights are e2 = ", o.e2, ", e3 = ", o.e3, "; expected finite values >= 0, not both 0");
  if (o.e3 > 0 && o.degree_v < 3) fail("e3 is ", o.e3, " but degree_v is ", o.degree_v, "; E3 needs degree_v >= 3");
  if (!(o.smoothing >= 0) || !std::isfinite(o.smoothing))
    fail("smoothing is ", o.smoothing, "; expected a finite value >= 0");
}

void check_row_counts(const SkinOptions& o, int n, int m, bool exact) {
  if (n < o.degree_u + 1) fail("n_control is ", n, "; expected at least degree_u + 1 = ", o.degree_u + 1);
  if (o.samples < 0 || (!exact && m < n)) fail("samples is ", o.samples, "; expected 0 (automatic) or >= n_control = ", n);
  for (std::size_t g = 0; g < o.straight_groups.size(); ++g) {
    const auto [first, last] = o.straight_groups[g];
    if (first < 0 || last < first || last >= n)
      fail("straight_groups[", g, "] is (", first, ", ", last, "); expected row indices 0 <= first <= last < ", n);
  }
}

/// Station parameters apply when every section is planar at one x and the x are monotone.
SkinParams resolve_params(const std::vector<Eigen::MatrixXd>& ctrl, SkinParams mode) {
  if (mode == SkinParams::Chord) return mode;
  const int q = static_cast<int>(ctrl.size());
  bool planar = true, monotone = true;
  double scale = 0;
  for (int d = 0; d < q; ++d) scale = std::max(scale, ctrl[d].cwiseAbs().maxCoeff());
  for (int d = 0; d < q; ++d) {
    const double spread = ctrl[d].col(0).maxCoeff() - ctrl[d].col(0).minCoeff();
    if (spread > 1e-9 * std::max(scale, 1.0)) planar = false;
  }
  const double dir = ctrl[q - 1](0, 0) - ctrl[0](0, 0);
  for (int d = 0; d + 1 < q; ++d)
    if (!((ctrl[d + 1](0, 0) - ctrl[d](0, 0)) * dir > 0)) monotone = false;
  if (planar && monotone) return SkinParams::Station;
  if (mode == SkinParams::Station) {
    if (!planar) fail("params is 'station' but the sections are not planar at constant x");
    fail("params is 'station' but the section x positions are not strictly monotone");
  }
  return SkinParams::Chord;
}

/// v: the sections' x scaled to [0, 1] (station) or the mean control-row chord (chord).
Eigen::VectorXd section_parameters(const std::vector<Eigen::MatrixXd>& ctrl, SkinParams mode, int n) {
  const int q = static_cast<int>(ctrl.size());
  Eigen::VectorXd v(q);
  if (resolve_params(ctrl, mode) == SkinParams::Station) {
    const double x0 = ctrl[0](0, 0), x1 = ctrl[q - 1](0, 0);
    for (int d = 0; d < q; ++d) v[d] = (ctrl[d](0, 0) - x0) / (x1 - x0);
  } else {
    v[0] = 0;
    for (int d = 1; d < q; ++d) {
      double c = 0;
      for (int i = 0; i < n; ++i) c += (ctrl[d].row(i) - ctrl[d - 1].row(i)).norm();
      v[d] = v[d - 1] + c / n;
    }
    if (!(v[q - 1] > 0)) fail("sections all coincide; expected sections at distinct places");
    v /= v[q - 1];
    for (int d = 1; d < q; ++d)
      if (!(v[d] > v[d - 1]))
        fail("sections[", d, "] coincides with sections[", d - 1, "]; expected distinct sections");
  }
  v[0] = 0;
  v[q - 1] = 1;
  return v;
}

/// (q, 3 n) data: column 3 i + k holds ctrl[d](i, k) through the sections d.
Eigen::MatrixXd data_columns(const std::vector<Eigen::MatrixXd>& ctrl, int n) {
  const int q = static_cast<int>(ctrl.size());
  Eigen::MatrixXd data(q, 3 * n);
  for (int d = 0; d < q; ++d)
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) data(d, 3 * i + k) = ctrl[d](i, k);
  return data;
}

/// Held runs (SkinOptions::hold_runs): per column, the maximal runs of at least kMinHeldRun
/// consecutive sections with one value (y and z only; x moves with the stations).
std::vector<std::vector<HeldRun>> held_runs(const std::vector<Eigen::MatrixXd>& ctrl, const Eigen::MatrixXd& data,
                                            bool hold) {
  std::vector<std::vector<HeldRun>> runs(data.cols());
  if (!hold) return runs;
  double extent = 1.0;
  for (const Eigen::MatrixXd& c : ctrl) extent = std::max(extent, c.cwiseAbs().maxCoeff());
  const double tol = kRunTolerance * extent;
  for (Eigen::Index col = 0; col < data.cols(); ++col)
    if (col % 3 != 0) runs[col] = find_runs(data.col(col), tol);
  return runs;
}

/// An interior row of a straight group: at fraction `frac` of the segment first -> last.
struct DerivedRow {
  int row;
  double frac;
  int first, last;
};

/// Straight groups: the interior rows are at one fraction s of the segment from the group's
/// first row to its last in every section; their longitudinal curves are built as the same
/// combination of the end rows' curves, so the segment stays straight between the sections
/// whatever the end rows hold. A group whose fractions differ between sections is refused.
/// Derived rows hold no runs of their own (cleared in `runs`).
std::vector<DerivedRow> straight_rows(const std::vector<Eigen::MatrixXd>& ctrl, const SkinOptions& o,
                                      std::vector<std::vector<HeldRun>>& runs) {
  const int q = static_cast<int>(ctrl.size());
  std::vector<DerivedRow> derived;
  for (std::size_t gi = 0; gi < o.straight_groups.size(); ++gi) {
    const auto [first, last] = o.straight_groups[gi];
    if (last - first < 2) continue;
    int dref = 0;
    for (int d = 0; d < q; ++d)
      if ((ctrl[d].row(last) - ctrl[d].row(first)).norm() > (ctrl[dref].row(last) - ctrl[dref].row(first)).norm()) dref = d;
    const Eigen::RowVector3d seg = ctrl[dref].row(last) - ctrl[dref].row(first);
    if (!(seg.norm() > 0)) fail("straight_groups[", gi, "]: its end rows coincide in every section; expected a segment");
    for (int i = first + 1; i < last; ++i) {
      const double frac = (ctrl[dref].row(i) - ctrl[dref].row(first)).dot(seg) / seg.squaredNorm();
      for (int d = 0; d < q; ++d) {
        const Eigen::RowVector3d a = ctrl[d].row(first), b = ctrl[d].row(last);
        const double err = (ctrl[d].row(i) - (a + frac * (b - a))).norm();
        if (err > 1e-9 * std::max(1.0, ctrl[d].cwiseAbs().maxCoeff()))
          fail("straight_groups[", gi, "]: row ", i, " is not at one fraction of the segment from row ", first, " to row ", last,
               " in every section (off by ", err, " m at section ", d, "); expected straight zones");
      }
      derived.push_back({i, frac, first, last});
      for (int k = 0; k < 3; ++k) runs[3 * i + k].clear();
    }
  }
  return derived;
}

/// Longitudinal knots: a knot at every interior section parameter (multiplicity degree_v - 1
/// at C1 joints, degree_v at C0 ones), one more in the interval next to each end of a held
/// run, clamped ends.
Eigen::VectorXd longitudinal_knots(const Eigen::VectorXd& v, const SkinOptions& o,
                                   const std::vector<std::vector<HeldRun>>& runs) {
  const int q = static_cast<int>(v.size()), pv = o.degree_v;
  std::set<int> joints, knuckles;
  for (int j : o.c1_sections) {
    if (j < 1 || j > q - 2) fail("c1_sections contains ", j, "; expected interior section indices 1..", q - 2);
    joints.insert(j);
  }
  for (int j : o.c0_sections) {
    if (j < 1 || j > q - 2) fail("c0_sections contains ", j, "; expected interior section indices 1..", q - 2);
    knuckles.insert(j);
  }
  std::vector<double> kv(pv + 1, 0.0);
  for (int d = 1; d < q - 1; ++d) {
    const int mult = knuckles.count(d) ? pv : joints.count(d) ? pv - 1 : 1;
    for (int r = 0; r < mult; ++r) kv.push_back(v[d]);
  }
  // One knot in the middle of the interval after each held run and before it: the run's
  // controls are fixed, and this knot gives the curve beyond one free control, so it leaves
  // the run with C^(degree_v - 1) continuity through a well-posed boundary value problem
  // (without it the curve would be an initial value spline, growing by ~3.7 per interval).
  // Between two runs of one row that meet (the next starts one station on, at another value)
  // two knots, at a third and two thirds: with one, a control held by both runs would hold two
  // values and leave a station up to 1e-6 of the extent off its row (33 um steps on designed hulls).
  std::set<double> extra;
  for (const auto& col_runs : runs) {
    // run r meets run r + 1: the next starts one station after it ends
    auto meets_next = [&](std::size_t r) { return r + 1 < col_runs.size() && col_runs[r + 1].first == col_runs[r].last + 1; };
    for (std::size_t r = 0; r < col_runs.size(); ++r) {
      const HeldRun& h = col_runs[r];
      if (meets_next(r)) {
        extra.insert(v[h.last] + (v[h.last + 1] - v[h.last]) / 3.0);
        extra.insert(v[h.last] + 2.0 * (v[h.last + 1] - v[h.last]) / 3.0);
      } else if (h.last < q - 1) {
        extra.insert(0.5 * (v[h.last] + v[h.last + 1]));
      }
      if (h.first > 0 && !(r > 0 && meets_next(r - 1))) extra.insert(0.5 * (v[h.first - 1] + v[h.first]));
    }
  }
  kv.insert(kv.end(), extra.begin(), extra.end());
  std::sort(kv.begin() + pv + 1, kv.end());
  for (int r = 0; r <= pv; ++r) kv.push_back(1.0);
  return Eigen::Map<Eigen::VectorXd>(kv.data(), static_cast<Eigen::Index>(kv.size()));
}

/// Recent factorisations of the longitudinal KKT matrix, kept by its exact value: a hull
/// rebuilt with only its sections' offsets changed (the designer's match loop, a slider) has
/// the same stations, knots and held runs, so the same matrix. A hit returns the factorisation
/// a miss would compute from those very bytes, so the solution is bit for bit the same.
class KktCache {
 public:
  static constexpr std::size_t kSize = 16;  ///< matrices kept (a hull has a few column groups)

  std::shared_ptr<const Eigen::PartialPivLU<Eigen::MatrixXd>> get(const Eigen::MatrixXd& K) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      for (auto it = entries_.begin(); it != entries_.end(); ++it)
        if (same(it->first, K)) {
          auto hit = *it;
          entries_.erase(it);
          entries_.insert(entries_.begin(), hit);
          return hit.second;
        }
    }
    auto lu = std::make_shared<const Eigen::PartialPivLU<Eigen::MatrixXd>>(K);
    const std::lock_guard<std::mutex> lock(mutex_);
    entries_.insert(entries_.begin(), {K, lu});
    if (entries_.size() > kSize) entries_.pop_back();
    return lu;
  }

 private:
  static bool same(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
    // an empty matrix has no data pointer, and memcmp must not be given one
    return a.rows() == b.rows() && a.cols() == b.cols() &&
           (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * static_cast<std::size_t>(a.size())) == 0);
  }
  std::mutex mutex_;
  std::vector<std::pair<Eigen::MatrixXd, std::shared_ptr<const Eigen::PartialPivLU<Eigen::MatrixXd>>>> entries_;
};

KktCache& kkt_cache() {
  static KktCache cache;
  return cache;
}

/// The longitudinal least-squares problem shared by every column: objective
/// 1/2 c' H c - b' c with constraints C c = e. Interpolate: H = 2 G, C = [Nv; ends],
/// e = [data; 0]. Approximate: H = (2/q) Nv'Nv + 2 lam G, b = (2/q) Nv' data, C = ends.
/// Constraint rows are scaled to the fairness block's magnitude (cs): with E3 (entries ~ q^3)
/// the unscaled KKT pivots of the O(1) interpolation rows fall under a full-pivoting LU's rank threshold.
struct LongitudinalSystem {
  const SkinOptions& o;
  const Eigen::VectorXd& Kv;
  const Eigen::MatrixXd& data;
  int q, pv, nv;
  bool interp;
  Eigen::MatrixXd Nv, H;
  Eigen::RowVectorXd D0, D1;  ///< first derivative rows at v = 0 and v = 1 (parallel ends)
  Eigen::RowVectorXd J0, J1;  ///< jumps of the degree_v-th derivative at the first / last interior knot (not-a-knot ends)
  double cs;

  LongitudinalSystem(const SkinOptions& opt, const Eigen::VectorXd& knots, const Eigen::VectorXd& v,
                     const Eigen::MatrixXd& columns)
      : o(opt), Kv(knots), data(columns), q(static_cast<int>(v.size())), pv(opt.degree_v),
        nv(static_cast<int>(knots.size()) - opt.degree_v - 1), interp(opt.mode == SkinMode::Interpolate) {
    Nv.resize(q, nv);
    for (int d = 0; d < q; ++d) Nv.row(d) = basis_row(Kv, pv, v[d]);
    const double hq = 1.0 / (q - 1);  // makes E2 and h^2 E3 commensurate
    Eigen::MatrixXd G = o.e2 * detail::derivative_gram(Kv, pv, 2);
    if (o.e3 > 0) G += o.e3 * hq * hq * detail::derivative_gram(Kv, pv, 3);
    D0 = basis_row(Kv, pv, 0.0, 1);
    D1 = basis_row(Kv, pv, 1.0, 1);
    if (o.start == SkinEnd::NotAKnot) J0 = top_derivative_jump(true);
    if (o.end == SkinEnd::NotAKnot) J1 = top_derivative_jump(false);
    const double lam = o.smoothing * hq * hq * hq * hq;
    H = interp ? Eigen::MatrixXd(2.0 * G) : Eigen::MatrixXd((2.0 / q) * Nv.transpose() * Nv + 2.0 * lam * G);
    cs = std::max(1e-300, H.cwiseAbs().maxCoeff());
  }

  /// The degree_v-th derivative (constant on each span) on the span after the first interior
  /// knot minus on the span before it (`first`), or at the last interior knot; empty (no row)
  /// when the curve is one span. A knot of multiplicity > 1 there cannot join the spans.
  Eigen::RowVectorXd top_derivative_jump(bool first) const {
    const int lo = pv + 1, hi = static_cast<int>(Kv.size()) - pv - 2;  // interior knot indices
    if (lo > hi) return {};
    const int k = first ? lo : hi;
    const bool single = (k == lo || Kv[k - 1] < Kv[k]) && (k == hi || Kv[k + 1] > Kv[k]);
    if (!single)
      fail("end condition 'not_a_knot' at the ", first ? "first" : "last",
           " section, but the nearest interior knot is multiple (a C0 or C1 section next to the end); expected 'free'");
    const double before = 0.5 * (Kv[k - 1] + Kv[k]), after = 0.5 * (Kv[k] + Kv[k + 1]);
    // scaled to unit size like the interpolation rows (its entries go as 1 / span^degree_v)
    const Eigen::RowVectorXd jump = basis_row(Kv, pv, after, pv) - basis_row(Kv, pv, before, pv);
    return jump / jump.cwiseAbs().maxCoeff();
  }

  /// Constraint rows over all controls, each with its station (-1 for an end row).
  void constraint_rows(bool with_ends, std::vector<Eigen::RowVectorXd>& crow, std::vector<int>& data_row) const {
    if (interp)
      for (int d = 0; d < q; ++d) crow.push_back(Nv.row(d)), data_row.push_back(d);
    if (J0.size()) crow.push_back(J0), data_row.push_back(-1);
    if (J1.size()) crow.push_back(J1), data_row.push_back(-1);
    if (with_ends && o.start == SkinEnd::Parallel) crow.push_back(D0), data_row.push_back(-1);
    if (with_ends && o.end == SkinEnd::Parallel) crow.push_back(D1), data_row.push_back(-1);
  }

  [[noreturn]] void singular() const {
    if (interp)
      fail("the longitudinal interpolation problem is singular (", q, " sections, degree_v ", pv,
           "); expected distinct section parameters");
    fail("the longitudinal approximation problem is singular (", q, " sections, degree_v ", pv,
         ", smoothing ", o.smoothing, "); expected smoothing > 0 or more sections");
  }

  /// Whether the constraint row involves one of the controls `freev` (not only held ones).
  static bool involves(const Eigen::RowVectorXd& row, const std::vector<int>& freev) {
    double f = 0;
    for (int j : freev) f = std::max(f, std::abs(row[j]));
    return f > 1e-14 * row.cwiseAbs().maxCoeff();
  }

  /// Solves the columns `cols`, which share the held controls `mask` (values in held_val)
  /// and whether their ends are constrained, writing their controls into lon.
  void solve_group(const std::vector<char>& mask, bool with_ends, const std::vector<int>& cols,
                   const std::vector<Eigen::VectorXd>& held_val, Eigen::MatrixXd& lon) const {
    std::vector<int> freev;
    for (int j = 0; j < nv; ++j)
      if (!mask[j]) freev.push_back(j);
    const int nf = static_cast<int>(freev.size());
    // Keep the constraint rows that still involve a free control (a station inside a held
    // run is met by the held controls themselves).
    std::vector<Eigen::RowVectorXd> crow;
    std::vector<int> data_row;
    constraint_rows(with_ends, crow, data_row);
    std::vector<int> keep;
    for (std::size_t r = 0; r < crow.size(); ++r)
      if (involves(crow[r], freev)) keep.push_back(static_cast<int>(r));
    const int mc = static_cast<int>(keep.size());
    Eigen::MatrixXd K = Eigen::MatrixXd::Zero(nf + mc, nf + mc);
    for (int a = 0; a < nf; ++a)
      for (int b2 = 0; b2 < nf; ++b2) K(a, b2) = H(freev[a], freev[b2]);
    for (int r = 0; r < mc; ++r)
      for (int a = 0; a < nf; ++a) K(nf + r, a) = K(a, nf + r) = cs * crow[keep[r]][freev[a]];
    Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(nf + mc, cols.size());
    for (std::size_t c = 0; c < cols.size(); ++c) {
      const int col = cols[c];
      const Eigen::VectorXd& hv = held_val[col];
      Eigen::VectorXd b = Eigen::VectorXd::Zero(nv);
      if (!interp) b = (2.0 / q) * Nv.transpose() * data.col(col);
      const Eigen::VectorXd top = b - H * hv;  // hv is zero on the free controls
      for (int a = 0; a < nf; ++a) rhs(a, c) = top[freev[a]];
      for (int r = 0; r < mc; ++r) {
        const int dr = data_row[keep[r]];
        rhs(nf + r, c) = cs * ((dr >= 0 ? data(dr, col) : 0.0) - crow[keep[r]].dot(hv));
      }
    }
    // A singular system shows as a residual the solve cannot remove (the pivot-based rank is
    // unreliable here: E3 and interpolation rows differ by many orders of magnitude). Partial
    // pivoting first (a third of full pivoting's time on KCS's 30 held columns); full pivoting
    // where its residual is not met, and only then is the system singular.
    auto unmet = [&](const Eigen::MatrixXd& x) {
      return !x.allFinite() || (K * x - rhs).norm() > 1e-10 * (K.norm() * x.norm() + rhs.norm());
    };
    Eigen::MatrixXd sol = kkt_cache().get(K)->solve(rhs);
    if (unmet(sol)) sol = Eigen::FullPivLU<Eigen::MatrixXd>(K).solve(rhs);
    if (unmet(sol)) singular();
    for (std::size_t c = 0; c < cols.size(); ++c) {
      Eigen::VectorXd z = held_val[cols[c]];
      for (int a = 0; a < nf; ++a) z[freev[a]] = sol(a, c);
      lon.col(cols[c]) = z;
    }
  }

  /// Controls held by column col's runs (mask) and their values (val, zero elsewhere).
  void held(int col, const Eigen::VectorXd& v, const std::vector<std::vector<HeldRun>>& runs, std::vector<char>& mask,
            Eigen::VectorXd& val) const {
    mask.assign(nv, 0);
    val = Eigen::VectorXd::Zero(nv);
    for (const HeldRun& h : runs[col])
      for (int j = 0; j < nv; ++j)
        if (Kv[j] < v[h.last] && Kv[j + pv + 1] > v[h.first]) mask[j] = 1, val[j] = h.value;
  }

  /// lon (nv, 3 n): every column's longitudinal controls. Controls whose support meets a
  /// held run (open interval) are held at the run's value; columns that share a held set and
  /// end conditions share one factorisation.
  Eigen::MatrixXd solve(const Eigen::VectorXd& v, const std::vector<std::vector<HeldRun>>& runs) const {
    const Eigen::Index cols = data.cols();
    std::vector<std::vector<char>> held_mask(cols);
    std::vector<Eigen::VectorXd> held_val(cols);
    for (int col = 0; col < cols; ++col) held(col, v, runs, held_mask[col], held_val[col]);
    std::map<std::pair<std::vector<char>, bool>, std::vector<int>> groups;
    for (int col = 0; col < cols; ++col) groups[{held_mask[col], col % 3 != 0}].push_back(col);
    Eigen::MatrixXd lon(nv, cols);
    for (const auto& [key, members] : groups) solve_group(key.first, key.second, members, held_val, lon);
    return lon;
  }
};

/// Rows of straight groups as the same combination of their end rows' longitudinal curves.
void apply_straight_rows(const std::vector<DerivedRow>& derived, Eigen::MatrixXd& lon) {
  for (const DerivedRow& r : derived)
    for (int k = 0; k < 3; ++k) {
      const Eigen::VectorXd a = lon.col(3 * r.first + k), b = lon.col(3 * r.last + k);
      lon.col(3 * r.row + k) = a + r.frac * (b - a);  // a + s (b - a): exact where a == b (flats)
    }
}

/// SkinOptions::y_nonnegative: the surface looked at on kCentrePlaneSamples + 1 points per
/// knot span each way; where it dips below the centre plane, each row with a control below it
/// there is solved again near the dip with its controls bounded at y >= 0. All or nothing: a
/// skin kept off the plane in some rows only still crosses it.
class CentrePlaneKeeper {
 public:
  CentrePlaneKeeper(const LongitudinalSystem& sys, const Eigen::VectorXd& Ku, const Eigen::VectorXd& v,
                    const std::vector<std::vector<HeldRun>>& runs, const std::vector<DerivedRow>& derived)
      : sys_(sys), Ku_(Ku), v_(v), runs_(runs), derived_(derived),
        size_(std::max(1.0, sys.data.cwiseAbs().maxCoeff())), below_(-kCentrePlaneTolerance * size_) {
    for (const DerivedRow& d : derived) ends_of_[d.row] = {d.first, d.last};
  }

  /// lon (nv, 3 n) kept off the plane (up to kCentrePlanePasses looks), or left as it was.
  void keep(Eigen::MatrixXd& lon) {
    // Every y control on its side: so is the surface (convex hull), and nothing is sampled (the
    // designed hulls: half the skin's time otherwise).
    bool below = false;
    for (Eigen::Index c = 1; c < lon.cols() && !below; c += 3) below = lon.col(c).minCoeff() < below_;
    if (!below) return;
    Nvs_ = samples(sys_.Kv, sys_.pv, &span_);
    Nus_ = samples(Ku_, sys_.o.degree_u, nullptr);
    std::vector<Eigen::RowVectorXd> crow;
    std::vector<int> data_row;
    sys_.constraint_rows(true, crow, data_row);  // y columns keep their end conditions
    for (std::size_t r = 0; r < crow.size(); ++r)
      if (data_row[r] < 0) ends_.push_back(crow[r]);
    for (int pass = 0; pass < kCentrePlanePasses && !refused_; ++pass) {
      const std::map<int, std::vector<char>> dips = dipping(lon);
      if (dips.empty()) return;
      for (const auto& [col, dip] : dips) {
        original_.emplace(col, lon.col(col));  // the least-E2 controls, kept from the first pass
        lon.col(col) = bounded(col, lon.col(col), dip);
        if (refused_) break;
      }
      apply_straight_rows(derived_, lon);
    }
    if (!refused_ && !dipping(lon).empty()) refused_ = true, refused_miss_ = kInfinity;
    if (refused_) {
      for (const auto& [col, z] : original_) lon.col(col) = z;
      apply_straight_rows(derived_, lon);
      original_.clear();
      miss_ = 0;
    }
  }

  /// Columns moved (3 n flags; a straight group's interior row with its end rows).
  std::vector<char> moved(int cols) const {
    std::vector<char> out(cols, 0);
    for (const auto& kv : original_) out[kv.first] = 1;
    for (const DerivedRow& d : derived_)
      if (out[3 * d.first + 1] || out[3 * d.last + 1]) out[3 * d.row + 1] = 1;
    return out;
  }
  int columns() const { return static_cast<int>(original_.size()); }
  double miss() const { return miss_; }
  double refused_miss() const { return refused_ ? refused_miss_ : 0.0; }

 private:
  static constexpr double kInfinity = std::numeric_limits<double>::infinity();

  /// Basis rows at kCentrePlaneSamples + 1 points per non-empty knot span (and each one's span).
  static Eigen::MatrixXd samples(const Eigen::VectorXd& K, int p, std::vector<int>* span) {
    const int n = static_cast<int>(K.size()) - p - 1;
    std::vector<Eigen::RowVectorXd> rows;
    for (int k = p; k < n; ++k) {
      if (!(K[k + 1] > K[k])) continue;
      for (int i = 0; i <= kCentrePlaneSamples; ++i) {
        rows.push_back(basis_row(K, p, K[k] + (K[k + 1] - K[k]) * i / kCentrePlaneSamples));
        if (span) span->push_back(k);
      }
    }
    Eigen::MatrixXd out(static_cast<Eigen::Index>(rows.size()), n);
    for (std::size_t r = 0; r < rows.size(); ++r) out.row(static_cast<Eigen::Index>(r)) = rows[r];
    return out;
  }

  /// Per y column, the controls near which the surface dips below the plane: at a sampled
  /// (u, v) where it does, the controls whose support holds the point, in each row whose u
  /// basis is not zero there and which has a control below the plane among them (an
  /// interior row of a straight group stands for its end rows). Empty: on its side.
  std::map<int, std::vector<char>> dipping(const Eigen::MatrixXd& lon) const {
    const int n = static_cast<int>(lon.cols() / 3), pv = sys_.pv, nv = sys_.nv;
    Eigen::MatrixXd Y(Nvs_.rows(), n);  // each row's curve at the v samples
    for (int i = 0; i < n; ++i) Y.col(i) = Nvs_ * lon.col(3 * i + 1);
    std::map<int, std::vector<char>> dips;
    for (Eigen::Index r = 0; r < Y.rows(); ++r) {
      if (Y.row(r).minCoeff() >= below_) continue;  // every row on its side: so is the surface
      const Eigen::VectorXd ys = Nus_ * Y.row(r).transpose();
      const int j0 = span_[r] - pv;
      for (Eigen::Index su = 0; su < ys.size(); ++su) {
        if (ys[su] >= below_) continue;
        for (int i = 0; i < n; ++i) {
          if (!(Nus_(su, i) > 0)) continue;
          const auto e = ends_of_.find(i);
          for (int row : e == ends_of_.end() ? std::vector<int>{i} : std::vector<int>{e->second.first, e->second.second}) {
            if (lon.col(3 * row + 1).segment(j0, pv + 1).minCoeff() >= 0) continue;  // adds nothing below
            std::vector<char>& m = dips[3 * row + 1];
            m.resize(nv, 0);
            for (int j = j0; j <= span_[r]; ++j) m[j] = 1;
          }
        }
      }
    }
    return dips;
  }

  /// Column col's controls z solved again with the free controls within kCentrePlaneReach of
  /// the dip moving, bounded at y >= 0: the fairness objective plus the rows' misses weighted
  /// by kCentrePlaneRowWeight (interpolate mode), the end rows met exactly. Sets refused_
  /// (returning z) where that misses a row by more than kCentrePlaneMaxMiss of the size.
  Eigen::VectorXd bounded(int col, const Eigen::VectorXd& z, const std::vector<char>& dip) {
    const int nv = sys_.nv;
    std::vector<char> mask;
    Eigen::VectorXd val;
    sys_.held(col, v_, runs_, mask, val);
    // Only controls near the dip move: the rest of the row keeps its least-E2 interpolant
    // (a whole row re-solved softly moved by millimetres far from the fold and put lobes
    // into KCS's waterlines at the bulb).
    std::vector<int> freev;
    for (int j = 0; j < nv; ++j) {
      bool near = false;
      for (int k = std::max(0, j - kCentrePlaneReach); k <= std::min(nv - 1, j + kCentrePlaneReach) && !near; ++k)
        near = dip[k];
      if (near && !mask[j]) freev.push_back(j);
    }
    const int nf = static_cast<int>(freev.size());
    if (nf == 0) return refuse(z, kInfinity);  // held by its runs all about the dip
    Eigen::VectorXd hv = z;
    for (int a = 0; a < nf; ++a) hv[freev[a]] = 0.0;
    const Eigen::MatrixXd& data = sys_.data;
    const Eigen::MatrixXd &H = sys_.H, &Nv = sys_.Nv;
    const Eigen::VectorXd resid = Nv * hv - data.col(col);
    const double w = sys_.interp ? kCentrePlaneRowWeight * sys_.cs : 0.0;
    QuadraticProgram qp;
    qp.H.resize(nf, nf);
    qp.g.resize(nf);
    for (int a = 0; a < nf; ++a) {
      const int ja = freev[a];
      const double b = sys_.interp ? 0.0 : (2.0 / sys_.q) * Nv.col(ja).dot(data.col(col));
      qp.g[a] = H.row(ja).dot(hv) + w * Nv.col(ja).dot(resid) - b;
      for (int b2 = 0; b2 < nf; ++b2) qp.H(a, b2) = H(ja, freev[b2]) + w * Nv.col(ja).dot(Nv.col(freev[b2]));
    }
    end_rows(freev, hv, qp);
    qp.A = -Eigen::MatrixXd::Identity(nf, nf);
    qp.b = Eigen::VectorXd::Zero(nf);
    std::vector<int> warm;
    for (int a = 0; a < nf; ++a)
      if (z[freev[a]] < 0) warm.push_back(a);
    const QpSolution sol = solve_qp(qp, warm);
    if (sol.status != QpStatus::Optimal) return refuse(z, kInfinity);
    Eigen::VectorXd out = hv;
    for (int a = 0; a < nf; ++a) out[freev[a]] = std::max(0.0, sol.x[a]);  // the bound to round-off
    const double miss = (Nv * (out - original_.at(col))).cwiseAbs().maxCoeff();  // at the stations
    if (miss > kCentrePlaneMaxMiss * size_) return refuse(z, miss);
    miss_ = std::max(miss_, miss);
    return out;
  }

  /// The end rows (not-a-knot, parallel ends) that involve a moving control, as equalities.
  void end_rows(const std::vector<int>& freev, const Eigen::VectorXd& hv, QuadraticProgram& qp) const {
    std::vector<const Eigen::RowVectorXd*> keep;
    for (const Eigen::RowVectorXd& row : ends_)
      if (LongitudinalSystem::involves(row, freev)) keep.push_back(&row);
    const int nf = static_cast<int>(freev.size());
    qp.E.resize(static_cast<Eigen::Index>(keep.size()), nf);
    qp.e.resize(static_cast<Eigen::Index>(keep.size()));
    for (std::size_t k = 0; k < keep.size(); ++k) {
      for (int a = 0; a < nf; ++a) qp.E(k, a) = (*keep[k])[freev[a]];
      qp.e[k] = -keep[k]->dot(hv);
    }
  }

  Eigen::VectorXd refuse(const Eigen::VectorXd& z, double miss) {
    refused_ = true;
    refused_miss_ = std::max(refused_miss_, miss);
    return z;
  }

  const LongitudinalSystem& sys_;
  const Eigen::VectorXd& Ku_;
  const Eigen::VectorXd& v_;
  const std::vector<std::vector<HeldRun>>& runs_;
  const std::vector<DerivedRow>& derived_;
  double size_, below_;
  Eigen::MatrixXd Nvs_, Nus_;  ///< basis rows at the samples along v and across u
  std::vector<int> span_;      ///< each v sample's knot span (its controls: span - degree_v .. span)
  std::vector<Eigen::RowVectorXd> ends_;        ///< the end condition rows (not-a-knot, parallel)
  std::map<int, std::pair<int, int>> ends_of_;  ///< a straight group's interior row -> its end rows
  std::map<int, Eigen::VectorXd> original_;      ///< moved y columns -> their least-E2 controls
  bool refused_ = false;
  double refused_miss_ = 0, miss_ = 0;
};

/// The skinned surface and its diagnostics from the longitudinal controls.
SkinResult skin_result(const LongitudinalSystem& sys, const Eigen::VectorXd& Ku, const Eigen::VectorXd& v,
                       const Eigen::MatrixXd& lon, double fit_max, const std::vector<std::vector<HeldRun>>& runs,
                       const CentrePlaneKeeper* keeper) {
  const int n = static_cast<int>(lon.cols() / 3), nv = sys.nv, pv = sys.pv;
  Eigen::MatrixXd P(n * nv, 3);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < nv; ++j)
      for (int k = 0; k < 3; ++k) P(i * nv + j, k) = lon(j, 3 * i + k);
  SkinResult res{NurbsSurface(sys.o.degree_u, pv, Ku, sys.Kv, n, nv, P), v, fit_max, 0.0, Eigen::VectorXd(n)};
  const Eigen::MatrixXd fitted = sys.Nv * lon;
  // y of the rows the keeper moved: their miss is centre_plane_miss, not the interpolation's
  const std::vector<char> moved = keeper ? keeper->moved(static_cast<int>(lon.cols())) : std::vector<char>(lon.cols(), 0);
  double lmax = 0;
  for (int d = 0; d < sys.q; ++d)
    for (int i = 0; i < n; ++i) {
      Eigen::RowVector3d miss = fitted.block(d, 3 * i, 1, 3) - sys.data.block(d, 3 * i, 1, 3);
      if (moved[3 * i + 1]) miss[1] = 0.0;
      lmax = std::max(lmax, miss.norm());
    }
  res.longitudinal_max = lmax;
  if (keeper) {
    res.centre_plane_columns = keeper->columns();
    res.centre_plane_miss = keeper->miss();
    res.centre_plane_refused_miss = keeper->refused_miss();
  }
  // A KKT system too ill-conditioned for its solve can pass the residual test on its own scale
  // and still miss the rows: refuse rather than return a surface off its sections.
  const double extent = std::max(1.0, sys.data.cwiseAbs().maxCoeff());
  if (sys.interp && !(lmax <= kInterpolationTolerance * extent))
    fail("the longitudinal interpolation misses the sections by ", lmax, " m (", sys.q, " sections, degree_v ", pv,
         "); expected them met: sections too close together for their spacing, or conflicting end conditions");
  res.held_columns = 0;
  for (const auto& r : runs) res.held_columns += !r.empty();
  const Eigen::MatrixXd G2 = detail::derivative_gram(sys.Kv, pv, 2);
  for (int i = 0; i < n; ++i) {
    double e = 0;
    for (int k = 0; k < 3; ++k) e += lon.col(3 * i + k).dot(G2 * lon.col(3 * i + k));
    res.row_e2[i] = e;
  }
  return res;
}

}  // namespace

SkinResult fair_skin(const std::vector<NurbsCurve>& sections, const SkinOptions& o) {
  const int q = static_cast<int>(sections.size());
  const int largest = check_sections(sections);
  check_degrees_and_weights(o);
  // Sections already on one knot vector of degree degree_u (the hull's sections are designed
  // so): their control points are the rows, exactly. The refit (Kim & Hwangbo 2008: equal
  // arc-length resampling and a common-knot fit) only exists to make such a knot vector, and it ripples about flats and tight bilges.
  const bool exact = shared_knot_vector(sections, o);
  const int n = exact ? sections[0].n_control() : (o.n_control > 0 ? o.n_control : std::max(12, 2 * largest));
  const int m = o.samples > 0 ? o.samples : 4 * n;
  check_row_counts(o, n, m, exact);

  Eigen::VectorXd Ku;
  std::vector<Eigen::MatrixXd> ctrl(q);
  double fit_max = 0;
  if (exact) {
    Ku = sections[0].knots();
    for (int d = 0; d < q; ++d) ctrl[d] = sections[d].control_points();
  } else {
    fit_max = refit_sections(sections, o, n, m, Ku, ctrl);
  }
  const Eigen::VectorXd v = section_parameters(ctrl, o.params, n);
  const Eigen::MatrixXd data = data_columns(ctrl, n);
  std::vector<std::vector<HeldRun>> runs = held_runs(ctrl, data, o.hold_runs);
  const std::vector<DerivedRow> derived = straight_rows(ctrl, o, runs);
  const Eigen::VectorXd Kv = longitudinal_knots(v, o, runs);
  const LongitudinalSystem sys(o, Kv, v, data);
  Eigen::MatrixXd lon = sys.solve(v, runs);
  apply_straight_rows(derived, lon);
  if (!o.y_nonnegative) return skin_result(sys, Ku, v, lon, fit_max, runs, nullptr);
  CentrePlaneKeeper keeper(sys, Ku, v, runs, derived);
  keeper.keep(lon);
  return skin_result(sys, Ku, v, lon, fit_max, runs, &keeper);
}

}  // namespace fairlines
