#pragma once
// The scenario parameters of a model, described once beside the model: its key, the data member it
// sets, the accepted range and, for an optional parameter, the value taken when it is not given. The
// scenario reader walks these lists (one reader for every model). Material models (equations of
// state, strength: krug/material/parameters.hpp) and failure laws (krug/fracture/failure_law.hpp)
// both describe themselves this way; the description lives here, below both, so that neither module
// includes the other.
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
  // An optional parameter that stands for a constant of the material's strength model (a failure
  // law's melt temperature, say): the key of that constant in the `strength` block. When the
  // parameter is not given and the material's strength model has this key, the reader takes the
  // strength model's value instead of `fallback`, so the constant is written once.
  std::string_view strength_key = {};
};

namespace parameter {

inline constexpr double infinity = std::numeric_limits<double>::infinity();

// Required parameters by range.
template <class M>
constexpr ModelParameter<M> positive(std::string_view key, double M::*member) {
  return {key, member, 0.0, infinity, true, true, 0.0, {}};
}
template <class M>
constexpr ModelParameter<M> non_negative(std::string_view key, double M::*member) {
  return {key, member, 0.0, infinity, false, true, 0.0, {}};
}
template <class M>
constexpr ModelParameter<M> between(std::string_view key, double M::*member, double low, double high,
                                    bool low_exclusive = false) {
  return {key, member, low, high, low_exclusive, true, 0.0, {}};
}
// Any finite or infinite number.
template <class M>
constexpr ModelParameter<M> any(std::string_view key, double M::*member) {
  return {key, member, -infinity, infinity, false, true, 0.0, {}};
}
// The same parameter made optional, with the value taken when it is absent.
template <class M>
constexpr ModelParameter<M> optional(ModelParameter<M> p, double fallback) {
  p.required = false;
  p.fallback = fallback;
  return p;
}
// An optional parameter that, when absent, takes the strength model's constant of key `strength_key`
// if the material's strength model has one, else `fallback`.
template <class M>
constexpr ModelParameter<M> from_strength(ModelParameter<M> p, std::string_view strength_key, double fallback) {
  p = optional(p, fallback);
  p.strength_key = strength_key;
  return p;
}

}  // namespace parameter

// Models without parameters.
template <class Model>
constexpr std::array<ModelParameter<Model>, 0> parameters(std::type_identity<Model>) {
  return {};
}

}  // namespace krug
