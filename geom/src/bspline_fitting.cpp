#include "cncc/geom/bspline_fitting.h"

#include "cncc/geom/arc_length.h"
#include "cncc/geom/bspline_basis.h"
#include "cncc/geom/curve_deviation.h"
#include "cncc/geom/geometry_error.h"

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <optional>

namespace cncc::geom {

namespace {

using Vector = Eigen::Vector3d;

constexpr int kSamplesPerSpan = 16;
constexpr int kInitialSpans = 8;
constexpr int kMaxFits = 120;
constexpr int kNewtonSteps = 3;
// Per-span measurement aims slightly inside the tolerance; the full measurement decides.
constexpr double kSearchMargin = 0.995;
// A span fitted almost exactly still counts as this fraction of a span when knots are
// redistributed, so that it cannot swallow its neighbours.
constexpr double kSmallestSpanShare = 0.05;
constexpr int kAttemptsPerCount = 2;

// Fit parameter t <-> curve parameter u. For arc length, a table of s(u) at
// kArcLengthTableSteps equal steps of u, interpolated linearly both ways: the fit
// parameter need only be close to arc length (parameter correction refines the
// samples' parameters anyway), and exact lookups would dominate the fitting time.
constexpr int kArcLengthTableSteps = 4096;

class ParameterMap {
public:
  ParameterMap(const Curve& curve, FitParameterisation kind) : domain_(curve.domain()) {
    if (kind != FitParameterisation::ArcLength)
      return;
    ArcLengthTable table(curve);
    for (int k = 0; k <= kArcLengthTableSteps; ++k) {
      double u = k == kArcLengthTableSteps
                     ? domain_.t1
                     : domain_.t0 + domain_.length() * k / kArcLengthTableSteps;
      curveParameters_.push_back(u);
      lengths_.push_back(table.lengthAt(u));
    }
  }
  ParameterRange fitDomain() const {
    return lengths_.empty() ? domain_ : ParameterRange{0.0, lengths_.back()};
  }
  double curveParameter(double t) const { return interpolate(lengths_, curveParameters_, t); }
  double fitParameter(double u) const { return interpolate(curveParameters_, lengths_, u); }

private:
  // y(x) from the increasing table xs, ys; identity without a table.
  static double interpolate(const std::vector<double>& xs, const std::vector<double>& ys,
                            double x) {
    if (xs.empty())
      return x;
    std::size_t i = std::size_t(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
    i = std::clamp<std::size_t>(i, 1, xs.size() - 1) - 1;
    double width = xs[i + 1] - xs[i];
    double fraction = width > 0.0 ? std::clamp((x - xs[i]) / width, 0.0, 1.0) : 0.0;
    return ys[i] + fraction * (ys[i + 1] - ys[i]);
  }

  ParameterRange domain_;
  std::vector<double> curveParameters_;
  std::vector<double> lengths_;
};

struct Sample {
  double t; // fit parameter
  Vector point;
};

class Fitter {
public:
  Fitter(const Curve& curve, const BSplineFitOptions& options)
      : curve_(curve), options_(options), map_(curve, options.parameterisation),
        proximity_(curve, options.tolerance * 1e-3), limit_(kSearchMargin * options.tolerance) {
    // The curve's own breakpoints (where a higher derivative jumps) stay knots.
    std::vector<double> cuts = curve.breakpoints();
    for (std::size_t i = 1; i + 1 < cuts.size(); ++i)
      mandatory_.push_back(map_.fitParameter(cuts[i]));
  }

  BSplineFit run() {
    ParameterRange range = map_.fitDomain();
    std::vector<double> breaks =
        redistribute({range.t0, range.t1}, {limit_}, kInitialSpans + int(mandatory_.size()));
    std::optional<BSplineFit> best;
    std::map<int, int> failures;
    for (int fits = 1; fits <= kMaxFits; ++fits) {
      NurbsCurve spline = fit(breaks);
      std::vector<double> errors = spanErrors(spline, breaks);
      int spans = int(breaks.size()) - 1;
      int needed = estimatedSpans(errors);
      int next;
      if (passes(spline, errors, best, fits)) {
        next = std::min(spans - 1, needed);
        if (next < minimumSpans() || failures[next] >= kAttemptsPerCount)
          break;
      } else {
        int attempts = ++failures[spans];
        next = std::max(spans, needed);
        if (attempts >= kAttemptsPerCount)
          next = std::max(next, spans + 1);
        if (best) {
          next = std::min(next, int(best->spline.knots().breakpoints().size()) - 2);
          if (next < spans || (next == spans && attempts >= kAttemptsPerCount))
            break;
        }
      }
      breaks = redistribute(breaks, errors, next);
    }
    if (!best)
      throw GeometryError("no B-spline within the tolerance was found");
    return *best;
  }

private:
  int degree() const { return options_.degree; }
  int minimumSpans() const { return int(mandatory_.size()) + 1; }

  // Whether the fit is within the tolerance (per span, then measured in full); keeps
  // it in `best` if it has fewer spans.
  bool passes(const NurbsCurve& spline, const std::vector<double>& errors,
              std::optional<BSplineFit>& best, int fits) const {
    if (*std::max_element(errors.begin(), errors.end()) > limit_)
      return false;
    double deviation =
        measureCurveDeviation(spline, curve_, proximity_, {options_.tolerance * 1e-3})
            .maxDeviation();
    if (deviation > options_.tolerance)
      return false;
    if (!best || spline.controlPoints().size() < best->spline.controlPoints().size())
      best = BSplineFit{spline, deviation, fits};
    else
      best->fits = fits;
    return true;
  }

  std::vector<Sample> samples(const std::vector<double>& breaks) const {
    std::vector<Sample> result;
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
      for (int k = 0; k < kSamplesPerSpan; ++k) {
        double t = breaks[i] + (breaks[i + 1] - breaks[i]) * k / kSamplesPerSpan;
        result.push_back({t, curve_.point(map_.curveParameter(t))});
      }
    double end = breaks.back();
    result.push_back({end, curve_.point(curve_.domain().t1)});
    result.front().point = curve_.point(curve_.domain().t0);
    return result;
  }

  KnotVector knotsFor(const std::vector<double>& breaks) const {
    std::vector<double> knots(std::size_t(degree()), breaks.front());
    knots.insert(knots.end(), breaks.begin(), breaks.end());
    knots.insert(knots.end(), std::size_t(degree()), breaks.back());
    return KnotVector(std::move(knots), degree());
  }

  // Least squares for the inner control points, ends fixed to the end samples.
  // Returns nothing if the normal equations are singular.
  std::optional<std::vector<Vector>> solve(const KnotVector& knots,
                                           const std::vector<Sample>& data) const {
    int p = degree();
    int last = knots.controlPointCount() - 1;
    int unknowns = last - 1;
    const Vector& first = data.front().point;
    const Vector& end = data.back().point;
    std::vector<Eigen::Triplet<double>> entries;
    Eigen::MatrixX3d right = Eigen::MatrixX3d::Zero(unknowns, 3);
    for (const Sample& s : data) {
      int span = knots.findSpan(s.t);
      BasisValues basis = basisFunctions(knots, span, s.t);
      Vector residual = s.point;
      for (int a = 0; a <= p; ++a) {
        int index = span - p + a;
        if (index == 0)
          residual -= basis[a] * first;
        else if (index == last)
          residual -= basis[a] * end;
      }
      for (int a = 0; a <= p; ++a) {
        int row = span - p + a - 1;
        if (row < 0 || row >= unknowns)
          continue;
        right.row(row) += basis[a] * residual.transpose();
        for (int b = 0; b <= p; ++b) {
          int column = span - p + b - 1;
          if (column >= 0 && column < unknowns)
            entries.emplace_back(row, column, basis[a] * basis[b]);
        }
      }
    }
    Eigen::SparseMatrix<double> normal(unknowns, unknowns);
    normal.setFromTriplets(entries.begin(), entries.end());
    Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal);
    if (solver.info() != Eigen::Success)
      return std::nullopt;
    Eigen::MatrixX3d inner = solver.solve(right);
    if (solver.info() != Eigen::Success || !inner.allFinite())
      return std::nullopt;
    std::vector<Vector> controls{first};
    for (int i = 0; i < unknowns; ++i)
      controls.push_back(inner.row(i).transpose());
    controls.push_back(end);
    return controls;
  }

  // Moves each inner sample's parameter to its closest point on the spline (Newton).
  static void correctParameters(const NurbsCurve& spline, std::vector<Sample>& data) {
    ParameterRange range = spline.domain();
    for (std::size_t j = 1; j + 1 < data.size(); ++j) {
      double t = data[j].t;
      for (int step = 0; step < kNewtonSteps; ++step) {
        CurveDerivatives d = spline.derivatives(t);
        Vector r = d.point - data[j].point;
        double slope = d.first.dot(r);
        double curvatureTerm = d.first.squaredNorm() + d.second.dot(r);
        if (!(curvatureTerm > 0.0))
          break;
        t = range.clamp(t - slope / curvatureTerm);
      }
      data[j].t = t;
    }
  }

  NurbsCurve fit(const std::vector<double>& breaks) const {
    KnotVector knots = knotsFor(breaks);
    std::vector<Sample> data = samples(breaks);
    std::optional<std::vector<Vector>> controls = solve(knots, data);
    if (!controls)
      throw GeometryError("the least-squares B-spline system is singular");
    NurbsCurve spline = NurbsCurve::bspline(knots, *controls);
    for (int round = 0; round < options_.parameterCorrections; ++round) {
      correctParameters(spline, data);
      std::optional<std::vector<Vector>> corrected = solve(knots, data);
      if (!corrected)
        break;
      spline = NurbsCurve::bspline(knots, *corrected);
    }
    return spline;
  }

  std::vector<double> spanErrors(const NurbsCurve& spline,
                                 const std::vector<double>& breaks) const {
    std::vector<double> errors;
    for (std::size_t i = 0; i + 1 < breaks.size(); ++i)
      errors.push_back(
          largestDistanceToCurve(spline, breaks[i], breaks[i + 1], proximity_).distance);
    return errors;
  }

  // Spans the errors ask for: each span's share (e_i / limit)^(1/(p+1)).
  std::vector<double> spanShares(const std::vector<double>& errors) const {
    std::vector<double> shares;
    for (double e : errors)
      shares.push_back(std::pow(e / limit_, 1.0 / (degree() + 1)));
    return shares;
  }

  int estimatedSpans(const std::vector<double>& errors) const {
    double total = 0.0;
    for (double share : spanShares(errors))
      total += share;
    return std::max(minimumSpans(), int(std::ceil(total)));
  }

  // `spans` new spans (at least one between neighbouring mandatory knots) splitting
  // the integral of the piecewise constant density share_i / h_i evenly within each
  // piece between mandatory knots; pieces get spans by their share of the integral
  // (largest remainders).
  std::vector<double> redistribute(const std::vector<double>& breaks,
                                   const std::vector<double>& errors, int spans) const {
    std::vector<double> shares = spanShares(errors);
    std::vector<double> cumulative{0.0};
    for (double share : shares)
      cumulative.push_back(cumulative.back() + std::max(share, kSmallestSpanShare));
    // Inverse and forward maps of the cumulative density (piecewise linear).
    auto integralAt = [&](double t) {
      std::size_t i =
          std::size_t(std::upper_bound(breaks.begin(), breaks.end(), t) - breaks.begin());
      i = std::clamp<std::size_t>(i, 1, breaks.size() - 1) - 1;
      double fraction = (t - breaks[i]) / (breaks[i + 1] - breaks[i]);
      return cumulative[i] + fraction * (cumulative[i + 1] - cumulative[i]);
    };
    auto parameterAt = [&](double value) {
      std::size_t i = std::size_t(std::upper_bound(cumulative.begin(), cumulative.end(), value) -
                                  cumulative.begin());
      i = std::clamp<std::size_t>(i, 1, cumulative.size() - 1) - 1;
      double fraction = (value - cumulative[i]) / (cumulative[i + 1] - cumulative[i]);
      return breaks[i] + fraction * (breaks[i + 1] - breaks[i]);
    };
    std::vector<double> ends{breaks.front()};
    ends.insert(ends.end(), mandatory_.begin(), mandatory_.end());
    ends.push_back(breaks.back());
    std::size_t pieces = ends.size() - 1;
    spans = std::max(spans, int(pieces));
    std::vector<double> pieceIntegral;
    for (std::size_t j = 0; j < pieces; ++j)
      pieceIntegral.push_back(integralAt(ends[j + 1]) - integralAt(ends[j]));
    std::vector<int> counts = apportion(pieceIntegral, spans);
    std::vector<double> result{breaks.front()};
    for (std::size_t j = 0; j < pieces; ++j) {
      double from = integralAt(ends[j]);
      for (int k = 1; k < counts[j]; ++k)
        result.push_back(parameterAt(from + pieceIntegral[j] * k / counts[j]));
      result.push_back(ends[j + 1]);
    }
    return result;
  }

  // Splits `total` >= weights.size() into one count per weight, each at least 1, by
  // the largest remainder method.
  static std::vector<int> apportion(const std::vector<double>& weights, int total) {
    double sum = 0.0;
    for (double w : weights)
      sum += w;
    int spare = total - int(weights.size());
    std::vector<int> counts;
    std::vector<std::pair<double, std::size_t>> remainders;
    int given = 0;
    for (std::size_t j = 0; j < weights.size(); ++j) {
      double exact = sum > 0.0 ? spare * weights[j] / sum : 0.0;
      counts.push_back(1 + int(std::floor(exact)));
      given += counts.back() - 1;
      remainders.push_back({exact - std::floor(exact), j});
    }
    std::sort(remainders.begin(), remainders.end(), std::greater<>());
    for (int k = 0; k < spare - given; ++k)
      ++counts[remainders[std::size_t(k) % remainders.size()].second];
    return counts;
  }

  const Curve& curve_;
  const BSplineFitOptions& options_;
  ParameterMap map_;
  CurveProximity proximity_;
  double limit_;
  std::vector<double> mandatory_; // fit parameters of the curve's interior breakpoints
};

} // namespace

BSplineFit fitBSpline(const Curve& curve, const BSplineFitOptions& options) {
  if (options.degree != 2 && options.degree != 3)
    throw GeometryError("B-spline fitting supports degree 2 or 3");
  if (!(options.tolerance > 0.0) || !std::isfinite(options.tolerance))
    throw GeometryError("the fitting tolerance must be positive");
  if (options.parameterisation != FitParameterisation::FewestControlPoints)
    return Fitter(curve, options).run();
  BSplineFitOptions arcLength = options;
  arcLength.parameterisation = FitParameterisation::ArcLength;
  BSplineFitOptions ownParameter = options;
  ownParameter.parameterisation = FitParameterisation::CurveParameter;
  BSplineFit byArcLength = Fitter(curve, arcLength).run();
  BSplineFit byOwnParameter = Fitter(curve, ownParameter).run();
  int fits = byArcLength.fits + byOwnParameter.fits;
  BSplineFit& fewer =
      byOwnParameter.spline.controlPoints().size() < byArcLength.spline.controlPoints().size()
          ? byOwnParameter
          : byArcLength;
  fewer.fits = fits;
  return fewer;
}

} // namespace cncc::geom
