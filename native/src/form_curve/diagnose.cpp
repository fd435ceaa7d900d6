// Input validation, closed-form feasibility conditions and the infeasibility report.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <numbers>
#include <sstream>

#include <Eigen/SVD>

#include "fairlines/errors.hpp"
#include "fairlines/limits.hpp"
#include "nurbs/checks.hpp"
#include "solver.hpp"

namespace fairlines {

const std::vector<std::string>& form_parameter_names() {
  static const std::vector<std::string> names = {"xB",     "yB",     "zB",  "xE",  "yE",   "zE", "alphaB",
                                                 "alphaE", "CAB",    "CAE", "Area", "xC",  "yC"};
  return names;
}

namespace {

std::string fmt(double v) { return detail::format_number(v, 10); }

[[noreturn]] void infeasible(const std::vector<std::string>& names, const std::string& why) {
  std::ostringstream os;
  os << "infeasible form parameters {";
  for (size_t i = 0; i < names.size(); ++i) os << (i ? ", " : "") << names[i];
  os << "}: " << why;
  throw InfeasibleFormParameters(os.str());
}

// Levenshtein distance (insertions, deletions, substitutions), case-insensitive.
size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diag = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t up = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (same ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

// "unknown form parameter 'Aera' (did you mean 'Area'?); expected one of ...".
[[noreturn]] void unknown_parameter(const std::string& key) {
  const auto& names = form_parameter_names();
  std::string list, nearest;
  size_t best = std::string::npos;
  for (const auto& nm : names) {
    list += (list.empty() ? "" : ", ") + nm;
    const size_t d = edit_distance(key, nm);
    if (d < best) best = d, nearest = nm;
  }
  std::string hint = best <= std::max<size_t>(2, key.size() / 2) ? " (did you mean '" + nearest + "'?)" : "";
  throw InvalidInput("unknown form parameter '" + key + "'" + hint + "; expected one of " + list);
}

// Magnitude limit of a form parameter in the unit of the offsets (see limits.hpp).
double magnitude_limit(const std::string& k) {
  if (k == "alphaB" || k == "alphaE") return limits::kMaxAngleDegrees;
  if (k == "Area") return limits::kMaxFormCurveLength * limits::kMaxFormCurveLength;
  return limits::kMaxFormCurveLength;  // coordinates, centroid; end curvature in 1/length
}

void check_magnitude(const std::string& k, double val) {
  if (!std::isfinite(val)) throw InvalidInput("form parameter " + k + "=" + fmt(val) + " is not a finite number");
  const double limit = magnitude_limit(k);
  if (std::abs(val) <= limit) return;
  const bool angle = k == "alphaB" || k == "alphaE";
  throw InvalidInput("form parameter " + k + "=" + fmt(val) + " is beyond the supported magnitude " + fmt(limit) +
                     (angle ? " degrees; angles are degrees from +x, expected within [-360, 360]"
                            : "; lengths are metres (or one consistent unit): check the units"));
}

void check_counts(const FormCurveRequest& req) {
  if (req.n_control > limits::kMaxFormCurveControlPoints)
    throw InvalidInput("n_control=" + std::to_string(req.n_control) + " is beyond the limit of " +
                       std::to_string(limits::kMaxFormCurveControlPoints) + " control points of a form-parameter curve");
  if (req.points.size() > static_cast<size_t>(limits::kMaxFormCurvePoints))
    throw InvalidInput("points has " + std::to_string(req.points.size()) + " entries; the limit is " +
                       std::to_string(limits::kMaxFormCurvePoints));
  if (req.options.max_iterations < 1 || req.options.max_iterations > limits::kMaxFormCurveIterations)
    throw InvalidInput("max_iterations=" + std::to_string(req.options.max_iterations) + "; expected 1 <= max_iterations <= " +
                       std::to_string(limits::kMaxFormCurveIterations));
  if (req.options.multistart < 0 || req.options.multistart > limits::kMaxFormCurveMultistart)
    throw InvalidInput("multistart=" + std::to_string(req.options.multistart) + "; expected 0 <= multistart <= " +
                       std::to_string(limits::kMaxFormCurveMultistart));
  if (req.params.empty() && req.points.empty() && req.tangent_start.size() == 0 && req.tangent_end.size() == 0)
    throw InvalidInput("the request is empty: no form parameter, point or tangent given; expected at least one of " +
                       std::string("xB, yB, xE, yE, alphaB, alphaE, CAB, CAE, Area, xC, yC or points"));
}

void check_shape(const FormCurveRequest& req) {
  if (req.dim != 2 && req.dim != 3)
    throw InvalidInput("dim=" + std::to_string(req.dim) + " is not supported; expected 2 or 3");
  if (req.degree < 2 || req.degree > 15)
    throw InvalidInput("degree=" + std::to_string(req.degree) + " is out of range; expected 2 <= degree <= 15");
  if (req.n_control < req.degree + 1)
    throw InvalidInput("n_control=" + std::to_string(req.n_control) + " is too small for degree " +
                       std::to_string(req.degree) + "; expected n_control >= " + std::to_string(req.degree + 1));
}

/// Checks every named form parameter; the scalar conditions they make (one each).
int parameter_conditions(const FormCurveRequest& req) {
  const auto& names = form_parameter_names();
  int m = 0;
  for (const auto& [k, val] : req.params) {
    if (std::find(names.begin(), names.end(), k) == names.end()) unknown_parameter(k);
    if ((k == "zB" || k == "zE") && req.dim != 3)
      throw InvalidInput("form parameter '" + k + "' needs dim=3 (got dim=" + std::to_string(req.dim) + ")");
    check_magnitude(k, val);
    ++m;
  }
  return m;
}

/// Checks the 3-D end tangents; the scalar conditions they make (two each).
int tangent_conditions(const FormCurveRequest& req) {
  int m = 0;
  for (const auto* t : {&req.tangent_start, &req.tangent_end}) {
    if (t->size() == 0) continue;
    const char* nm = t == &req.tangent_start ? "tangent_start" : "tangent_end";
    if (req.dim != 3) throw InvalidInput(std::string(nm) + " needs dim=3; use alphaB / alphaE for plane curves");
    if (t->size() != 3 || !t->allFinite() || t->norm() == 0)
      throw InvalidInput(std::string(nm) + " must be a finite non-zero 3-vector");
    m += 2;
  }
  return m;
}

/// Checks the points; the scalar conditions the interpolated ones make (each adds dim
/// equations and one unknown parameter).
int point_conditions(const FormCurveRequest& req) {
  int m = 0;
  for (size_t j = 0; j < req.points.size(); ++j) {
    const auto& pt = req.points[j];
    const std::string nm = "points[" + std::to_string(j) + "]";
    if (pt.position.size() != req.dim)
      throw InvalidInput(nm + " has " + std::to_string(pt.position.size()) + " coordinates; expected " +
                         std::to_string(req.dim));
    if (!pt.position.allFinite()) throw InvalidInput(nm + " has a non-finite coordinate");
    if (pt.position.cwiseAbs().maxCoeff() > limits::kMaxFormCurveLength)
      throw InvalidInput(nm + " has a coordinate beyond the supported magnitude " + fmt(limits::kMaxFormCurveLength) +
                         "; lengths are metres (or one consistent unit): check the units");
    if (std::isnan(pt.weight) || pt.weight <= 0)
      throw InvalidInput(nm + " weight=" + fmt(pt.weight) + " is invalid; expected > 0 (inf = interpolate)");
    if (std::isinf(pt.weight)) m += req.dim - 1;
  }
  return m;
}

void check_fairness_weights(const FairnessWeights& fw) {
  for (const auto& [nm, val] : {std::pair<const char*, double>{"e1", fw.e1}, {"e2", fw.e2}, {"e3", fw.e3},
                                {"length", fw.length}})
    if (!std::isfinite(val) || val < 0)
      throw InvalidInput(std::string("fairness weight ") + nm + "=" + fmt(val) + " is invalid; expected finite >= 0");
  if (fw.e1 + fw.e2 + fw.e3 <= 0)
    throw InvalidInput("fairness weights e1, e2, e3 are all zero; at least one must be > 0");
}

void check_bounds_and_tolerance(const FormCurveRequest& req) {
  if (req.bounds.monotone_axis < -1 || req.bounds.monotone_axis > 1)
    throw InvalidInput("bounds monotone axis=" + std::to_string(req.bounds.monotone_axis) +
                       "; expected -1 (none), 0 (x) or 1 (y)");
  if (!std::isfinite(req.bounds.min_end_speed) || req.bounds.min_end_speed < 0 || req.bounds.min_end_speed > 1)
    throw InvalidInput("bounds min_end_speed=" + fmt(req.bounds.min_end_speed) + "; expected 0 <= value <= 1");
  if (!(req.options.tolerance > 0) || !(req.options.tolerance < 1e-3))
    throw InvalidInput("tolerance=" + fmt(req.options.tolerance) + "; expected 0 < tolerance < 1e-3");
  if ((req.params.count("CAB") || req.params.count("CAE")) && req.degree < 2)
    throw InvalidInput("end curvatures need degree >= 2");
}

/// m scalar conditions must leave the control points freedom for fairing; and a start curve
/// given must fit the request.
void check_freedom(const FormCurveRequest& req, int m) {
  const int dof = req.dim * req.n_control;
  if (m >= dof + (m > 0 ? 0 : 1)) {
    std::ostringstream os;
    os << "n_control=" << req.n_control << " is too small: " << m << " scalar conditions on " << dof
       << " control-point coordinates leave no freedom for fairing; expected n_control >= "
       << (m / req.dim + 1);
    throw InvalidInput(os.str());
  }
  if (req.initial_control_points.size() > 0 &&
      (req.initial_control_points.rows() != req.n_control || req.initial_control_points.cols() != req.dim ||
       !req.initial_control_points.allFinite()))
    throw InvalidInput("initial_control_points must be a finite (n_control x dim) array");
}

}  // namespace

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

// The requested form parameters, read by name.
struct Named {
  const std::map<std::string, double>& P;
  bool has(const char* k) const { return P.count(k) > 0; }
  double v(const char* k) const { return P.at(k); }
};

// A monotone curve runs one way from start to end; its end angles must agree. Returns the
// direction of the monotone coordinate (+1 increasing, -1 decreasing).
double check_monotone_direction(const Named& q, int ax) {
  double sgn = 1;
  if (ax < 0) return sgn;
  const char* bn = ax == 0 ? "xB" : "yB";
  const char* en = ax == 0 ? "xE" : "yE";
  const char* an = ax == 0 ? "x" : "y";
  if (q.has(bn) && q.has(en)) {
    if (q.v(bn) == q.v(en))
      infeasible({bn, en}, std::string(an) + "-monotone curve needs " + en + " != " + bn + " (both " + fmt(q.v(bn)) +
                               "); pass bounds with monotone=None for a closed or returning curve");
    sgn = q.v(en) > q.v(bn) ? 1 : -1;
  }
  for (const char* a : {"alphaB", "alphaE"}) {
    if (!q.has(a)) continue;
    const double comp = ax == 0 ? std::cos(q.v(a) * kDegree) : std::sin(q.v(a) * kDegree);
    if (sgn * comp >= -1e-12) continue;
    std::ostringstream os;
    os << "the tangent " << a << "=" << fmt(q.v(a)) << " deg makes " << an << " run "
       << (sgn > 0 ? "backwards" : "forwards") << " at the " << (a[5] == 'B' ? "start" : "end") << ", but the curve must be "
       << an << "-monotone " << (sgn > 0 ? "increasing" : "decreasing") << "; achievable " << a << " range: "
       << (ax == 0 ? (sgn > 0 ? "[-90, 90]" : "[90, 270]") : (sgn > 0 ? "[0, 180]" : "[-180, 0]"));
    std::vector<std::string> names = {a};
    if (q.has(bn) && q.has(en)) names.insert(names.begin(), {bn, en});
    infeasible(names, os.str());
  }
  return sgn;
}

// End heights and end angles that the bound y >= 0 rules out.
void check_y_bound(const Named& q) {
  for (const char* k : {"yB", "yE"})
    if (q.has(k) && q.v(k) < 0)
      infeasible({k}, std::string(k) + "=" + fmt(q.v(k)) + " is below the bound y >= 0; achievable range [0, inf)");
  if (q.has("yB") && q.v("yB") == 0 && q.has("alphaB") && std::sin(q.v("alphaB") * kDegree) < -1e-12)
    infeasible({"yB", "alphaB"}, "starting on y = 0 with alphaB=" + fmt(q.v("alphaB")) +
                                     " deg would leave y >= 0; achievable alphaB range [0, 180]");
  if (q.has("yE") && q.v("yE") == 0 && q.has("alphaE") && std::sin(q.v("alphaE") * kDegree) > 1e-12)
    infeasible({"yE", "alphaE"}, "ending on y = 0 with alphaE=" + fmt(q.v("alphaE")) +
                                     " deg needs the curve below y = 0 just before; achievable alphaE range [-180, 0]");
}

// Cauchy-Schwarz / Bessel: over a graph, int y^2 dx >= (A^2/L)(1 + 12 ((xC - xm)/L)^2),
// equality for a straight line; hence yC >= (|A|/(2L))(1 + 12 ((xC - xm)/L)^2).
void check_centroid_height(const Named& q, double sgn, double L, double xm) {
  const double Aabs = sgn * q.v("Area");
  if (!(Aabs > 0)) return;
  const double dx = q.has("xC") ? (q.v("xC") - xm) / L : 0.0;
  const double ymin = Aabs / (2 * L) * (1 + 12 * dx * dx);
  if (q.v("yC") >= ymin * (1 - 1e-12)) return;
  std::ostringstream os;
  os << "a curve that does not fold back (x monotone from xB to xE) has int y^2 dx >= "
     << "(A^2/L)(1 + 12((xC - xm)/L)^2) (Cauchy-Schwarz; equality only for a straight line), so yC >= "
     << fmt(ymin) << " here; requested yC=" << fmt(q.v("yC")) << ". Achievable: yC in [" << fmt(ymin)
     << ", inf)";
  if (q.has("xC")) {
    const double r = L * std::sqrt(std::max(0.0, (2 * q.v("yC") * L / Aabs - 1) / 12));
    os << "; or, keeping yC and Area, xC in [" << fmt(xm - r) << ", " << fmt(xm + r) << "]";
    os << "; or, keeping xC and yC, |Area| <= " << fmt(2 * q.v("yC") * L / (1 + 12 * dx * dx));
  } else {
    os << "; or, keeping yC, |Area| <= " << fmt(2 * q.v("yC") * L);
  }
  std::vector<std::string> names = {"xB", "xE", "Area"};
  if (q.has("xC")) names.push_back("xC");
  names.push_back("yC");
  infeasible(names, os.str());
}

// Area and centroid conditions for a curve that is a graph y(x) over [xB, xE] (x-monotone).
void check_graph_integrals(const Named& q, double sgn, bool ynn) {
  const double x0 = std::min(q.v("xB"), q.v("xE")), x1 = std::max(q.v("xB"), q.v("xE"));
  const double L = x1 - x0, xm = 0.5 * (x0 + x1);
  if (ynn && q.has("Area")) {
    const double Aabs = sgn * q.v("Area");  // area in |dx|
    const bool positive_ends = (q.has("yB") && q.v("yB") > 0) || (q.has("yE") && q.v("yE") > 0);
    if (Aabs < 0 || (Aabs == 0 && (positive_ends || q.has("xC") || q.has("yC"))))
      infeasible({"xB", "xE", "Area"}, "with y >= 0 and x running from xB to xE the area must have the sign of "
                                       "xE - xB and be non-zero; requested Area=" +
                                           fmt(q.v("Area")) + ", achievable " + (sgn > 0 ? "(0, inf)" : "(-inf, 0)"));
  }
  if (ynn && q.has("xC") && !(q.v("xC") > x0 && q.v("xC") < x1))
    infeasible({"xB", "xE", "xC"}, "the centroid of an area under a curve with y >= 0 over x in [" + fmt(x0) + ", " +
                                       fmt(x1) + "] lies strictly inside that range; requested xC=" + fmt(q.v("xC")) +
                                       ", achievable (" + fmt(x0) + ", " + fmt(x1) + ")");
  if (ynn && q.has("yC") && !(q.v("yC") > 0))
    infeasible({"yC"}, "with y >= 0 the centroid height is positive; requested yC=" + fmt(q.v("yC")) +
                           ", achievable (0, inf)");
  if (q.has("Area") && q.has("yC") && q.v("Area") != 0) check_centroid_height(q, sgn, L, xm);
}

}  // namespace

void check_form_parameters_feasible(const FormCurveRequest& req) {
  const Named q{req.params};
  const int ax = req.bounds.monotone_axis;
  const double sgn = check_monotone_direction(q, ax);
  if (req.bounds.y_nonnegative) check_y_bound(q);
  if (ax == 0 && q.has("xB") && q.has("xE")) check_graph_integrals(q, sgn, req.bounds.y_nonnegative);
}

namespace form_curve_impl {

void validate_request(const FormCurveRequest& req) {
  check_shape(req);
  check_counts(req);
  // scalar conditions on the curve, to be left freedom for fairing
  int m = parameter_conditions(req);
  m += tangent_conditions(req);
  m += point_conditions(req);
  check_fairness_weights(req.fairness);
  check_bounds_and_tolerance(req);
  check_freedom(req, m);
}

std::string failure_report(Solver& solver, const RunOutcome& best) {
  Problem& pb = solver.pb;
  std::ostringstream os;
  std::vector<std::string> moved;
  for (const auto& k : pb.cons)
    if (k.kind != ConKind::Linear && std::abs(k.requested - k.start) > 1e-14 * (1 + std::abs(k.requested)))
      moved.push_back(k.name);
  // constraint gradients that became (nearly) dependent at the last point
  std::vector<std::string> dependent;
  if (solver.m > 0 && best.z.size() == pb.nv) {
    Eigen::VectorXd c;
    Eigen::MatrixXd J;
    pb.constraints(best.z, c, &J, nullptr, nullptr);
    for (int i = 0; i < solver.m; ++i) J.row(i) /= std::max(J.row(i).norm(), 1e-300);
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J.transpose(), Eigen::ComputeThinV);
    const Eigen::VectorXd sv = svd.singularValues();
    if (sv.size() > 0 && sv[sv.size() - 1] < 1e-3) {
      const Eigen::VectorXd w = svd.matrixV().col(sv.size() - 1);
      for (int i = 0; i < solver.m; ++i)
        if (std::abs(w[i]) > 0.1) dependent.push_back(pb.cons[i].name);
    }
  }
  os << "infeasible form parameters {";
  const auto& names = dependent.empty() ? moved : dependent;
  for (size_t i = 0; i < names.size(); ++i) os << (i ? ", " : "") << names[i];
  os << "}: no curve with " << pb.n << " control points of degree " << pb.p
     << " meeting the section bounds was found (continuation from the fairest start curve stalled at "
     << fmt(100 * best.tau) << "% of the way to the requested values, after further random starts). Reached";
  for (const auto& k : pb.cons)
    if (k.kind != ConKind::Linear)
      os << " " << k.name << "=" << fmt(k.start + best.tau * (k.requested - k.start)) << " (requested "
         << fmt(k.requested) << ", start curve " << fmt(k.start) << ");";
  if (!dependent.empty()) os << " their constraint gradients become linearly dependent there.";
  os << " Try fewer parameters, more control points or values nearer the reached ones.";
  return os.str();
}

}  // namespace form_curve_impl
}  // namespace fairlines
