// nrrd_header.cpp - see nrrd_header.hpp.  Fields are first collected (each
// once), then interpreted in dependency order, so that their order in the file
// does not matter.  The geometry fields are read by nrrd_geometry.cpp.
#include "nrrd_header.hpp"

#include "nrrd_geometry.hpp"
#include "number_text.hpp"
#include "text_scan.hpp"

#include <arbor/sdk/error.hpp>

#include <cmath>
#include <map>
#include <vector>

namespace arbor::importers {

namespace {

struct TypeName {
    const char *name;
    arbor_voxel_type type;
};

// Every spelling the NRRD specification allows for the types Arbor holds.
constexpr TypeName kTypes[] = {
    {"signed char", ARBOR_VOXEL_I8},
    {"int8", ARBOR_VOXEL_I8},
    {"int8_t", ARBOR_VOXEL_I8},
    {"uchar", ARBOR_VOXEL_U8},
    {"unsigned char", ARBOR_VOXEL_U8},
    {"uint8", ARBOR_VOXEL_U8},
    {"uint8_t", ARBOR_VOXEL_U8},
    {"short", ARBOR_VOXEL_I16},
    {"short int", ARBOR_VOXEL_I16},
    {"signed short", ARBOR_VOXEL_I16},
    {"signed short int", ARBOR_VOXEL_I16},
    {"int16", ARBOR_VOXEL_I16},
    {"int16_t", ARBOR_VOXEL_I16},
    {"ushort", ARBOR_VOXEL_U16},
    {"unsigned short", ARBOR_VOXEL_U16},
    {"unsigned short int", ARBOR_VOXEL_U16},
    {"uint16", ARBOR_VOXEL_U16},
    {"uint16_t", ARBOR_VOXEL_U16},
    {"int", ARBOR_VOXEL_I32},
    {"signed int", ARBOR_VOXEL_I32},
    {"int32", ARBOR_VOXEL_I32},
    {"int32_t", ARBOR_VOXEL_I32},
    {"uint", ARBOR_VOXEL_U32},
    {"unsigned int", ARBOR_VOXEL_U32},
    {"uint32", ARBOR_VOXEL_U32},
    {"uint32_t", ARBOR_VOXEL_U32},
    {"float", ARBOR_VOXEL_F32},
    {"double", ARBOR_VOXEL_F64},
};

constexpr const char *k64BitTypes[] = {
    "longlong", "long long", "long long int", "signed long long",   "signed long long int",
    "int64",    "int64_t",   "ulonglong",     "unsigned long long", "unsigned long long int",
    "uint64",   "uint64_t",
};

// "space directions" and "Space Directions" name the same field, as do the
// old spellings without spaces ("datafile", "lineskip", "byteskip").
std::string field_key(std::string_view name)
{
    std::string key;
    for (char c : lower(trim(name)))
        if (c != ' ' && c != '\t')
            key += c;
    return key;
}

// Lowercase with runs of blanks folded to one space: "unsigned  short".
std::string type_key(std::string_view text)
{
    std::string key;
    for (std::string_view word : split_words(text)) {
        if (!key.empty())
            key += ' ';
        key += lower(word);
    }
    return key;
}

// Key/value values escape newlines and backslashes.
std::string unescape(std::string_view s)
{
    std::string out;
    for (std::size_t i = 0; i < s.size(); ++i) {
        if (s[i] == '\\' && i + 1 < s.size() && (s[i + 1] == 'n' || s[i + 1] == '\\')) {
            out += s[i + 1] == 'n' ? '\n' : '\\';
            ++i;
        } else {
            out += s[i];
        }
    }
    return out;
}

class NrrdParser {
public:
    NrrdParser(std::string_view text, std::string_view file_name)
        : text_(text), file_(file_name), fields_{{}, std::string(file_name)}
    {
    }

    NrrdHeader parse()
    {
        collect();
        parse_dimension();
        parse_type();
        parse_sizes();
        parse_kinds();
        parse_encoding();
        parse_endian();
        parse_data_file();
        parse_skips();
        read_nrrd_geometry(fields_, dimension_, header_.grid);
        parse_value_mapping();
        return header_;
    }

private:
    [[noreturn]] void bad(arbor_status status, const std::string &problem) const
    {
        fields_.bad(status, problem);
    }

    const NrrdField *find(const char *key) const { return fields_.find(key); }

    const NrrdField &require(const char *key, const char *name) const
    {
        const NrrdField *f = find(key);
        if (!f)
            bad(ARBOR_ERROR_FORMAT, std::string("has no '") + name + "' field");
        return *f;
    }

    static std::string shown(const NrrdField &f) { return NrrdFields::shown(f); }

    void collect()
    {
        if (text_.empty())
            sdk::fail(ARBOR_ERROR_FORMAT, std::string(file_) + " is empty, not a NRRD file");
        LineCursor lines(text_);
        std::string_view line;
        if (!lines.next(line) || !has_nrrd_magic(line))
            sdk::fail(ARBOR_ERROR_FORMAT, std::string(file_) +
                                              " is not a NRRD file: it starts with " +
                                              excerpt(line, 16) + " instead of NRRD0001..NRRD0005");
        const char version = line[7];
        if (version < '1' || version > '5' || trim(line).size() != 8)
            bad(ARBOR_ERROR_UNSUPPORTED,
                "magic " + excerpt(trim(line), 16) +
                    " is not a NRRD format version Arbor reads (NRRD0001..NRRD0005)");
        while (lines.next(line)) {
            if (line.empty())
                break; // the blank line that ends the header
            if (line.front() == '#')
                continue;
            const std::size_t colon = line.find(':');
            if (colon == std::string_view::npos || colon == 0)
                bad(ARBOR_ERROR_FORMAT, "line " + std::to_string(lines.number()) + " " +
                                            excerpt(line) +
                                            " is neither a field ('name: value'), a key/value pair "
                                            "('key:=value') nor a comment");
            if (colon + 1 < line.size() && line[colon + 1] == '=') {
                keys_[std::string(line.substr(0, colon))] = unescape(line.substr(colon + 2));
                continue;
            }
            NrrdField field{std::string(trim(line.substr(0, colon))),
                            std::string(trim(line.substr(colon + 1)))};
            const std::string key = field_key(field.name);
            // The lines after "data file: LIST" are file names, not fields.
            if (key == "datafile") {
                const auto words = split_words(field.value);
                if (!words.empty() && words[0] == "LIST")
                    bad(ARBOR_ERROR_UNSUPPORTED,
                        "'data file: LIST' spreads the voxels over several files; Arbor reads one "
                        "data file per volume");
            }
            if (!fields_.entries.emplace(key, std::move(field)).second)
                bad(ARBOR_ERROR_FORMAT,
                    "field " + excerpt(trim(line.substr(0, colon))) + " appears twice");
        }
    }

    void parse_dimension()
    {
        const NrrdField &f = require("dimension", "dimension");
        const std::optional<int64_t> n = parse_integer(f.value);
        if (!n || *n < 1)
            bad(ARBOR_ERROR_FORMAT,
                "dimension " + excerpt(f.value) + " is not a positive whole number");
        if (*n != 2 && *n != 3)
            bad(ARBOR_ERROR_UNSUPPORTED,
                "dimension " + std::to_string(*n) +
                    ": Arbor reads scalar volumes with 3 axes (or 2, as one slice)");
        dimension_ = static_cast<int>(*n);
    }

    void parse_type()
    {
        const NrrdField &f = require("type", "type");
        const std::string key = type_key(f.value);
        for (const TypeName &t : kTypes)
            if (key == t.name) {
                header_.grid.type = t.type;
                return;
            }
        for (const char *name : k64BitTypes)
            if (key == name)
                bad(ARBOR_ERROR_UNSUPPORTED,
                    "type " + excerpt(f.value) +
                        ": 64-bit integer voxels are not supported (Arbor holds "
                        "8-, 16- and 32-bit integers, float and double)");
        if (key == "block")
            bad(ARBOR_ERROR_UNSUPPORTED,
                "type 'block' (opaque blocks of bytes) is not a scalar voxel type");
        bad(ARBOR_ERROR_FORMAT, "type " + excerpt(f.value) + " is not a NRRD type");
    }

    void parse_sizes()
    {
        const NrrdField &f = require("sizes", "sizes");
        const auto words = split_words(f.value);
        if (words.size() != static_cast<std::size_t>(dimension_))
            bad(ARBOR_ERROR_FORMAT, shown(f) + " has " + std::to_string(words.size()) +
                                        " numbers, but dimension is " + std::to_string(dimension_));
        for (int a = 0; a < dimension_; ++a) {
            const std::optional<int64_t> n = parse_integer(words[static_cast<std::size_t>(a)]);
            if (!n)
                bad(ARBOR_ERROR_FORMAT, shown(f) + ": " +
                                            excerpt(words[static_cast<std::size_t>(a)]) +
                                            " is not a whole number that fits in 64 bits");
            if (*n < 1)
                bad(ARBOR_ERROR_FORMAT, shown(f) + ": every size must be at least 1");
            header_.grid.dims[static_cast<std::size_t>(a)] = *n;
        }
    }

    // Axes whose kind says they hold components (vector, colour, matrix,
    // list...) rather than positions would be misread as a spatial axis.
    void parse_kinds()
    {
        const NrrdField *f = find("kinds");
        if (!f)
            return;
        const auto words = split_words(f->value);
        if (words.size() != static_cast<std::size_t>(dimension_))
            bad(ARBOR_ERROR_FORMAT, shown(*f) + " has " + std::to_string(words.size()) +
                                        " entries, but dimension is " + std::to_string(dimension_));
        for (std::size_t a = 0; a < words.size(); ++a) {
            const std::string kind = lower(words[a]);
            if (kind != "domain" && kind != "space" && kind != "time" && kind != "none" &&
                kind != "???" && kind != "stub" && kind != "scalar")
                bad(ARBOR_ERROR_UNSUPPORTED,
                    "kinds: axis " + std::to_string(a) + " is " + excerpt(words[a]) +
                        " (not a spatial axis); Arbor reads scalar volumes whose axes "
                        "are all spatial");
        }
    }

    void parse_encoding()
    {
        const NrrdField &f = require("encoding", "encoding");
        const std::string e = lower(f.value);
        if (e == "raw")
            header_.encoding = NrrdEncoding::raw;
        else if (e == "gzip" || e == "gz")
            header_.encoding = NrrdEncoding::gzip;
        else if (e == "ascii" || e == "text" || e == "txt")
            header_.encoding = NrrdEncoding::ascii;
        else
            bad(ARBOR_ERROR_UNSUPPORTED,
                "encoding " + excerpt(f.value) +
                    " is not supported; Arbor reads raw, gzip and ascii NRRD data");
    }

    void parse_endian()
    {
        const NrrdField *f = find("endian");
        const bool matters =
            arbor_voxel_size(header_.grid.type) > 1 && header_.encoding != NrrdEncoding::ascii;
        if (!f) {
            if (matters)
                bad(ARBOR_ERROR_FORMAT, "type " +
                                            std::string(arbor_voxel_type_name(header_.grid.type)) +
                                            " with " + require("encoding", "encoding").value +
                                            " encoding needs an 'endian' field (little or big)");
            return;
        }
        const std::string e = lower(f->value);
        if (e == "little")
            header_.byte_order = std::endian::little;
        else if (e == "big")
            header_.byte_order = std::endian::big;
        else
            bad(ARBOR_ERROR_FORMAT, "endian " + excerpt(f->value) + " is neither little nor big");
    }

    void parse_data_file()
    {
        const NrrdField *f = find("datafile");
        if (!f)
            return;
        const auto words = split_words(f->value);
        if (words.empty())
            bad(ARBOR_ERROR_FORMAT, "'data file' names no file");
        if (words.size() >= 4 && words[0].find('%') != std::string_view::npos)
            bad(ARBOR_ERROR_UNSUPPORTED,
                "'data file: " + std::string(words[0]) +
                    " ...' spreads the voxels over numbered files; Arbor reads "
                    "one data file per volume");
        header_.data_file = f->value;
    }

    void parse_skips()
    {
        if (const NrrdField *f = find("lineskip")) {
            const std::optional<int64_t> n = parse_integer(f->value);
            if (!n || *n < 0)
                bad(ARBOR_ERROR_FORMAT, shown(*f) + " is not a whole number >= 0");
            header_.line_skip = *n;
        }
        if (const NrrdField *f = find("byteskip")) {
            const std::optional<int64_t> n = parse_integer(f->value);
            if (!n || *n < -1)
                bad(ARBOR_ERROR_FORMAT, shown(*f) + " is not a whole number >= -1");
            if (*n == -1 && header_.encoding != NrrdEncoding::raw)
                bad(ARBOR_ERROR_FORMAT,
                    "byte skip -1 (data at the end of the file) needs raw encoding");
            header_.byte_skip = *n;
        }
    }

    void parse_value_mapping()
    {
        const auto real = [&](const char *key, double &out) {
            const auto it = keys_.find(key);
            if (it == keys_.end())
                return;
            const std::optional<double> v = parse_real(trim(it->second));
            if (!v || !std::isfinite(*v))
                bad(ARBOR_ERROR_FORMAT,
                    std::string(key) + ":=" + excerpt(it->second) + " is not a finite number");
            out = *v;
        };
        real("arbor_value_scale", header_.mapping.scale);
        real("arbor_value_offset", header_.mapping.offset);
        if (const auto it = keys_.find("arbor_value_unit"); it != keys_.end())
            header_.mapping.unit = it->second;
    }

    std::string_view text_;
    std::string_view file_;
    NrrdFields fields_;
    std::map<std::string, std::string> keys_;
    int dimension_ = 0;
    NrrdHeader header_;
};

} // namespace

bool has_nrrd_magic(std::string_view head)
{
    return head.size() >= 8 && head.substr(0, 7) == "NRRD000" && head[7] >= '0' && head[7] <= '9';
}

std::optional<std::size_t> nrrd_header_length(std::string_view text)
{
    LineCursor lines(text);
    std::string_view line;
    while (lines.next(line))
        if (line.empty() && lines.number() > 1 && text[lines.offset() - 1] == '\n')
            return lines.offset();
    return std::nullopt;
}

NrrdHeader parse_nrrd_header(std::string_view text, std::string_view file_name)
{
    return NrrdParser(text, file_name).parse();
}

} // namespace arbor::importers
