#pragma once

#include "cncc/geom/curve.h"

#include <memory>
#include <vector>

namespace cncc::geom {

/// Curves joined end to start into one path. The global parameter runs through the
/// pieces in order, each piece keeping its own parameter length: piece i covers
/// [T_i, T_i + (t1_i - t0_i)] with T_0 = 0 and global t maps to t0_i + (t - T_i).
/// Joins are breakpoints; at a join the later piece is evaluated.
class CompositeCurve : public Curve {
public:
  /// Throws GeometryError if pieces is empty or a piece does not start within
  /// `joinTolerance` of where the previous one ends.
  explicit CompositeCurve(std::vector<std::shared_ptr<const Curve>> pieces,
                          double joinTolerance = 1e-9);

  std::size_t pieceCount() const { return pieces_.size(); }
  const Curve& piece(std::size_t i) const { return *pieces_[i]; }
  /// Index of the piece holding global parameter t and the piece's own parameter.
  std::pair<std::size_t, double> locate(double t) const;

  ParameterRange domain() const override { return {0.0, starts_.back()}; }
  Eigen::Vector3d point(double t) const override;
  Eigen::Vector3d derivative(double t) const override;
  Eigen::Vector3d secondDerivative(double t) const override;
  CurveDerivatives derivatives(double t) const override;
  std::vector<double> breakpoints() const override;

private:
  std::vector<std::shared_ptr<const Curve>> pieces_;
  std::vector<double> starts_; // global start of each piece, then the global end
};

/// The pieces of a CompositeCurve, or the curve itself when it is not one.
inline std::vector<const Curve*> piecesOf(const Curve& curve) {
  std::vector<const Curve*> pieces;
  if (const auto* composite = dynamic_cast<const CompositeCurve*>(&curve)) {
    for (std::size_t i = 0; i < composite->pieceCount(); ++i) {
      pieces.push_back(&composite->piece(i));
    }
  } else {
    pieces.push_back(&curve);
  }
  return pieces;
}

} // namespace cncc::geom
