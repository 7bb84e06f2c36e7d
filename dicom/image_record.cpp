#include "image_record.hpp"

#include "dcmtk_setup.hpp"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dctk.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace arbor::dicom {

namespace fs = std::filesystem;

namespace {

// Large frame counts come from corrupt or hostile headers, not scanners.
constexpr int64_t kMaxFrames = 100000;
// Elements longer than this stay on disk while the header is read.
constexpr Uint32 kHeaderReadLength = 4096;

std::string trimmed(const OFString &s)
{
    std::string t(s.c_str());
    const auto b = t.find_first_not_of(" \t\r\n");
    if (b == std::string::npos)
        return "";
    return t.substr(b, t.find_last_not_of(" \t\r\n") - b + 1);
}

// Bytes that are not valid UTF-8 (a character set DCMTK could not convert)
// become '?', so names can be printed and written to JSON as they are.
std::string valid_utf8(std::string s)
{
    std::size_t i = 0;
    while (i < s.size()) {
        const auto c = static_cast<unsigned char>(s[i]);
        const std::size_t n = c < 0x80 ? 1 : (c >> 5) == 0x6 ? 2 : (c >> 4) == 0xE ? 3 : (c >> 3) == 0x1E ? 4 : 0;
        bool ok = n > 0 && i + n <= s.size();
        for (std::size_t k = 1; ok && k < n; ++k)
            ok = (static_cast<unsigned char>(s[i + k]) & 0xC0) == 0x80;
        if (ok) {
            i += n;
        } else {
            s[i] = '?';
            ++i;
        }
    }
    return s;
}

std::string text(DcmItem &item, const DcmTagKey &tag)
{
    OFString s;
    return item.findAndGetOFStringArray(tag, s).good() ? valid_utf8(trimmed(s)) : std::string();
}

std::vector<std::string> values(DcmItem &item, const DcmTagKey &tag)
{
    std::vector<std::string> out;
    const std::string all = text(item, tag);
    std::size_t start = 0;
    while (!all.empty() && start <= all.size()) {
        const std::size_t end = std::min(all.find('\\', start), all.size());
        OFString part(all.substr(start, end - start).c_str());
        out.push_back(trimmed(part));
        start = end + 1;
    }
    return out;
}

class RecordReader {
public:
    RecordReader(const fs::path &path, DcmItem &dataset) : path_(path), ds_(dataset) {}

    [[noreturn]] void invalid(const std::string &what) const
    {
        throw std::runtime_error(path_.string() + ": " + what);
    }

    // Numeric attribute `tag`, value `pos`; nullopt when absent or empty.
    // Present but not a number is an error that names the attribute.
    std::optional<double> number(DcmItem &item, const DcmTagKey &tag, const char *name,
                                 unsigned long pos = 0) const
    {
        DcmElement *e = nullptr;
        if (item.findAndGetElement(tag, e).bad() || !e || e->getLength() == 0)
            return std::nullopt;
        OFString s;
        if (e->getOFString(s, pos).bad())
            return std::nullopt;
        const std::string t = trimmed(s);
        if (t.empty())
            return std::nullopt;
        char *end = nullptr;
        const double v = std::strtod(t.c_str(), &end);
        if (end == t.c_str() || *end != '\0' || !std::isfinite(v))
            invalid(std::string(name) + " '" + t + "' is not a number");
        return v;
    }

    // Value `pos` of a multi-valued numeric attribute that has that many: an
    // empty one (two backslashes in a row) is an error that names the attribute.
    double value_at(DcmItem &item, const DcmTagKey &tag, const char *name, unsigned long pos) const
    {
        const std::optional<double> v = number(item, tag, name, pos);
        if (!v)
            invalid(std::string(name) + " value " + std::to_string(pos + 1) + " is empty");
        return *v;
    }

    uint32_t whole(DcmItem &item, const DcmTagKey &tag, const char *name, uint32_t fallback) const
    {
        const auto v = number(item, tag, name);
        if (!v)
            return fallback;
        if (*v < 0 || *v > 4294967295.0 || *v != std::floor(*v))
            invalid(std::string(name) + " " + std::to_string(*v) + " is not a valid count");
        return static_cast<uint32_t>(*v);
    }

    template <std::size_t N>
    std::optional<std::array<double, N>> vector(DcmItem &item, const DcmTagKey &tag,
                                                const char *name) const
    {
        DcmElement *e = nullptr;
        if (item.findAndGetElement(tag, e).bad() || !e || e->getLength() == 0)
            return std::nullopt;
        if (e->getVM() != N)
            invalid(std::string(name) + " has " + std::to_string(e->getVM()) + " values, not " +
                    std::to_string(N));
        std::array<double, N> out{};
        for (std::size_t i = 0; i < N; ++i)
            out[i] = value_at(item, tag, name, i);
        return out;
    }

    // First item of functional-group macro `seq` for a frame: per-frame
    // groups override shared ones.
    static DcmItem *macro(DcmItem *per_frame, DcmItem *shared, const DcmTagKey &seq)
    {
        DcmItem *item = nullptr;
        if (per_frame && per_frame->findAndGetSequenceItem(seq, item, 0).good() && item)
            return item;
        if (shared && shared->findAndGetSequenceItem(seq, item, 0).good() && item)
            return item;
        return nullptr;
    }

    void read_geometry(DcmItem &item, FrameGeometry &g) const
    {
        if (auto p = vector<3>(item, DCM_ImagePositionPatient, "Image Position (Patient)"))
            g.position = p;
        if (auto o = vector<6>(item, DCM_ImageOrientationPatient, "Image Orientation (Patient)"))
            g.orientation = o;
        if (auto s = vector<2>(item, DCM_PixelSpacing, "Pixel Spacing")) {
            if (!((*s)[0] > 0) || !((*s)[1] > 0))
                invalid("Pixel Spacing must be positive");
            g.pixel_spacing = s;
        }
    }

    void read_mapping(DcmItem &item, RescaleMapping &m, const std::string &modality) const
    {
        const auto slope = number(item, DCM_RescaleSlope, "Rescale Slope");
        const auto intercept = number(item, DCM_RescaleIntercept, "Rescale Intercept");
        if (slope) {
            if (*slope == 0.0)
                invalid("Rescale Slope is 0");
            m.slope = *slope;
        }
        if (intercept)
            m.intercept = *intercept;
        const std::string type = text(item, DCM_RescaleType);
        if (!type.empty())
            m.unit = type == "US" ? "" : type; // US: unspecified
        else if (modality == "CT" && (slope || intercept))
            m.unit = "HU";
    }

    void read_padding(ImageRecord &r) const
    {
        for (auto [tag, out, name] :
             {std::tuple{DCM_PixelPaddingValue, &r.padding_value, "Pixel Padding Value"},
              std::tuple{DCM_PixelPaddingRangeLimit, &r.padding_range_limit,
                         "Pixel Padding Range Limit"}}) {
            if (auto v = number(ds_, tag, name))
                *out = static_cast<int64_t>(*v);
        }
    }

    void read_pixel_format(ImageRecord &r) const
    {
        r.rows = whole(ds_, DCM_Rows, "Rows", 0);
        r.columns = whole(ds_, DCM_Columns, "Columns", 0);
        r.has_pixel_data = ds_.tagExists(DCM_PixelData);
        if (r.rows == 0 || r.columns == 0)
            return;
        r.samples_per_pixel = whole(ds_, DCM_SamplesPerPixel, "Samples per Pixel", 1);
        r.bits_allocated = whole(ds_, DCM_BitsAllocated, "Bits Allocated", 0);
        r.bits_stored = whole(ds_, DCM_BitsStored, "Bits Stored", r.bits_allocated);
        r.high_bit = whole(ds_, DCM_HighBit, "High Bit", r.bits_stored ? r.bits_stored - 1 : 0);
        r.is_signed = whole(ds_, DCM_PixelRepresentation, "Pixel Representation", 0) == 1;
        r.photometric = text(ds_, DCM_PhotometricInterpretation);
        if (r.bits_allocated != 8 && r.bits_allocated != 16 && r.bits_allocated != 32)
            invalid("Bits Allocated " + std::to_string(r.bits_allocated) +
                    " is not supported (8, 16 or 32)");
        if (r.bits_stored == 0 || r.bits_stored > r.bits_allocated || r.high_bit >= r.bits_allocated ||
            r.high_bit + 1 < r.bits_stored)
            invalid("inconsistent pixel format: Bits Allocated " + std::to_string(r.bits_allocated) +
                    ", Bits Stored " + std::to_string(r.bits_stored) + ", High Bit " +
                    std::to_string(r.high_bit));
        read_padding(r);
    }

    int64_t frame_count() const
    {
        const auto n = number(ds_, DCM_NumberOfFrames, "Number of Frames");
        if (!n)
            return 1;
        if (*n < 1 || *n > kMaxFrames || *n != std::floor(*n))
            invalid("Number of Frames " + std::to_string(*n) + " is out of range (1 to " +
                    std::to_string(kMaxFrames) + ")");
        return static_cast<int64_t>(*n);
    }

    void read_frames(ImageRecord &r) const
    {
        const int64_t n = frame_count();
        DcmItem *shared = nullptr;
        ds_.findAndGetSequenceItem(DCM_SharedFunctionalGroupsSequence, shared, 0);
        DcmSequenceOfItems *per_frame = nullptr;
        ds_.findAndGetSequence(DCM_PerFrameFunctionalGroupsSequence, per_frame);
        if (per_frame && static_cast<int64_t>(per_frame->card()) != n)
            invalid("Per-frame Functional Groups Sequence has " + std::to_string(per_frame->card()) +
                    " items for " + std::to_string(n) + " frames");

        Frame top;
        read_geometry(ds_, top.geometry);
        read_mapping(ds_, top.mapping, r.modality);
        r.frames.assign(static_cast<std::size_t>(n), top);
        if (shared || per_frame) {
            for (int64_t f = 0; f < n; ++f) {
                DcmItem *own = per_frame ? per_frame->getItem(static_cast<unsigned long>(f)) : nullptr;
                Frame &frame = r.frames[static_cast<std::size_t>(f)];
                if (DcmItem *m = macro(own, shared, DCM_PlanePositionSequence))
                    read_geometry(*m, frame.geometry);
                if (DcmItem *m = macro(own, shared, DCM_PlaneOrientationSequence))
                    read_geometry(*m, frame.geometry);
                if (DcmItem *m = macro(own, shared, DCM_PixelMeasuresSequence)) {
                    read_geometry(*m, frame.geometry);
                    if (auto s = number(*m, DCM_SpacingBetweenSlices, "Spacing Between Slices"))
                        r.frame_spacing = *s;
                    else if (auto t = number(*m, DCM_SliceThickness, "Slice Thickness"); t && r.frame_spacing == 0)
                        r.frame_spacing = *t;
                }
                if (DcmItem *m = macro(own, shared, DCM_PixelValueTransformationSequence))
                    read_mapping(*m, frame.mapping, r.modality);
            }
            r.per_frame_positions = n > 1 && macro(per_frame ? per_frame->getItem(1) : nullptr,
                                                   nullptr, DCM_PlanePositionSequence) != nullptr;
        }
        if (r.frame_spacing == 0) {
            if (auto s = number(ds_, DCM_SpacingBetweenSlices, "Spacing Between Slices"))
                r.frame_spacing = *s;
            else if (auto t = number(ds_, DCM_SliceThickness, "Slice Thickness"))
                r.frame_spacing = *t;
        }
        if (!(r.frame_spacing > 0))
            r.frame_spacing = 0;
        offset_frames_along_grid(r);
    }

    // RT Dose and some NM objects place frames with Grid Frame Offset Vector
    // (offsets along the normal from the first frame's position).
    void offset_frames_along_grid(ImageRecord &r) const
    {
        if (r.per_frame_positions || r.frames.size() < 2)
            return;
        const auto &g0 = r.frames[0].geometry;
        DcmElement *e = nullptr;
        if (!g0.position || !g0.orientation ||
            ds_.findAndGetElement(DcmTagKey(0x3004, 0x000C), e).bad() || !e ||
            e->getVM() != r.frames.size())
            return;
        const auto &o = *g0.orientation;
        const std::array<double, 3> n = {o[1] * o[5] - o[2] * o[4], o[2] * o[3] - o[0] * o[5],
                                         o[0] * o[4] - o[1] * o[3]};
        for (std::size_t f = 0; f < r.frames.size(); ++f) {
            const double d = value_at(ds_, DcmTagKey(0x3004, 0x000C), "Grid Frame Offset Vector", f);
            std::array<double, 3> p = *g0.position;
            for (int a = 0; a < 3; ++a)
                p[static_cast<std::size_t>(a)] += d * n[static_cast<std::size_t>(a)];
            r.frames[f].geometry.position = p;
        }
        r.per_frame_positions = true;
    }

private:
    const fs::path &path_;
    DcmItem &ds_;
};

} // namespace

bool ImageRecord::is_localizer() const
{
    return std::find(image_type.begin(), image_type.end(), "LOCALIZER") != image_type.end();
}

bool looks_like_dicom(const uint8_t *head, std::size_t size)
{
    if (size >= 132 && std::memcmp(head + 128, "DICM", 4) == 0)
        return true;
    if (size < 8)
        return false;
    const unsigned group_le = head[0] | (head[1] << 8);
    const unsigned group_be = (head[0] << 8) | head[1];
    const unsigned element_le = head[2] | (head[3] << 8);
    return ((group_le == 0x0002 || group_le == 0x0008) && element_le < 0x0200) ||
           (group_be == 0x0008 && head[2] == 0x00);
}

bool looks_like_dicom(const fs::path &path)
{
    std::ifstream in(path, std::ios::binary);
    uint8_t head[132] = {};
    in.read(reinterpret_cast<char *>(head), sizeof head);
    return looks_like_dicom(head, static_cast<std::size_t>(in.gcount()));
}

ImageRecord read_image_record(const fs::path &path)
{
    ensure_dcmtk_ready();
    DcmFileFormat file;
    const OFCondition status = file.loadFile(OFFilename(path.c_str()), EXS_Unknown, EGL_noChange,
                                             kHeaderReadLength, ERM_autoDetect);
    if (status.bad())
        throw std::runtime_error(path.string() + ": not readable as DICOM (" + status.text() + ")");
    DcmDataset &ds = *file.getDataset();
    // Names and descriptions in UTF-8 whatever Specific Character Set says;
    // what cannot be converted is cleaned up by text().
    ds.convertToUTF8();
    ImageRecord r;
    r.path = path;
    const DcmXfer xfer(ds.getOriginalXfer());
    r.transfer_syntax_uid = xfer.getXferID();
    r.transfer_syntax_name = xfer.getXferName();
    const std::pair<std::string ImageRecord::*, DcmTagKey> identity[] = {
        {&ImageRecord::sop_class_uid, DCM_SOPClassUID},
        {&ImageRecord::sop_instance_uid, DCM_SOPInstanceUID},
        {&ImageRecord::study_uid, DCM_StudyInstanceUID},
        {&ImageRecord::series_uid, DCM_SeriesInstanceUID},
        {&ImageRecord::frame_of_reference_uid, DCM_FrameOfReferenceUID},
        {&ImageRecord::patient_name, DCM_PatientName},
        {&ImageRecord::patient_id, DCM_PatientID},
        {&ImageRecord::study_date, DCM_StudyDate},
        {&ImageRecord::study_description, DCM_StudyDescription},
        {&ImageRecord::series_description, DCM_SeriesDescription},
        {&ImageRecord::series_number, DCM_SeriesNumber},
        {&ImageRecord::modality, DCM_Modality},
    };
    for (const auto &[member, tag] : identity)
        r.*member = text(ds, tag);
    r.image_type = values(ds, DCM_ImageType);
    RecordReader reader(path, ds);
    if (auto n = reader.number(ds, DCM_InstanceNumber, "Instance Number"))
        r.instance_number = static_cast<int64_t>(*n);
    reader.read_pixel_format(r);
    if (r.rows > 0 && r.columns > 0)
        reader.read_frames(r);
    return r;
}

} // namespace arbor::dicom
