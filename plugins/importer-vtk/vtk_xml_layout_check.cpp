// vtk_xml_layout_check.cpp - see vtk_xml_layout_check.hpp.  The XML
// structure and where each array's data begin come from VTK's own parser
// (vtkXMLDataParser, which keeps no inline data and stops before appended
// data); the headers themselves are read from the file here.
#include "vtk_xml_layout_check.hpp"

#include <arbor/sdk/error.hpp>

#include <vtkBase64Utilities.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string_view>
#include <vector>

namespace arbor::importer_vtk {

namespace {

// Deflate expands at most 1032:1; arrays whose size the XML does not tell
// (strings) are held to that.
constexpr double kMaxExpansion = 1032;

struct HeaderFormat {
    std::size_t word = 4; // header_type UInt32 or UInt64
    bool big_endian = false;
};

// The parser, able to say where an element's inline data begin (VTK keeps
// that to itself).
class InlineDataParser : public vtkXMLDataParser {
public:
    static InlineDataParser *New();
    vtkTypeMacro(InlineDataParser, vtkXMLDataParser);

    uint64_t inline_data_position(vtkXMLDataElement *element)
    {
        SeekInlineDataPosition(element);
        return static_cast<uint64_t>(std::max<vtkTypeInt64>(TellG(), 0));
    }
};
vtkStandardNewMacro(InlineDataParser);

// Where an array's bytes are in the file: raw from an offset (appended raw
// data), or base64 text (inline data, appended base64 data).
struct ArrayBytes {
    const std::string *path = nullptr;
    uint64_t start = 0;
    bool base64 = false;

    // Up to `count` decoded bytes from the start.
    std::vector<unsigned char> prefix(std::size_t count) const
    {
        std::ifstream in(*path, std::ios::binary);
        in.seekg(static_cast<std::streamoff>(start));
        // Base64 takes 4 characters for 3 bytes; white space may be mixed in.
        std::string encoded(base64 ? count / 3 * 4 + 64 + count / 8 : count, '\0');
        in.read(encoded.data(), static_cast<std::streamsize>(encoded.size()));
        encoded.resize(static_cast<std::size_t>(in.gcount()));
        if (!base64)
            return {encoded.begin(), encoded.end()};
        return decode(encoded, count);
    }

    static std::vector<unsigned char> decode(std::string_view text, std::size_t count)
    {
        std::vector<unsigned char> out;
        unsigned char quad[4];
        int have = 0;
        for (const char c : text) {
            if (out.size() >= count)
                break;
            if (std::isspace(static_cast<unsigned char>(c)))
                continue;
            quad[have++] = static_cast<unsigned char>(c);
            if (have < 4)
                continue;
            have = 0;
            unsigned char bytes[3];
            const int n = vtkBase64Utilities::DecodeTriplet(quad[0], quad[1], quad[2], quad[3], &bytes[0],
                                                            &bytes[1], &bytes[2]);
            if (n <= 0)
                break;
            out.insert(out.end(), bytes, bytes + n);
        }
        if (out.size() > count)
            out.resize(count);
        return out;
    }
};

// A byte count that may not fit in 64 bits.
std::string count_text(double bytes)
{
    char text[64];
    std::snprintf(text, sizeof text, "%.0f", bytes);
    return text;
}

uint64_t word_at(const std::vector<unsigned char> &bytes, std::size_t index, const HeaderFormat &f)
{
    uint64_t v = 0;
    for (std::size_t i = 0; i < f.word; ++i) {
        const std::size_t at = index * f.word + (f.big_endian ? i : f.word - 1 - i);
        v = v << 8 | bytes[at];
    }
    return v;
}

// Bytes of a value of VTK XML type `name`, 0 when it is not a number type.
double type_size(const char *name)
{
    static const std::pair<const char *, double> kSizes[] = {
        {"Int8", 1},  {"UInt8", 1},  {"Int16", 2},   {"UInt16", 2},  {"Int32", 4},
        {"UInt32", 4}, {"Int64", 8}, {"UInt64", 8}, {"Float32", 4}, {"Float64", 8},
    };
    for (const auto &[type, size] : kSizes)
        if (name && std::strcmp(name, type) == 0)
            return size;
    return 0;
}

// Bytes the array holds as its piece's extent (points or cells) or its
// NumberOfTuples says; 0 when the XML does not tell.
double array_bytes(vtkXMLDataElement &array)
{
    int components = 1;
    if (array.GetScalarAttribute("NumberOfComponents", components) && components < 1)
        components = 1;
    const double value = type_size(array.GetAttribute("type")) * components;
    long tuples = 0;
    if (array.GetScalarAttribute("NumberOfTuples", tuples))
        return tuples > 0 ? value * static_cast<double>(tuples) : 0.0;
    vtkXMLDataElement *group = array.GetParent();
    vtkXMLDataElement *piece = group ? group->GetParent() : nullptr;
    int extent[6];
    if (!piece || piece->GetVectorAttribute("Extent", 6, extent) != 6)
        return 0.0;
    const bool cells = group->GetName() && std::strcmp(group->GetName(), "CellData") == 0;
    double count = 1;
    for (int a = 0; a < 3; ++a)
        count *= std::max(1.0, double(extent[2 * a + 1]) - double(extent[2 * a]) + (cells ? 0.0 : 1.0));
    return value * count;
}

std::string array_label(vtkXMLDataElement &array)
{
    const char *name = array.GetAttribute("Name");
    const char *group = array.GetParent() && array.GetParent()->GetName() ? array.GetParent()->GetName() : "";
    return std::string(group) + " array '" + (name ? name : "") + "'";
}

void check_header(const ArrayBytes &bytes, double available, double array_size, const HeaderFormat &f,
                  const std::string &what, const std::string &array)
{
    const auto fail = [&](const std::string &problem) {
        sdk::fail(ARBOR_ERROR_FORMAT, what + ": the compressed data of " + array + " " + problem);
    };
    const std::vector<unsigned char> head = bytes.prefix(3 * f.word);
    if (head.size() < 3 * f.word)
        fail("ends inside its compression header");
    const uint64_t blocks = word_at(head, 0, f), block_size = word_at(head, 1, f), last = word_at(head, 2, f);
    const double header_bytes = (3.0 + double(blocks)) * double(f.word);
    if (header_bytes > available)
        fail("claims " + std::to_string(blocks) + " blocks, whose sizes alone need more than the " +
             count_text(available) + " bytes the file holds there");
    if (blocks == 0) {
        if (last != 0) // VTK's total size would wrap around, and it would read block 0 of an empty table
            fail("claims no blocks but a last block of " + std::to_string(last) + " bytes");
        return;
    }
    if (block_size == 0 || last > block_size)
        fail("claims blocks of " + std::to_string(block_size) + " bytes and a last block of " +
             std::to_string(last) + " bytes (it must be smaller, 0 meaning full)");
    const std::vector<unsigned char> all = bytes.prefix(static_cast<std::size_t>(header_bytes));
    if (all.size() < static_cast<std::size_t>(header_bytes))
        fail("ends inside its compression header");
    double compressed = 0, largest_compressed = 0;
    for (uint64_t b = 0; b < blocks; ++b) {
        const double size = double(word_at(all, 3 + b, f));
        compressed += size;
        largest_compressed = std::max(largest_compressed, size);
    }
    if (header_bytes + compressed > available)
        fail("claims " + count_text(compressed) + " compressed bytes, more than the " +
             count_text(available - header_bytes) + " the file holds there");
    const double largest = blocks == 1 && last > 0 ? double(last) : double(block_size);
    const double bound = array_size > 0 ? array_size : kMaxExpansion * largest_compressed;
    if (largest > bound)
        fail("decompresses to blocks of " + count_text(largest) + " bytes, more than the " + count_text(bound) +
             (array_size > 0 ? " bytes of the whole array" : " bytes deflate can expand them to"));
}

void collect_arrays(vtkXMLDataElement &e, std::vector<vtkXMLDataElement *> &out)
{
    if (e.GetName() && std::strcmp(e.GetName(), "DataArray") == 0)
        out.push_back(&e);
    for (int i = 0; i < e.GetNumberOfNestedElements(); ++i)
        if (vtkXMLDataElement *nested = e.GetNestedElement(i))
            collect_arrays(*nested, out);
}

std::string extent_text(const int *e)
{
    std::string out;
    for (int a = 0; a < 3; ++a)
        out += (a ? " x " : "") + std::to_string(e[2 * a]) + ".." + std::to_string(e[2 * a + 1]);
    return out;
}

void check_piece_extents(vtkXMLDataElement &root, const std::string &what)
{
    vtkXMLDataElement *image = root.FindNestedElementWithName("ImageData");
    int whole[6];
    if (!image || image->GetVectorAttribute("WholeExtent", 6, whole) != 6)
        return; // VTK's reader says what is missing
    int pieces = 0;
    for (int i = 0; i < image->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement *piece = image->GetNestedElement(i);
        if (!piece || !piece->GetName() || std::strcmp(piece->GetName(), "Piece") != 0)
            continue;
        ++pieces;
        int extent[6];
        if (piece->GetVectorAttribute("Extent", 6, extent) != 6)
            continue;
        bool empty = false, inside = true;
        for (int a = 0; a < 3; ++a) {
            empty = empty || extent[2 * a + 1] < extent[2 * a];
            inside = inside && extent[2 * a] >= whole[2 * a] && extent[2 * a + 1] <= whole[2 * a + 1];
        }
        if (!empty && !inside)
            sdk::fail(ARBOR_ERROR_FORMAT, what + ": piece " + std::to_string(pieces) + " covers " +
                                              extent_text(extent) + ", outside the image's whole extent " +
                                              extent_text(whole));
    }
}

// Every compressed binary array's header.
void check_compression_headers(InlineDataParser &parser, const std::string &path, uint64_t file_size,
                               const std::string &what)
{
    vtkXMLDataElement *root = parser.GetRootElement();
    if (!root->GetAttribute("compressor") || !*root->GetAttribute("compressor"))
        return; // VTK reads uncompressed data by the extent, not by a header
    HeaderFormat format;
    if (const char *type = root->GetAttribute("header_type"); type && std::strcmp(type, "UInt64") == 0)
        format.word = 8;
    if (const char *order = root->GetAttribute("byte_order"); order && std::strcmp(order, "BigEndian") == 0)
        format.big_endian = true;
    vtkXMLDataElement *appended = root->FindNestedElementWithName("AppendedData");
    const bool appended_base64 = appended && appended->GetAttribute("encoding") &&
                                 std::strcmp(appended->GetAttribute("encoding"), "base64") == 0;
    const uint64_t appended_at = static_cast<uint64_t>(std::max<vtkTypeInt64>(parser.GetAppendedDataPosition(), 0));

    std::vector<vtkXMLDataElement *> arrays;
    collect_arrays(*root, arrays);
    for (vtkXMLDataElement *array : arrays) {
        // As VTK decides: an offset means appended data, else format="binary" inline base64.
        const char *form = array->GetAttribute("format");
        ArrayBytes bytes;
        bytes.path = &path;
        double available = 0;
        if (array->GetAttribute("offset")) {
            long offset = 0;
            array->GetScalarAttribute("offset", offset);
            if (offset < 0 || uint64_t(offset) >= file_size - std::min(file_size, appended_at))
                continue; // VTK cannot seek there, and says so
            bytes.start = appended_at + uint64_t(offset);
            bytes.base64 = appended_base64;
            available = double(file_size - bytes.start) * (appended_base64 ? 0.75 : 1.0);
        } else if (form && std::strcmp(form, "binary") == 0) {
            bytes.start = parser.inline_data_position(array);
            if (bytes.start >= file_size)
                continue; // VTK finds no data there, and says so
            bytes.base64 = true;
            available = double(file_size - bytes.start) * 0.75;
        } else {
            continue; // ASCII: no header
        }
        check_header(bytes, available, array_bytes(*array), format, what, array_label(*array));
    }
}

} // namespace

void check_xml_image_layout(const std::string &path, uint64_t file_size, const std::string &what)
{
    // A stream of ours stays open after the parse, to find inline data in.
    std::ifstream stream(path, std::ios::binary);
    vtkNew<InlineDataParser> parser;
    parser->SetStream(&stream);
    if (!stream || !parser->Parse() || !parser->GetRootElement())
        return;
    check_piece_extents(*parser->GetRootElement(), what);
    check_compression_headers(*parser, path, file_size, what);
}

} // namespace arbor::importer_vtk
