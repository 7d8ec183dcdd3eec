#pragma once
// The scenario parameters of a material model, described once beside the model: its key, the data
// member it sets, the accepted range and, for an optional parameter, the value taken when it is not
// given (ModelParameter, krug/core/parameters.hpp). The scenario reader walks these lists (one reader
// for every model), so a new equation of state or strength model is its header (the struct, its law,
// its `parameters` function) plus its line in the model variant (`Eos` in eos.hpp, `Strength` in
// material.hpp) and its schema entry.
//
// A model with the member `reference_density` takes it from the material's `density`, not from its
// own block.
#include "krug/core/parameters.hpp"
