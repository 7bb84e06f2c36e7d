#include "persistence_diagram_files.hpp"

#include "core/voxel_type.hpp"

#include <zlib.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <sstream>
#include <stdexcept>

namespace arbor::io {

namespace {

class LineReader {
public:
    explicit LineReader(const std::filesystem::path &path) : path_(path)
    {
        file_ = gzopen(path.c_str(), "rb");
        if (!file_)
            throw std::runtime_error(path.string() + ": cannot open (" + std::string(std::strerror(errno)) + ")");
    }
    ~LineReader() { gzclose(file_); }
    LineReader(const LineReader &) = delete;
    LineReader &operator=(const LineReader &) = delete;

    bool next(std::string &line)
    {
        line.clear();
        char buffer[4096];
        while (gzgets(file_, buffer, sizeof buffer)) {
            line += buffer;
            if (!line.empty() && line.back() == '\n')
                break;
        }
        int error = 0;
        const char *message = gzerror(file_, &error);
        // zlib reports a gzip stream that ends before its trailer (a cut
        // download or copy) as Z_BUF_ERROR: the lines read so far may be
        // fewer than the file had, so it is an error, not the end.
        if (error == Z_BUF_ERROR)
            throw std::runtime_error(path_.string() + ": truncated: the compressed data ends before its end marker");
        if (error != Z_OK)
            throw std::runtime_error(path_.string() + ": cannot read: " + message);
        if (line.empty())
            return false;
        ++number_;
        while (!line.empty() && (line.back() == '\n' || line.back() == '\r'))
            line.pop_back();
        return true;
    }

    [[noreturn]] void fail(const std::string &what) const
    {
        throw std::runtime_error(path_.string() + ":" + std::to_string(number_) + ": " + what);
    }

private:
    std::filesystem::path path_;
    gzFile file_;
    std::size_t number_ = 0;
};

bool blank(const std::string &line)
{
    return line.find_first_not_of(" \t") == std::string::npos;
}

double number(const std::string &token, const LineReader &in, const char *what)
{
    char *end = nullptr;
    errno = 0;
    const double v = std::strtod(token.c_str(), &end);
    if (token.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
        in.fail(std::string(what) + " \"" + token + "\" is not a finite number");
    return v;
}

long integer(const std::string &token, const LineReader &in, const char *what)
{
    char *end = nullptr;
    const long v = std::strtol(token.c_str(), &end, 10);
    if (token.empty() || *end != '\0')
        in.fail(std::string(what) + " \"" + token + "\" is not an integer");
    return v;
}

void check_order(double birth, double death, const LineReader &in)
{
    if (death < birth)
        in.fail("death " + std::to_string(death) + " is below birth " + std::to_string(birth));
}

std::vector<std::string> split_csv(const std::string &line)
{
    std::vector<std::string> out;
    std::string cell;
    std::istringstream s(line);
    while (std::getline(s, cell, ','))
        out.push_back(cell.substr(cell.find_first_not_of(" \t") == std::string::npos ? cell.size()
                                                                                       : cell.find_first_not_of(" \t")));
    if (!line.empty() && line.back() == ',')
        out.emplace_back();
    for (std::string &c : out)
        while (!c.empty() && (c.back() == ' ' || c.back() == '\t'))
            c.pop_back();
    return out;
}

void read_csv(LineReader &in, const std::string &header, topology::PersistenceDiagram &d)
{
    const std::vector<std::string> names = split_csv(header);
    int dimension = -1, birth = -1, death = -1, essential = -1;
    for (std::size_t k = 0; k < names.size(); ++k) {
        const int i = static_cast<int>(k);
        if (names[k] == "dimension")
            dimension = i;
        else if (names[k] == "birth")
            birth = i;
        else if (names[k] == "death")
            death = i;
        else if (names[k] == "essential")
            essential = i;
    }
    if (dimension < 0 || birth < 0 || death < 0)
        in.fail("the CSV header needs the columns dimension, birth and death");
    std::string line;
    while (in.next(line)) {
        if (blank(line))
            continue;
        const std::vector<std::string> cells = split_csv(line);
        if (cells.size() != names.size())
            in.fail(std::to_string(cells.size()) + " values where the header names " + std::to_string(names.size()));
        topology::DiagramPoint p;
        const long dim = integer(cells[dimension], in, "dimension");
        if (dim < 0 || dim > 3)
            in.fail("dimension " + std::to_string(dim) + " is not 0 to 3");
        p.dimension = static_cast<int>(dim);
        p.birth = number(cells[birth], in, "birth");
        p.death = number(cells[death], in, "death");
        check_order(p.birth, p.death, in);
        if (essential >= 0) {
            const long e = integer(cells[essential], in, "essential");
            if (e != 0 && e != 1)
                in.fail("essential must be 0 or 1, not " + cells[essential]);
            p.essential = e == 1;
        }
        d.points.push_back(p);
    }
}

void read_pairs(LineReader &in, std::string line, topology::PersistenceDiagram &d, int grid_dim)
{
    do {
        if (blank(line))
            continue;
        if (line[0] == '#') {
            const std::size_t at = line.find("dims=");
            if (at != std::string::npos) {
                std::istringstream dims(line.substr(at + 5));
                Geometry g;
                if (dims >> g.dims[0] >> g.dims[1] >> g.dims[2])
                    grid_dim = topology::grid_dimension(g);
            }
            continue;
        }
        std::istringstream fields(line);
        std::string type, birth_vertex, death_vertex, birth, death;
        if (!(fields >> type >> birth_vertex >> death_vertex >> birth >> death))
            in.fail("expected \"type birth_vertex death_vertex birth_value death_value ...\"");
        const long t = integer(type, in, "pair type");
        if (t < -1 || t > 2)
            in.fail("pair type " + type + " is not -1, 0, 1 or 2");
        topology::DiagramPoint p;
        p.dimension = topology::pair_dimension(static_cast<int>(t), grid_dim);
        p.essential = t == -1;
        p.birth = number(birth, in, "birth value");
        p.death = number(death, in, "death value");
        check_order(p.birth, p.death, in);
        d.points.push_back(p);
    } while (in.next(line));
}

std::string value_text(double v, bool integers)
{
    char buf[64];
    std::snprintf(buf, sizeof buf, integers ? "%.0f" : "%.9g", v);
    return buf;
}

} // namespace

topology::PersistenceDiagram read_persistence_diagram(const std::filesystem::path &path)
{
    LineReader in(path);
    topology::PersistenceDiagram d;
    std::string line;
    // The first line that is neither blank nor a comment tells the format.
    std::vector<std::string> comments;
    while (in.next(line)) {
        if (blank(line))
            continue;
        if (line[0] == '#') {
            comments.push_back(line);
            continue;
        }
        break;
    }
    if (line.empty() || blank(line) || line[0] == '#') {
        // Only comments: an empty diagram, but the file must look like one.
        if (comments.empty())
            throw std::runtime_error(path.string() + ": empty: no pairs and no header");
        return d;
    }
    int grid_dim = 3;
    for (const std::string &c : comments) {
        const std::size_t at = c.find("dims=");
        if (at == std::string::npos)
            continue;
        std::istringstream dims(c.substr(at + 5));
        Geometry g;
        if (dims >> g.dims[0] >> g.dims[1] >> g.dims[2])
            grid_dim = topology::grid_dimension(g);
    }
    if (line.find(',') != std::string::npos || std::isalpha(static_cast<unsigned char>(line[0])))
        read_csv(in, line, d);
    else
        read_pairs(in, line, d, grid_dim);
    return d;
}

void write_pairs_csv(std::ostream &out, const std::vector<topology::PersistencePair> &pairs, const Geometry &grid,
                     arbor_voxel_type type)
{
    const int grid_dim = topology::grid_dimension(grid);
    const bool integers = is_integer_voxel_type(type);
    const int64_t nx = grid.dims[0], ny = grid.dims[1];
    out << "dimension,birth,death,persistence,essential,birth_vertex,death_vertex,bx,by,bz,dx,dy,dz\n";
    for (const topology::PersistencePair &p : pairs) {
        const int64_t b = p.birth, e = p.death;
        out << topology::pair_dimension(p.type, grid_dim) << ',' << value_text(p.birth_value, integers) << ','
            << value_text(p.death_value, integers) << ',' << value_text(p.persistence(), integers) << ','
            << (p.type == -1 ? 1 : 0) << ',' << p.birth << ',' << p.death << ',' << b % nx << ',' << (b / nx) % ny
            << ',' << b / (nx * ny) << ',' << e % nx << ',' << (e / nx) % ny << ',' << e / (nx * ny) << '\n';
    }
}

} // namespace arbor::io
