// vtk_file_kind.cpp - sniffing the XML <VTKFile type="..."> attribute and the
// legacy "# vtk DataFile" header without a VTK reader (cheap enough for
// probing, and able to name a dataset type the readers would refuse).
#include "vtk_file_kind.hpp"

#include <cctype>
#include <sstream>

namespace arbor::importer_vtk {

namespace {

std::string upper(std::string s)
{
    for (char &c : s)
        c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    return s;
}

std::string_view skip_space(std::string_view s)
{
    // A UTF-8 byte order mark may precede an XML declaration.
    if (s.substr(0, 3) == "\xEF\xBB\xBF")
        s.remove_prefix(3);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
        s.remove_prefix(1);
    return s;
}

// Value of attribute `name` inside one start tag (text up to its '>').
std::string attribute(std::string_view tag, std::string_view name)
{
    std::size_t at = 0;
    while ((at = tag.find(name, at)) != std::string_view::npos) {
        const bool word_start = at > 0 && std::isspace(static_cast<unsigned char>(tag[at - 1]));
        std::size_t p = at + name.size();
        at = p;
        if (!word_start)
            continue;
        while (p < tag.size() && std::isspace(static_cast<unsigned char>(tag[p])))
            ++p;
        if (p >= tag.size() || tag[p] != '=')
            continue;
        ++p;
        while (p < tag.size() && std::isspace(static_cast<unsigned char>(tag[p])))
            ++p;
        if (p >= tag.size() || (tag[p] != '"' && tag[p] != '\''))
            continue;
        const char quote = tag[p++];
        const std::size_t end = tag.find(quote, p);
        if (end == std::string_view::npos)
            return "";
        return std::string(tag.substr(p, end - p));
    }
    return "";
}

// Any XML file starts like a .vti; only a <VTKFile> element makes it VTK's.
VtkFileKind classify_xml(std::string_view text)
{
    VtkFileKind kind;
    const std::size_t open = text.find("<VTKFile");
    if (open == std::string_view::npos)
        return kind;
    kind.layout = VtkLayout::xml;
    const std::size_t close = text.find('>', open);
    if (close == std::string_view::npos)
        return kind;
    kind.dataset = attribute(text.substr(open, close - open), "type");
    return kind;
}

// Line 1 "# vtk DataFile Version x.y", line 2 a free title, then (as VTK reads
// it, words separated by any white space) ASCII|BINARY, DATASET, the type.
VtkFileKind classify_legacy(std::string_view text)
{
    VtkFileKind kind;
    kind.layout = VtkLayout::legacy;
    std::size_t eol = text.find('\n');
    if (eol == std::string_view::npos)
        return kind;
    eol = text.find('\n', eol + 1);
    if (eol == std::string_view::npos)
        return kind;
    // Only the header words matter; binary data may follow them.
    std::istringstream words(std::string(text.substr(eol + 1, 512)));
    std::string encoding, keyword, dataset;
    if (!(words >> encoding >> keyword))
        return kind;
    kind.binary = upper(encoding) == "BINARY";
    if (upper(keyword) == "DATASET" && words >> dataset)
        kind.dataset = upper(dataset);
    else if (upper(keyword) != "DATASET")
        kind.dataset = upper(keyword); // e.g. FIELD: a data object, no dataset
    return kind;
}

} // namespace

bool VtkFileKind::is_image() const
{
    return (layout == VtkLayout::xml && dataset == "ImageData") ||
           (layout == VtkLayout::legacy && dataset == "STRUCTURED_POINTS");
}

VtkFileKind classify_vtk_file(std::string_view head)
{
    if (head.substr(0, 14) == "# vtk DataFile")
        return classify_legacy(head);
    const std::string_view text = skip_space(head);
    if (text.substr(0, 5) == "<?xml" || text.substr(0, 8) == "<VTKFile")
        return classify_xml(text);
    return {};
}

} // namespace arbor::importer_vtk
