// metaimage_header.cpp - see metaimage_header.hpp.  Follows ITK's MetaIO
// reader where the format is only defined by it: keys are synonyms in the
// same places (ElementSpacing/ElementSize, Offset/Position/Origin,
// TransformMatrix/Rotation/Orientation), TransformMatrix lists the direction
// of each grid axis in turn (ITK MetaImageIO::ReadImageInformation sets axis
// i from elements i*N..i*N+N-1), and HeaderSize counts from the start of the
// data file.  AnatomicalOrientation is ignored, as ITK does on reading: the
// matrix is what places the voxels.
#include "metaimage_header.hpp"

#include "number_text.hpp"
#include "text_scan.hpp"

#include <arbor/sdk/error.hpp>

#include <cmath>
#include <initializer_list>
#include <map>
#include <vector>

namespace arbor::importers {

namespace {

struct ElementTypeName {
    const char *name;
    arbor_voxel_type type;
};

constexpr ElementTypeName kElementTypes[] = {
    {"MET_UCHAR", ARBOR_VOXEL_U8},   {"MET_CHAR", ARBOR_VOXEL_I8},
    {"MET_USHORT", ARBOR_VOXEL_U16}, {"MET_SHORT", ARBOR_VOXEL_I16},
    {"MET_UINT", ARBOR_VOXEL_U32},   {"MET_INT", ARBOR_VOXEL_I32},
    {"MET_FLOAT", ARBOR_VOXEL_F32},  {"MET_DOUBLE", ARBOR_VOXEL_F64},
};

struct Entry {
    std::string key; // as written, for messages
    std::string value;
};

std::optional<bool> parse_bool(std::string_view text)
{
    const std::string t = lower(trim(text));
    if (t == "true" || t == "t" || t == "1" || t == "yes")
        return true;
    if (t == "false" || t == "f" || t == "0" || t == "no")
        return false;
    return std::nullopt;
}

// Splits "Key = Value"; false for a line that is not one.
bool split_entry(std::string_view line, std::string_view &key, std::string_view &value)
{
    const std::size_t eq = line.find('=');
    if (eq == std::string_view::npos)
        return false;
    key = trim(line.substr(0, eq));
    value = trim(line.substr(eq + 1));
    return !key.empty();
}

class MetaImageParser {
public:
    MetaImageParser(std::string_view text, std::string_view file_name)
        : text_(text), file_(file_name)
    {
    }

    MetaImageHeader parse()
    {
        collect();
        if (const Entry *e = find("objecttype"); e && !iequals(e->value, "Image"))
            bad(ARBOR_ERROR_UNSUPPORTED,
                "ObjectType " + excerpt(e->value) + ": Arbor reads Image objects");
        parse_ndims();
        parse_dims();
        parse_element_type();
        parse_channels();
        parse_geometry();
        parse_storage();
        return header_;
    }

private:
    [[noreturn]] void bad(arbor_status status, const std::string &problem) const
    {
        sdk::fail(status, "header of " + std::string(file_) + ": " + problem);
    }

    const Entry *find(const char *key) const
    {
        const auto it = entries_.find(key);
        return it == entries_.end() ? nullptr : &it->second;
    }

    // The first of several synonymous keys that is present.
    const Entry *find_any(std::initializer_list<const char *> keys) const
    {
        for (const char *k : keys)
            if (const Entry *e = find(k))
                return e;
        return nullptr;
    }

    static std::string shown(const Entry &e) { return e.key + " = " + excerpt(e.value); }

    void collect()
    {
        if (text_.empty())
            sdk::fail(ARBOR_ERROR_FORMAT, std::string(file_) + " is empty, not a MetaImage file");
        LineCursor lines(text_);
        std::string_view line;
        while (lines.next(line)) {
            if (trim(line).empty() || trim(line).front() == '#')
                continue;
            std::string_view key, value;
            if (!split_entry(line, key, value))
                bad(ARBOR_ERROR_FORMAT, "line " + std::to_string(lines.number()) + " " +
                                            excerpt(line) + " is not a 'Key = Value' line");
            const std::string folded = lower(key);
            if (!entries_.emplace(folded, Entry{std::string(key), std::string(value)}).second)
                bad(ARBOR_ERROR_FORMAT, "key " + excerpt(key) + " appears twice");
            if (folded == "elementdatafile") {
                header_.header_length = lines.offset();
                return;
            }
        }
        bad(ARBOR_ERROR_FORMAT,
            "has no ElementDataFile line (the line that ends a MetaImage header)");
    }

    std::vector<double> reals(const Entry &e, std::size_t count) const
    {
        const std::optional<std::vector<double>> v = parse_reals(e.value);
        if (!v || v->size() != count)
            bad(ARBOR_ERROR_FORMAT, shown(e) + " is not " + std::to_string(count) + " numbers");
        for (double x : *v)
            if (!std::isfinite(x))
                bad(ARBOR_ERROR_FORMAT, shown(e) + " holds a value that is not a finite number");
        return *v;
    }

    void parse_ndims()
    {
        const Entry *e = find("ndims");
        if (!e)
            bad(ARBOR_ERROR_FORMAT, "has no NDims line");
        const std::optional<int64_t> n = parse_integer(e->value);
        if (!n || *n < 1)
            bad(ARBOR_ERROR_FORMAT, shown(*e) + " is not a positive whole number");
        if (*n != 2 && *n != 3)
            bad(ARBOR_ERROR_UNSUPPORTED,
                "NDims " + std::to_string(*n) +
                    ": Arbor reads 3-dimensional images (or 2, as one slice)");
        ndims_ = static_cast<std::size_t>(*n);
    }

    void parse_dims()
    {
        const Entry *e = find("dimsize");
        if (!e)
            bad(ARBOR_ERROR_FORMAT, "has no DimSize line");
        const auto words = split_words(e->value);
        if (words.size() != ndims_)
            bad(ARBOR_ERROR_FORMAT, shown(*e) + " has " + std::to_string(words.size()) +
                                        " numbers, but NDims is " + std::to_string(ndims_));
        for (std::size_t a = 0; a < ndims_; ++a) {
            const std::optional<int64_t> n = parse_integer(words[a]);
            if (!n)
                bad(ARBOR_ERROR_FORMAT, shown(*e) + ": " + excerpt(words[a]) +
                                            " is not a whole number that fits in 64 bits");
            if (*n < 1)
                bad(ARBOR_ERROR_FORMAT, shown(*e) + ": every size must be at least 1");
            header_.grid.dims[a] = *n;
        }
    }

    void parse_element_type()
    {
        const Entry *e = find("elementtype");
        if (!e)
            bad(ARBOR_ERROR_FORMAT, "has no ElementType line");
        for (const ElementTypeName &t : kElementTypes)
            if (iequals(e->value, t.name)) {
                header_.grid.type = t.type;
                return;
            }
        if (lower(e->value).starts_with("met_"))
            bad(ARBOR_ERROR_UNSUPPORTED,
                "ElementType " + excerpt(e->value) +
                    " is not supported; Arbor reads MET_UCHAR, MET_CHAR, MET_USHORT, "
                    "MET_SHORT, MET_UINT, MET_INT, MET_FLOAT and MET_DOUBLE");
        bad(ARBOR_ERROR_FORMAT,
            "ElementType " + excerpt(e->value) + " is not a MetaImage element type");
    }

    void parse_channels()
    {
        const Entry *e = find("elementnumberofchannels");
        if (!e)
            return;
        const std::optional<int64_t> n = parse_integer(e->value);
        if (!n || *n < 1)
            bad(ARBOR_ERROR_FORMAT, shown(*e) + " is not a positive whole number");
        if (*n != 1)
            bad(ARBOR_ERROR_UNSUPPORTED, "ElementNumberOfChannels " + std::to_string(*n) +
                                             ": Arbor reads scalar images (1 channel)");
    }

    void parse_geometry()
    {
        VoxelGrid &g = header_.grid;
        if (const Entry *e = find_any({"elementspacing", "elementsize"})) {
            const std::vector<double> s = reals(*e, ndims_);
            for (std::size_t a = 0; a < ndims_; ++a) {
                if (s[a] <= 0.0)
                    bad(ARBOR_ERROR_FORMAT, shown(*e) + ": every spacing must be positive");
                g.spacing[a] = s[a];
            }
        }
        if (const Entry *e = find_any({"offset", "position", "origin"})) {
            const std::vector<double> o = reals(*e, ndims_);
            for (std::size_t a = 0; a < ndims_; ++a)
                g.origin[a] = o[a];
        }
        if (const Entry *e = find_any({"transformmatrix", "rotation", "orientation"})) {
            const std::vector<double> m = reals(*e, ndims_ * ndims_);
            for (std::size_t axis = 0; axis < ndims_; ++axis) {
                std::array<double, 3> v{0.0, 0.0, 0.0};
                for (std::size_t c = 0; c < ndims_; ++c)
                    v[c] = m[axis * ndims_ + c];
                if (set_direction_column(g, static_cast<int>(axis), v) == 0.0)
                    bad(ARBOR_ERROR_FORMAT,
                        shown(*e) + ": the direction of axis " + std::to_string(axis) + " is zero");
            }
        }
    }

    bool flag(const Entry &e) const
    {
        const std::optional<bool> b = parse_bool(e.value);
        if (!b)
            bad(ARBOR_ERROR_FORMAT, shown(e) + " is neither True nor False");
        return *b;
    }

    void parse_storage()
    {
        if (const Entry *e = find_any({"elementbyteordermsb", "binarydatabyteordermsb"}))
            header_.byte_order = flag(*e) ? std::endian::big : std::endian::little;
        if (const Entry *e = find("binarydata"))
            header_.binary = flag(*e);
        if (const Entry *e = find("compresseddata"))
            header_.compressed = flag(*e);
        if (const Entry *e = find("compresseddatasize")) {
            const std::optional<int64_t> n = parse_integer(e->value);
            if (!n || *n < 0)
                bad(ARBOR_ERROR_FORMAT, shown(*e) + " is not a whole number >= 0");
            header_.compressed_size = static_cast<uint64_t>(*n);
        }
        if (const Entry *e = find("headersize")) {
            const std::optional<int64_t> n = parse_integer(e->value);
            if (!n || *n < -1)
                bad(ARBOR_ERROR_FORMAT, shown(*e) + " is not a whole number >= -1");
            header_.header_size = *n;
        }
        const Entry &file = *find("elementdatafile");
        const auto words = split_words(file.value);
        if (words.empty())
            bad(ARBOR_ERROR_FORMAT, "ElementDataFile names no file");
        if (iequals(file.value, "LOCAL"))
            return;
        if (words[0] == "LIST")
            bad(ARBOR_ERROR_UNSUPPORTED,
                "'ElementDataFile = LIST' spreads the voxels over several files; "
                "Arbor reads one data file per volume");
        if (file.value.find('%') != std::string::npos)
            bad(ARBOR_ERROR_UNSUPPORTED,
                "ElementDataFile " + excerpt(file.value) +
                    " spreads the voxels over numbered files; Arbor reads one data "
                    "file per volume");
        header_.data_file = file.value;
    }

    std::string_view text_;
    std::string_view file_;
    std::map<std::string, Entry> entries_;
    std::size_t ndims_ = 0;
    MetaImageHeader header_;
};

} // namespace

std::optional<std::size_t> metaimage_header_length(std::string_view text)
{
    LineCursor lines(text);
    std::string_view line, key, value;
    while (lines.next(line))
        if (split_entry(line, key, value) && iequals(key, "ElementDataFile") &&
            text[lines.offset() - 1] == '\n')
            return lines.offset();
    return std::nullopt;
}

bool looks_like_metaimage(std::string_view head)
{
    LineCursor lines(head);
    std::string_view line, key, value;
    bool ndims = false, layout = false;
    while (lines.next(line)) {
        if (trim(line).empty())
            continue;
        if (!split_entry(line, key, value))
            break;
        const std::string k = lower(key);
        ndims = ndims || k == "ndims";
        layout = layout || k == "dimsize" || k == "elementtype";
        if (k == "elementdatafile")
            break;
    }
    return ndims && layout;
}

MetaImageHeader parse_metaimage_header(std::string_view text, std::string_view file_name)
{
    return MetaImageParser(text, file_name).parse();
}

} // namespace arbor::importers
