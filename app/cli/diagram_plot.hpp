// diagram_plot.hpp - a persistence diagram as a figure for a paper (PNG at a
// DPI, or SVG; the same drawing, io/figure.hpp): birth on x, death on y in
// the volume's value units, the diagonal, one marker shape and colour per
// homology dimension, the essential pair marked, ticks, axis titles, a legend
// with the counts, and a title.
#pragma once

#include "topology/persistence_pairs.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace arbor::cli {

struct DiagramPlotStyle {
    double size_inches = 4.0; // the square figure's side
    double dpi = 300.0;       // PNG only
};

// `title` heads the figure (the volume's name); `unit` names the values'
// unit in the axis titles (empty: none).  Throws std::runtime_error naming
// the file when it cannot be written.
void write_diagram_plot(const std::filesystem::path &path, const std::vector<topology::PersistencePair> &pairs,
                        int grid_dimension, const std::string &title, const std::string &unit,
                        const DiagramPlotStyle &style);

} // namespace arbor::cli
