#pragma once
// The scenario parameters of a material model, described once beside the model: its key, the data
// member it sets, the accepted range and, for an optional parameter, the value taken when it is not
// given. The scenario reader walks these lists (one reader for every model), so a new equation of
// state or strength model is its header (the struct, its law, its `parameters` function) plus its
// line in the model variant (`Eos` in eos.hpp, `Strength` in material.hpp) and its schema entry.
//
// A model with the member `reference_density` takes it from the material's `density`, not from its
// own block.
#include <array>
#include <limits>
#include <string_view>
#include <type_traits>

namespace krug {

template <class Model>
struct ModelParameter {
  std::string_view key;
  double Model::*member = nullptr;
  double minimum = -std::numeric_limits<double>::infinity();
  double maximum = std::numeric_limits<double>::infinity();
  bool minimum_exclusive = false;
  bool required = true;
  double fallback = 0.0;  // the value of an optional parameter that is not given
};

namespace parameter {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

// Required parameters by range.
template <class M>
constexpr ModelParameter<M> positive(std::string_view key, double M::*member) {
  return {key, member, 0.0, infinity, true, true, 0.0};
}
template <class M>
constexpr ModelParameter<M> non_negative(std::string_view key, double M::*member) {
  return {key, member, 0.0, infinity, false, true, 0.0};
}
template <class M>
constexpr ModelParameter<M> between(std::string_view key, double M::*member, double low, double high,
                                    bool low_exclusive = false) {
  return {key, member, low, high, low_exclusive, true, 0.0};
}
// The same parameter made optional, with the value taken when it is absent.
template <class M>
constexpr ModelParameter<M> optional(ModelParameter<M> p, double fallback) {
  p.required = false;
  p.fallback = fallback;
  return p;
}

}  // namespace parameter

// Models without parameters.
template <class Model>
constexpr std::array<ModelParameter<Model>, 0> parameters(std::type_identity<Model>) {
  return {};
}

}  // namespace krug
