#pragma once
// Plots of history.csv against time, drawn by the shipped script plot_history.py with Python and
// matplotlib (Debian: python3-matplotlib) when they are there. A missing Python never fails a run.
#include <filesystem>
#include <string>

namespace krug::app {

// Writes DIR/plots/*.png from DIR/history.csv. Returns an empty string when the plots were made,
// else a one-line reason for stderr (no Python, no matplotlib, script not found or failed).
std::string make_plots(const std::filesystem::path& directory);

// Writes DIR/ballistic.png from DIR/ballistic.csv and DIR/ballistic.json (scripts/plot_ballistic.py);
// the same return as make_plots.
std::string make_ballistic_plot(const std::filesystem::path& directory);

}  // namespace krug::app
