#include "expression.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <muParser.h>

#include "krug/core/error.hpp"

namespace krug::scenario {

struct Expression::Impl {
  mu::Parser parser;
  mutable std::array<double, 3> values{};
};

namespace {

std::string list_variables(const std::vector<std::string>& variables) {
  std::string text;
  for (const std::string& v : variables) text += (text.empty() ? "" : ", ") + v;
  return text;
}

}  // namespace

Expression::Expression(const std::string& text, const std::string& first_variable,
                       const std::string& second_variable, const std::string& path)
    : Expression(text, std::vector<std::string>{first_variable, second_variable}, path) {}

Expression::Expression(const std::string& text, std::vector<std::string> variables, const std::string& path)
    : impl_(std::make_unique<Impl>()), variables_(std::move(variables)), path_(path) {
  if (variables_.empty() || variables_.size() > impl_->values.size()) {
    throw InputError(fmt::format("{}: an expression takes one to three variables", path));
  }
  // Only a pure expression of the documented variables: no assignment (x = 3, x += 1), no list of
  // several results (1, 2), and a bounded size and nesting (the parser recurses on parentheses).
  auto refuse = [&](const std::string& why) {
    throw InputError(fmt::format("{}: expression \"{}\" {}; expected one formula in {} and pi", path,
                                 text.size() > 60 ? text.substr(0, 57) + "..." : text, why, list_variables(variables_)));
  };
  if (text.size() > 1000) refuse(fmt::format("is {} characters long, more than 1000", text.size()));
  int depth = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '(') ++depth;
    if (c == '(' && depth > 32) refuse("nests parentheses more than 32 deep");
    if (c == ')') --depth;
    if (c == '=') {
      const char before = i > 0 ? text[i - 1] : ' ', after = i + 1 < text.size() ? text[i + 1] : ' ';
      const bool comparison = after == '=' || before == '=' || before == '<' || before == '>' || before == '!';
      if (!comparison) refuse("assigns a value (=); a formula has no assignment");
    }
  }
  try {
    for (std::size_t k = 0; k < variables_.size(); ++k) impl_->parser.DefineVar(variables_[k], &impl_->values[k]);
    impl_->parser.DefineConst("pi", std::numbers::pi);
    impl_->parser.SetExpr(text);
    (void)impl_->parser.Eval();  // reports syntax errors and unknown names now, not mid-run
    if (impl_->parser.GetNumResults() != 1) refuse("gives a list of values (a comma outside a function's arguments)");
  } catch (const mu::Parser::exception_type& e) {
    throw InputError(fmt::format("{}: cannot evaluate expression \"{}\": {} (variables: {}, pi)", path, text,
                                 e.GetMsg(), list_variables(variables_)));
  }
}

Expression::~Expression() = default;

double Expression::evaluate(std::span<const double> values) const {
  std::copy(values.begin(), values.end(), impl_->values.begin());
  auto where = [&] {
    if (values.size() == 1) return fmt::format("{} = {}", variables_[0], values[0]);
    return fmt::format("({}, {})", values[0], values[1]);
  };
  double value = 0.0;
  try {
    value = impl_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw InputError(fmt::format("{}: expression failed at {}: {}", path_, where(), e.GetMsg()));
  }
  if (!std::isfinite(value)) {
    throw InputError(fmt::format("{}: expression gives {} at {}; expected a finite number", path_, value, where()));
  }
  return value;
}

double Expression::operator()(double first, double second) const {
  const std::array<double, 2> values{first, second};
  return evaluate(values);
}

double Expression::operator()(double only) const {
  const std::array<double, 1> values{only};
  return evaluate(values);
}

std::function<double(double)> time_function_from_json(const Json& value, const std::string& path) {
  if (value.is_number()) {
    const double v = value.get<double>();
    if (!std::isfinite(v)) throw InputError(fmt::format("{}: expected a finite number", path));
    return [v](double) { return v; };
  }
  if (value.is_string()) {
    auto expression = std::make_shared<Expression>(value.get<std::string>(), std::vector<std::string>{"t"}, path);
    return [expression](double t) { return (*expression)(t); };
  }
  throw InputError(fmt::format("{}: expected a number or an expression of t (a string), found {}", path,
                               describe_value(value)));
}

ScalarField ScalarField::from_json(const Json& value, const std::string& path, const std::string& first_variable,
                                   const std::string& second_variable) {
  if (value.is_number()) {
    const double v = value.get<double>();
    if (!std::isfinite(v)) throw InputError(fmt::format("{}: expected a finite number", path));
    return ScalarField(v);
  }
  if (value.is_string()) {
    ScalarField field;
    field.expression_ = std::make_shared<Expression>(value.get<std::string>(), first_variable, second_variable, path);
    return field;
  }
  throw InputError(fmt::format("{}: expected a number or an expression string, found {}", path,
                               describe_value(value)));
}

double ScalarField::at(double first, double second) const {
  return expression_ ? (*expression_)(first, second) : constant_;
}

}  // namespace krug::scenario
