// nrrd_fields.hpp - the fields of a NRRD header as collected from its lines,
// keyed without case and blanks ("space directions" -> "spacedirections"),
// and how problems with them are reported.  Shared by the parts of the NRRD
// parser (nrrd_header.cpp, nrrd_geometry.cpp).
#pragma once

#include "text_scan.hpp"

#include <arbor/sdk/error.hpp>

#include <map>
#include <string>

namespace arbor::importers {

struct NrrdField {
    std::string name; // as written, for messages
    std::string value;
};

struct NrrdFields {
    std::map<std::string, NrrdField> entries;
    std::string file_name;

    const NrrdField *find(const char *key) const
    {
        const auto it = entries.find(key);
        return it == entries.end() ? nullptr : &it->second;
    }

    [[noreturn]] void bad(arbor_status status, const std::string &problem) const
    {
        sdk::fail(status, "header of " + file_name + ": " + problem);
    }

    // A field for messages, e.g. "sizes '0 64 64'".
    static std::string shown(const NrrdField &f) { return f.name + " " + excerpt(f.value); }
};

} // namespace arbor::importers
