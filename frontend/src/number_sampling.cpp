#include "number_sampling.h"

#include <array>
#include <cmath>

namespace cncc::frontend {

namespace {

constexpr std::size_t sampleCount = curveSampleIntervals + 1;

// A number at every sample; one number, the first, when it is the same at
// all of them (it does not depend on `t`). Only the values in use are set.
struct Samples {
  bool uniform = true;
  std::array<double, sampleCount> values;

  std::size_t count() const { return uniform ? 1 : sampleCount; }
  static Samples of(double number) {
    Samples samples;
    samples.values[0] = number;
    return samples;
  }
};

// `operation` at every sample: once when both operands are uniform. Every
// sample is computed, and the caller checks the results: nothing else
// happens on the way, and any failure gives up the whole sampling. `result`
// may be `a` or `b`.
template <typename Operation>
void combine(const Samples& a, const Samples& b, Samples& result, Operation operation) {
  bool aUniform = a.uniform;
  bool bUniform = b.uniform;
  double aFirst = a.values[0];
  double bFirst = b.values[0];
  result.uniform = aUniform && bUniform;
  if (result.uniform) {
    result.values[0] = operation(aFirst, bFirst);
  } else if (aUniform) {
    for (std::size_t i = 0; i < sampleCount; ++i) {
      result.values[i] = operation(aFirst, b.values[i]);
    }
  } else if (bUniform) {
    for (std::size_t i = 0; i < sampleCount; ++i) {
      result.values[i] = operation(a.values[i], bFirst);
    }
  } else {
    for (std::size_t i = 0; i < sampleCount; ++i) {
      result.values[i] = operation(a.values[i], b.values[i]);
    }
  }
}

template <typename Operation> void apply(const Samples& a, Samples& result, Operation operation) {
  result.uniform = a.uniform;
  for (std::size_t i = 0; i < a.count(); ++i) {
    result.values[i] = operation(a.values[i]);
  }
}

bool allFinite(const Samples& samples) {
  for (std::size_t i = 0; i < samples.count(); ++i) {
    if (!std::isfinite(samples.values[i])) {
      return false;
    }
  }
  return true;
}

bool anyZero(const Samples& samples) {
  for (std::size_t i = 0; i < samples.count(); ++i) {
    if (samples.values[i] == 0) {
      return true;
    }
  }
  return false;
}

// The names a frame binds: a fn call's parameters (as the fast path binds
// them, with nothing outside), or, outermost, `t` over the bindings the
// curve is evaluated in.
struct Frame {
  std::span<const Declaration* const> declarations;
  const Samples* samples = nullptr;
  const Bindings* outer = nullptr;
};

// Far more than any curve needs, and a bound on the work for a pathological
// one (the fast path itself stops only at the step budget).
constexpr std::size_t maximumStepsPerSample = std::size_t{1} << 20;

// The fast path's largest fn call depth, as Evaluator::numberOfFunctionCall
// checks it.
constexpr std::size_t maximumCallDepth = 64;

// Deeper expressions (through fn bodies too) are left to the sampling one by
// one: a bound on the stack this takes.
constexpr std::size_t maximumNesting = 200;

class Sampler {
public:
  Sampler(const SemaContext& context, std::size_t callDepth)
      : context_(context), callDepth_(callDepth) {}

  // What Evaluator::evaluateNumber does, at every sample.
  bool evaluate(const Expr& expression, const Frame& frame, Samples& result) {
    if (++steps_ > maximumStepsPerSample || expression.type.kind == TypeKind::Error ||
        nesting_ == maximumNesting) {
      return false;
    }
    ++nesting_;
    bool evaluated = evaluateNode(expression, frame, result);
    --nesting_;
    return evaluated;
  }

  std::size_t steps() const { return steps_; }

private:
  bool evaluateNode(const Expr& expression, const Frame& frame, Samples& result) {
    switch (expression.kind) {
    case ExprKind::Number:
      result = Samples::of(as<NumberExpr>(expression).value);
      return true;
    case ExprKind::Name:
      return name(as<NameExpr>(expression), frame, result);
    case ExprKind::Unary:
      return unary(as<UnaryExpr>(expression), frame, result);
    case ExprKind::Binary:
      return binary(as<BinaryExpr>(expression), frame, result);
    case ExprKind::Call:
      return call(as<CallExpr>(expression), frame, result);
    default:
      return false;
    }
  }

  bool name(const NameExpr& name, const Frame& frame, Samples& result) {
    const Declaration* declaration = name.declaration;
    if (declaration == nullptr) {
      return false;
    }
    switch (declaration->kind) {
    case DeclarationKind::Constant:
    case DeclarationKind::Builtin:
      // A constant not evaluated yet is left to the ordinary sampling.
      if (!declaration->value || declaration->value->type.kind != TypeKind::Num) {
        return false;
      }
      result = Samples::of(declaration->value->number);
      return true;
    default:
      break;
    }
    for (std::size_t i = 0; i < frame.declarations.size(); ++i) {
      if (frame.declarations[i] == declaration) {
        result = frame.samples[i];
        return true;
      }
    }
    double number = 0;
    if (frame.outer == nullptr || !frame.outer->findNumber(declaration, number)) {
      return false;
    }
    result = Samples::of(number);
    return true;
  }

  bool unary(const UnaryExpr& unary, const Frame& frame, Samples& result) {
    Samples operand;
    if (unary.op != UnaryOperator::Negate || !evaluate(*unary.operand, frame, operand)) {
      return false;
    }
    apply(operand, result, [](double x) { return -x; });
    return true;
  }

  // As Evaluator::numberOfBinary.
  bool binary(const BinaryExpr& binary, const Frame& frame, Samples& result) {
    BinaryOperator op = binary.op;
    if (!isArithmetic(op)) {
      return false;
    }
    // The left operand is evaluated into `result`, which then takes the
    // combination: one set of samples less on the stack per level.
    Samples& left = result;
    Samples right;
    if (!evaluate(*binary.left, frame, left) || !evaluate(*binary.right, frame, right)) {
      return false;
    }
    switch (op) {
    case BinaryOperator::Add:
      combine(left, right, result, [](double a, double b) { return a + 1 * b; });
      break;
    case BinaryOperator::Subtract:
      combine(left, right, result, [](double a, double b) { return a + -1 * b; });
      break;
    case BinaryOperator::Multiply:
      combine(left, right, result, [](double a, double b) { return a * b; });
      break;
    case BinaryOperator::Divide:
      if (anyZero(right)) {
        return false;
      }
      combine(left, right, result, [](double a, double b) { return a / b; });
      break;
    case BinaryOperator::Remainder:
      if (anyZero(right)) {
        return false;
      }
      combine(left, right, result, [](double a, double b) {
        return arithmetic::applyBinary(arithmetic::MathFunction::Rem, a, b);
      });
      break;
    default:
      combine(left, right, result, [](double a, double b) {
        return arithmetic::applyBinary(arithmetic::MathFunction::Pow, a, b);
      });
      break;
    }
    return allFinite(result);
  }

  // As Evaluator::numberOfCall.
  bool call(const CallExpr& call, const Frame& frame, Samples& result) {
    using namespace arithmetic;
    const Declaration* declaration = call.declaration;
    if (declaration != nullptr && declaration->kind == DeclarationKind::Function) {
      return functionCall(call, *declaration, frame, result);
    }
    std::optional<MathFunction> numeric = numericMathCall(call);
    if (!numeric) {
      return false;
    }
    MathFunction function = *numeric;
    std::size_t count = call.arguments.size();
    std::array<Samples, 2> values;
    for (std::size_t i = 0; i < count; ++i) {
      if (!evaluate(*call.arguments[i].value, frame, values[i])) {
        return false;
      }
    }
    if (count == 1) {
      apply(values[0], result, [function](double x) { return applyUnary(function, x); });
      return allFinite(result);
    }
    bool swapped = binaryArgumentsSwapped(call, function);
    const Samples& first = swapped ? values[1] : values[0];
    const Samples& second = swapped ? values[0] : values[1];
    combine(first, second, result,
            [function](double a, double b) { return applyBinary(function, a, b); });
    return allFinite(result);
  }

  // As Evaluator::numberOfFunctionCall: the arguments in the caller's frame,
  // the body in a frame of the parameters alone.
  bool functionCall(const CallExpr& call, const Declaration& function, const Frame& frame,
                    Samples& result) {
    if (function.function == nullptr || context_.invalidFunctions.contains(&function)) {
      return false;
    }
    const NodeList<Parameter>& parameters = function.function->parameters;
    std::size_t count = parameters.size();
    if (count > Bindings::maximumNumbers || callDepth_ > maximumCallDepth) {
      return false;
    }
    std::array<const Expr*, Bindings::maximumNumbers> arguments{};
    Evaluator::bindArguments(
        call, count, [&](std::size_t i) -> std::string_view { return parameters[i].name; },
        arguments.data());
    std::array<const Declaration*, Bindings::maximumNumbers> declarations{};
    std::array<Samples, Bindings::maximumNumbers> values;
    for (std::size_t i = 0; i < count; ++i) {
      declarations[i] = parameters[i].declaration;
      if (arguments[i] == nullptr || declarations[i] == nullptr ||
          !evaluate(*arguments[i], frame, values[i])) {
        return false;
      }
    }
    ++callDepth_;
    bool evaluated = evaluate(*function.function->body,
                              Frame{std::span(declarations.data(), count), values.data()}, result);
    --callDepth_;
    return evaluated;
  }

  const SemaContext& context_;
  std::size_t callDepth_;
  std::size_t steps_ = 0;
  std::size_t nesting_ = 0;
};

} // namespace

std::optional<std::size_t> fastPathSampleSteps(const SemaContext& context, std::size_t callDepth,
                                               const Bindings& bindings,
                                               const CurveSamples& samples) {
  Samples t;
  t.uniform = false;
  for (int i = 0; i <= curveSampleIntervals; ++i) {
    // As the samples are taken one by one (curve_values.cpp).
    t.values[static_cast<std::size_t>(i)] =
        samples.low + (samples.high - samples.low) * i / curveSampleIntervals;
  }
  const Declaration* parameter = samples.parameter;
  Frame frame{std::span(&parameter, 1), &t, &bindings};
  Sampler sampler(context, callDepth);
  for (const Expr* expression : samples.expressions) {
    if (expression == nullptr) {
      continue;
    }
    Samples result;
    if (!mayBeNumber(*expression) || !sampler.evaluate(*expression, frame, result)) {
      return std::nullopt;
    }
  }
  return sampler.steps() * sampleCount;
}

} // namespace cncc::frontend
