#pragma once
// Umbrella header of the Krug library: numerics and scenes built in C++ (the scenario reader is in
// krug/scenario/, the run loop in krug/run/, the run's files in krug/output/).
#include "krug/core/error.hpp"
#include "krug/core/geometry_kind.hpp"
#include "krug/core/vec2.hpp"
#include "krug/material/eos.hpp"
#include "krug/material/material.hpp"
#include "krug/material/strength.hpp"
#include "krug/mesh/generators.hpp"
#include "krug/mesh/mesh.hpp"
#include "krug/mesh/quad.hpp"
#include "krug/mesh/zone_state.hpp"
#include "krug/solver/controls.hpp"
#include "krug/solver/gauges.hpp"
#include "krug/solver/ledger.hpp"
#include "krug/solver/simulation.hpp"
#include "krug/setup/scene.hpp"
