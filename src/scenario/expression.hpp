#pragma once
// Initial fields as expressions of position, parsed with muParser (private to the io library).
// A field is either a number or a string such as "x < 0.5 ? 1.0 : 0.125" or "-x/sqrt(x^2+y^2)".
// Variables are the geometry's coordinate names (x, y or z, r); the constant pi is defined. Boundary
// values that vary in time are expressions of t (s), such as "-100 * min(t / 1e-6, 1)".
#include <functional>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "json_reader.hpp"

namespace krug::scenario {

class Expression {
 public:
  Expression(const std::string& text, const std::string& first_variable, const std::string& second_variable,
             const std::string& path);
  // An expression of the given variables (one to three names).
  Expression(const std::string& text, std::vector<std::string> variables, const std::string& path);
  ~Expression();
  Expression(const Expression&) = delete;
  Expression& operator=(const Expression&) = delete;
  double operator()(double first, double second) const;
  double operator()(double only) const;  // an expression of one variable (time)

 private:
  double evaluate(std::span<const double> values) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<std::string> variables_;
  std::string path_;
};

// A boundary value as a function of time: a number, or an expression of t (s). Reads the value at
// `path`; the function throws InputError naming `path` (and t) where the expression is not finite.
std::function<double(double)> time_function_from_json(const Json& value, const std::string& path);

// A scalar field over the plane: a constant or an expression.
class ScalarField {
 public:
  ScalarField() = default;
  explicit ScalarField(double constant) : constant_(constant) {}
  // Reads a number or an expression string at `path`.
  static ScalarField from_json(const Json& value, const std::string& path, const std::string& first_variable,
                               const std::string& second_variable);
  double at(double first, double second) const;

 private:
  double constant_ = 0.0;
  std::shared_ptr<Expression> expression_;
};

}  // namespace krug::scenario
