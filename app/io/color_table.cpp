#include "color_table.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace arbor::io {

std::map<uint32_t, ColorTableEntry> read_color_table(const std::filesystem::path &path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path.string() + ": cannot open the colour table");
    std::map<uint32_t, ColorTableEntry> table;
    std::string line;
    for (std::size_t number = 1; std::getline(in, line); ++number) {
        const std::size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#')
            continue;
        std::istringstream fields(line);
        long long label = -1;
        std::string name;
        int r = -1, g = -1, b = -1, a = 255;
        if (!(fields >> label >> name >> r >> g >> b) || label < 0 || label > 4294967295LL || r < 0 || r > 255 ||
            g < 0 || g > 255 || b < 0 || b > 255 || ((fields >> a) && (a < 0 || a > 255)))
            throw std::runtime_error(path.string() + ":" + std::to_string(number) +
                                     ": expected 'label name R G B A' with colours 0..255");
        std::replace(name.begin(), name.end(), '_', ' ');
        table[static_cast<uint32_t>(label)] = {name, {static_cast<uint8_t>(r), static_cast<uint8_t>(g),
                                                      static_cast<uint8_t>(b)}};
        if (table.size() > 100000)
            throw std::runtime_error(path.string() + ": more than 100000 colours");
    }
    return table;
}

} // namespace arbor::io
