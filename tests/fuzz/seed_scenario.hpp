#pragma once
// The scenario of the checkpoint fuzzer's seed (make_checkpoint_seed) and of its restores: a
// fracturing flyer and plate, small enough to restore thousands of times a second.
namespace krug::fuzz {

inline constexpr const char* seed_scenario = R"({
  "geometry": "planar",
  "end_time": 1e-5,
  "materials": { "al": { "density": 2700, "eos": { "model": "linear", "bulk_modulus": 7.3e10 },
                         "strength": { "model": "perfectly_plastic", "shear_modulus": 2.6e10, "yield_stress": 3e8 },
                         "fracture": { "elongation": 0.05 } } },
  "bodies": [ { "name": "flyer", "material": "al",
                "mesh": { "type": "rectangle", "x": { "from": -0.002, "to": 0, "zones": 4 },
                                               "y": { "from": 0, "to": 0.004, "zones": 4 } },
                "initial": { "velocity": [800, 0] } },
              { "name": "plate", "material": "al",
                "mesh": { "type": "rectangle", "x": { "from": 0, "to": 0.002, "zones": 4 },
                                               "y": { "from": 0, "to": 0.004, "zones": 4 } } } ],
  "contact": { "pairs": [ { "bodies": ["flyer", "plate"] } ] }
})";

}  // namespace krug::fuzz
