#include "expression.hpp"

#include <cmath>
#include <numbers>

#include <fmt/format.h>
#include <muParser.h>

#include "krug/core/error.hpp"

namespace krug::io {

struct Expression::Impl {
  mu::Parser parser;
  mutable double first = 0.0;
  mutable double second = 0.0;
};

Expression::Expression(const std::string& text, const std::string& first_variable,
                       const std::string& second_variable, const std::string& path)
    : impl_(std::make_unique<Impl>()), path_(path) {
  try {
    impl_->parser.DefineVar(first_variable, &impl_->first);
    impl_->parser.DefineVar(second_variable, &impl_->second);
    impl_->parser.DefineConst("pi", std::numbers::pi);
    impl_->parser.SetExpr(text);
    (void)impl_->parser.Eval();  // reports syntax errors and unknown names now, not mid-run
  } catch (const mu::Parser::exception_type& e) {
    throw InputError(fmt::format("{}: cannot evaluate expression \"{}\": {} (variables: {}, {}, pi)", path, text,
                                 e.GetMsg(), first_variable, second_variable));
  }
}

Expression::~Expression() = default;

double Expression::operator()(double first, double second) const {
  impl_->first = first;
  impl_->second = second;
  double value = 0.0;
  try {
    value = impl_->parser.Eval();
  } catch (const mu::Parser::exception_type& e) {
    throw InputError(fmt::format("{}: expression failed at ({}, {}): {}", path_, first, second, e.GetMsg()));
  }
  if (!std::isfinite(value)) {
    throw InputError(fmt::format("{}: expression gives {} at ({}, {}); expected a finite number", path_, value,
                                 first, second));
  }
  return value;
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

}  // namespace krug::io
