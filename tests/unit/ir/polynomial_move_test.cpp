// move.polynomial in the IR: a non-rational cubic converted to spans, a
// span made to start elsewhere with its tangents kept, the text round
// trip, and the interpreter following the cubic from where the machine is.
#include "cncc/geom/geometry_error.h"
#include "cncc/geom/nurbs_curve.h"
#include "cncc/ir/interpreter.h"
#include "cncc/ir/polynomial_move.h"
#include "cncc/ir/printer.h"
#include "cncc/ir/verifier.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace cncc::ir {
namespace {

using ::testing::HasSubstr;
using ::testing::IsEmpty;

// A cubic B-spline of three spans (interior knots 0.25 and 0.5).
geom::NurbsCurve threeSpans() {
  return geom::NurbsCurve::bspline(
      geom::KnotVector({0, 0, 0, 0, 0.25, 0.5, 1, 1, 1, 1}, 3),
      {{0, 0, 0}, {5, 10, 0}, {15, 12, -1}, {25, 0, 0}, {30, -8, 1}, {40, 0, 0}});
}

TEST(PolynomialMoveTest, SpansFollowTheCurveExactly) {
  geom::NurbsCurve curve = threeSpans();
  std::vector<PolynomialMove> spans = polynomialMoves(curve);
  ASSERT_EQ(spans.size(), 3u);
  const double knots[] = {0, 0.25, 0.5, 1};
  for (std::size_t i = 0; i < spans.size(); ++i) {
    for (double t : {1.0, 0.7, 0.5, 0.2, 0.0}) {
      // t runs from 1 at the span's start to 0 at its end.
      double s = knots[i] + (1 - t) * (knots[i + 1] - knots[i]);
      EXPECT_LT((spans[i].pointAt(t) - curve.point(s)).norm(), 1e-12) << i << " " << t;
    }
    if (i > 0) {
      EXPECT_LT((spans[i].start() - spans[i - 1].end).norm(), 1e-12);
      EXPECT_LT(polynomialTransitionDegrees(spans[i - 1], spans[i]), 1e-6);
    }
  }
  EXPECT_THROW(polynomialMoves(geom::NurbsCurve(geom::KnotVector({0, 0, 0, 1, 1, 1}, 2),
                                                {{0, 0, 0}, {1, 1, 0}, {2, 0, 0}}, {1, 0.5, 1})),
               geom::GeometryError);
}

TEST(PolynomialMoveTest, StartAtKeepsTheTangentsAndMovesNoPointFurther) {
  PolynomialMove span = polynomialMoves(threeSpans()).front();
  PolynomialMove moved = span;
  Eigen::Vector3d shift(3e-5, -2e-5, 1e-5);
  moved.startAt(span.start() + shift);
  EXPECT_LT((moved.start() - span.start() - shift).norm(), 1e-15);
  EXPECT_LT((moved.end - span.end).norm(), 1e-15);
  EXPECT_LT((moved.startDirection() - span.startDirection()).norm(), 1e-12);
  EXPECT_LT((moved.endDirection() - span.endDirection()).norm(), 1e-12);
  for (double t = 0; t <= 1; t += 0.125) {
    EXPECT_LE((moved.pointAt(t) - span.pointAt(t)).norm(), shift.norm() + 1e-15);
  }
  PolynomialMove corner = span;
  corner.coefficients[2] = Eigen::Vector3d(-1, 0, 0); // ends heading +X
  PolynomialMove next;
  next.end = corner.end + Eigen::Vector3d(0, 1, 0);
  next.coefficients[2] = Eigen::Vector3d(0, -1, 0); // a straight line heading +Y
  EXPECT_NEAR(polynomialTransitionDegrees(corner, next), 90, 1e-9);
}

constexpr const char* spanPart = R"(func @span() {
  %zero = const 0
  %ten = const 10
  %safe = const 5
  %feed = const 200
  %k3 = const 2
  %k2 = const -3
  %k1 = const 11
  %two = const 2
  %minusTwo = const -2
  move.rapid %ten, %zero, %safe
  move.feed %ten, %zero, %zero, %feed
  move.polynomial %zero, %zero, %zero, %k3, %k2, %k1, %two, %minusTwo, %zero, %zero, %zero, %zero, %feed
}
)";

TEST(PolynomialMoveTest, PrintsParsesVerifiesAndInterprets) {
  ParseError error;
  std::optional<Function> function = parseFunction(spanPart, error);
  ASSERT_TRUE(function) << error.line << ": " << error.message;
  EXPECT_THAT(verifyFunction(*function), IsEmpty());
  std::string text = printFunction(*function);
  EXPECT_THAT(text, HasSubstr("move.polynomial %"));
  std::optional<Function> again = parseFunction(text, error);
  ASSERT_TRUE(again) << error.line << ": " << error.message;
  EXPECT_EQ(printFunction(*again), text);

  // x(t) = 2t^3 - 3t^2 + 11t from 10 to 0 (rising with t), y(t) = 2t^3 - 2t^2.
  ToolPath path = interpret(*function);
  ASSERT_GT(path.events.size(), 4u);
  const MachineEvent& last = path.events.back();
  EXPECT_EQ(last.x, 0);
  EXPECT_EQ(last.y, 0);
  EXPECT_EQ(last.feed, 200);
  std::size_t chords = 0;
  for (const MachineEvent& event : path.events) {
    if (event.kind != MachineEvent::Kind::Feed || event.x >= 10) {
      continue;
    }
    ++chords;
    double low = 0, high = 1; // the t of the point's x
    for (int step = 0; step < 60; ++step) {
      double t = (low + high) / 2;
      (((2 * t - 3) * t + 11) * t < event.x ? low : high) = t;
    }
    EXPECT_NEAR(event.y, (2 * low - 2) * low * low, 1e-9);
  }
  EXPECT_GT(chords, 10u);
}

TEST(PolynomialMoveTest, InterpreterStopsASpanThatStartsElsewhere) {
  std::string text = spanPart;
  text.replace(text.find("%k1 = const 11"), 14, "%k1 = const 11.01"); // starts at 10.01
  ParseError error;
  std::optional<Function> function = parseFunction(text, error);
  ASSERT_TRUE(function) << error.message;
  try {
    interpret(*function);
    FAIL() << "a span 0.01 from the machine ran";
  } catch (const InterpreterError& problem) {
    EXPECT_THAT(problem.what(), HasSubstr("from where the machine is"));
  }
  EXPECT_FALSE(parseFunction("func @f() {\n  %0 = const 1\n  move.polynomial %0, %0\n}\n", error));
  EXPECT_THAT(error.message, HasSubstr("takes 13 operands"));
}

} // namespace
} // namespace cncc::ir
