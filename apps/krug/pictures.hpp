#pragma once
// PNG pictures of a run (output.pictures, docs/outputs.md): the active zones of every body filled
// with the colour of one field, free particles as circles, a colour bar, a scale bar and the time,
// like the figures of Gulidov & Shabalin. Drawn with Cairo when krug is built with it (optional,
// app only); without Cairo pictures_available() is false and nothing is drawn.
#include <filesystem>
#include <string>

#include "krug/io/scenario.hpp"
#include "krug/solver/simulation.hpp"

namespace krug::app {

bool pictures_available();

// Writes DIR/pictures/NAME.png (under a temporary name, then renamed). Returns false (and writes
// nothing) when there is nothing to draw or Cairo is missing.
bool write_picture(const Simulation& simulation, const io::PictureSettings& settings, const std::string& title,
                   const std::filesystem::path& directory, const std::string& name);

}  // namespace krug::app
