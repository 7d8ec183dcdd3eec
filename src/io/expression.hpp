#pragma once
// Initial fields as expressions of position, parsed with muParser (private to the io library).
// A field is either a number or a string such as "x < 0.5 ? 1.0 : 0.125" or "-x/sqrt(x^2+y^2)".
// Variables are the geometry's coordinate names (x, y or z, r); the constant pi is defined.
#include <memory>
#include <string>

#include "json_reader.hpp"

namespace krug::io {

class Expression {
 public:
  Expression(const std::string& text, const std::string& first_variable, const std::string& second_variable,
             const std::string& path);
  ~Expression();
  Expression(const Expression&) = delete;
  Expression& operator=(const Expression&) = delete;
  double operator()(double first, double second) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
};

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

}  // namespace krug::io
