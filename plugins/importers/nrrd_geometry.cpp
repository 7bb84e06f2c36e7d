// nrrd_geometry.cpp - see nrrd_geometry.hpp.
#include "nrrd_geometry.hpp"

#include "anatomical_space.hpp"
#include "number_text.hpp"

#include <array>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

namespace arbor::importers {

namespace {

std::array<double, 3> cross(const std::array<double, 3> &a, const std::array<double, 3> &b)
{
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

// One pass over the geometry fields; the space (and its dimension) must be
// known before vectors in it can be read.
class NrrdGeometry {
public:
    NrrdGeometry(const NrrdFields &fields, int dimension, VoxelGrid &grid)
        : fields_(fields), dimension_(dimension), grid_(grid)
    {
    }

    void read()
    {
        parse_space();
        parse_axes_and_origin();
    }

private:
    [[noreturn]] void bad(arbor_status status, const std::string &problem) const
    {
        fields_.bad(status, problem);
    }
    const NrrdField *find(const char *key) const { return fields_.find(key); }
    static std::string shown(const NrrdField &f) { return NrrdFields::shown(f); }

    void parse_space()
    {
        if (const NrrdField *f = find("space")) {
            const std::string name = lower(f->value);
            const bool timed = name.ends_with("-time") || (name.size() == 4 && name.back() == 't' &&
                                                           space_to_lps(name.substr(0, 3)));
            if (timed)
                bad(ARBOR_ERROR_UNSUPPORTED,
                    "space " + excerpt(f->value) +
                        " has a time axis; Arbor reads 3-D scalar volumes");
            const std::optional<SpaceToLps> frame = space_to_lps(f->value);
            if (!frame)
                bad(ARBOR_ERROR_FORMAT, "space " + excerpt(f->value) + " is not a NRRD space");
            frame_ = *frame;
            space_dimension_ = 3;
        }
        if (const NrrdField *f = find("spacedimension")) {
            const std::optional<int64_t> n = parse_integer(f->value);
            if (!n || *n < 1)
                bad(ARBOR_ERROR_FORMAT, shown(*f) + " is not a positive whole number");
            if (space_dimension_ != 0 && *n != space_dimension_)
                bad(ARBOR_ERROR_FORMAT, shown(*f) + " contradicts the 3-D space named by 'space'");
            if (*n != 3 && !(*n == 2 && dimension_ == 2))
                bad(ARBOR_ERROR_UNSUPPORTED, shown(*f) + ": Arbor places volumes in 3-D space");
            // Without "space", a 3-D space is taken to be LPS, the SDK's frame.
            space_dimension_ = static_cast<int>(*n);
        }
    }

    // "(1,0,0) (0,-1,0) none" as vectors; nullopt for "none".
    std::vector<std::optional<std::vector<double>>> vectors(const NrrdField &f) const
    {
        std::vector<std::optional<std::vector<double>>> out;
        std::string_view rest = trim(f.value);
        while (!rest.empty()) {
            if (rest.substr(0, 4) == "none") {
                out.emplace_back(std::nullopt);
                rest = trim(rest.substr(4));
                continue;
            }
            const std::size_t close = rest.find(')');
            if (rest.front() != '(' || close == std::string_view::npos)
                bad(ARBOR_ERROR_FORMAT,
                    shown(f) + " is not a list of vectors like (1,0,0) or 'none'");
            std::vector<double> v;
            std::string_view inner = rest.substr(1, close - 1);
            while (true) {
                const std::size_t comma = inner.find(',');
                const std::optional<double> x = parse_real(trim(inner.substr(0, comma)));
                if (!x || !std::isfinite(*x))
                    bad(ARBOR_ERROR_FORMAT, shown(f) + ": " +
                                                excerpt(trim(inner.substr(0, comma))) +
                                                " is not a finite number");
                v.push_back(*x);
                if (comma == std::string_view::npos)
                    break;
                inner.remove_prefix(comma + 1);
            }
            out.emplace_back(std::move(v));
            rest = trim(rest.substr(close + 1));
        }
        return out;
    }

    // A vector of the file's space in LPS; 2-D spaces get z = 0.
    std::array<double, 3> to_lps(const std::vector<double> &v) const
    {
        std::array<double, 3> p{v[0], v[1], v.size() > 2 ? v[2] : 0.0};
        return space_dimension_ == 3 ? frame_.apply(p) : p;
    }

    // Space directions or origin without "space" or "space dimension" break
    // the specification, but their meaning is plain: take the vector length
    // as the space dimension, in LPS.
    void infer_space_dimension(const std::vector<std::optional<std::vector<double>>> &list,
                               const NrrdField &f)
    {
        if (space_dimension_ != 0)
            return;
        for (const auto &v : list)
            if (v) {
                space_dimension_ = static_cast<int>(v->size());
                break;
            }
        if (space_dimension_ != 3 && !(space_dimension_ == 2 && dimension_ == 2))
            bad(ARBOR_ERROR_FORMAT,
                shown(f) + " needs a 'space' or 'space dimension' field before it");
    }

    void parse_axes_and_origin()
    {
        if (const NrrdField *f = find("spacedirections"))
            parse_directions(*f);
        else if (const NrrdField *s = find("spacings"))
            parse_spacings(*s);
        if (const NrrdField *f = find("spaceorigin"))
            parse_origin(*f);
    }

    // Each axis's vector gives its direction (normalised) and its spacing
    // (the vector's length).
    void parse_directions(const NrrdField &f)
    {
        VoxelGrid &g = grid_;
        const auto list = vectors(f);
        if (list.size() != static_cast<std::size_t>(dimension_))
            bad(ARBOR_ERROR_FORMAT, shown(f) + " has " + std::to_string(list.size()) +
                                        " entries, but dimension is " + std::to_string(dimension_));
        infer_space_dimension(list, f);
        for (int a = 0; a < dimension_; ++a) {
            const auto &v = list[static_cast<std::size_t>(a)];
            if (!v)
                bad(ARBOR_ERROR_UNSUPPORTED,
                    "space directions: axis " + std::to_string(a) +
                        " is 'none' (not a spatial axis, e.g. vector components); Arbor reads "
                        "scalar volumes whose axes are all spatial");
            if (v->size() != static_cast<std::size_t>(space_dimension_))
                bad(ARBOR_ERROR_FORMAT, shown(f) + ": every vector needs " +
                                            std::to_string(space_dimension_) + " components");
            const double length = set_direction_column(g, a, to_lps(*v));
            if (length == 0.0)
                bad(ARBOR_ERROR_FORMAT,
                    shown(f) + ": the direction of axis " + std::to_string(a) + " is zero");
            g.spacing[static_cast<std::size_t>(a)] = length;
        }
        if (dimension_ == 2) {
            // The slice normal completes a right-handed frame.
            const std::array<double, 3> c0{g.direction[0], g.direction[3], g.direction[6]};
            const std::array<double, 3> c1{g.direction[1], g.direction[4], g.direction[7]};
            if (set_direction_column(g, 2, cross(c0, c1)) < 1e-9)
                bad(ARBOR_ERROR_FORMAT, shown(f) + ": the two axes are parallel");
        }
    }

    void parse_spacings(const NrrdField &f)
    {
        VoxelGrid &g = grid_;
        const auto words = split_words(f.value);
        if (words.size() != static_cast<std::size_t>(dimension_))
            bad(ARBOR_ERROR_FORMAT, shown(f) + " has " + std::to_string(words.size()) +
                                        " numbers, but dimension is " + std::to_string(dimension_));
        for (int a = 0; a < dimension_; ++a) {
            const std::optional<double> s = parse_real(words[static_cast<std::size_t>(a)]);
            if (!s || std::isinf(*s) || *s == 0.0)
                bad(ARBOR_ERROR_FORMAT,
                    shown(f) + ": every spacing must be a non-zero number (or nan)");
            if (std::isnan(*s))
                continue; // unknown spacing: keep 1
            // A negative spacing means the axis runs backwards.
            if (*s < 0.0)
                for (int row = 0; row < 3; ++row)
                    g.direction[static_cast<std::size_t>(3 * row + a)] *= -1.0;
            g.spacing[static_cast<std::size_t>(a)] = std::fabs(*s);
        }
    }

    void parse_origin(const NrrdField &f)
    {
        const auto list = vectors(f);
        if (list.size() != 1 || !list[0])
            bad(ARBOR_ERROR_FORMAT, shown(f) + " is not one vector like (0,0,0)");
        infer_space_dimension(list, f);
        if (list[0]->size() != static_cast<std::size_t>(space_dimension_))
            bad(ARBOR_ERROR_FORMAT,
                shown(f) + " needs " + std::to_string(space_dimension_) + " components");
        grid_.origin = to_lps(*list[0]);
    }

    const NrrdFields &fields_;
    int dimension_;
    VoxelGrid &grid_;
    int space_dimension_ = 0; // 0 until "space" or "space dimension" (or a vector) says
    SpaceToLps frame_;
};

} // namespace

void read_nrrd_geometry(const NrrdFields &fields, int dimension, VoxelGrid &grid)
{
    NrrdGeometry(fields, dimension, grid).read();
}

} // namespace arbor::importers
