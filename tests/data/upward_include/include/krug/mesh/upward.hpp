#pragma once
// A planted violation for the module-wall test (tests/CMakeLists.txt): mesh must not include solver.
#include "krug/solver/controls.hpp"
