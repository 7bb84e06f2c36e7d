#include "series_volume.hpp"

#include "pixel_frames.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <stdexcept>

namespace arbor::dicom {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string number(double v)
{
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string plane_name(const std::array<double, 6> &o)
{
    const Vec3 n = slice_normal(o);
    const double x = std::abs(n[0]), y = std::abs(n[1]), z = std::abs(n[2]);
    if (std::max({x, y, z}) < 0.9)
        return "oblique";
    return z >= x && z >= y ? "axial" : (y >= x ? "coronal" : "sagittal");
}

// Images that can share a volume: same size, orientation, pixel spacing and
// pixel format.
std::string agreement_key(const ImageRecord &r)
{
    const FrameGeometry &g = r.frames.front().geometry;
    std::string key = std::to_string(r.columns) + "x" + std::to_string(r.rows);
    if (g.orientation) {
        key += " " + plane_name(*g.orientation) + " (";
        for (std::size_t i = 0; i < 6; ++i)
            key += number(std::round((*g.orientation)[i] * 1e4) / 1e4 + 0.0) + (i == 5 ? ")" : ",");
    }
    if (g.pixel_spacing)
        key += ", pixels " + number((*g.pixel_spacing)[1]) + "x" + number((*g.pixel_spacing)[0]) + " mm";
    key += ", " + r.photometric;
    return key;
}

std::array<int64_t, 2> type_range(arbor_voxel_type t)
{
    switch (t) {
    case ARBOR_VOXEL_U8: return {0, 255};
    case ARBOR_VOXEL_I8: return {-128, 127};
    case ARBOR_VOXEL_U16: return {0, 65535};
    case ARBOR_VOXEL_I16: return {-32768, 32767};
    case ARBOR_VOXEL_U32: return {0, 4294967295LL};
    case ARBOR_VOXEL_I32: return {-2147483648LL, 2147483647LL};
    default: return {0, 0};
    }
}

template <class T>
T output_value(double v, double lo, double hi)
{
    if constexpr (std::is_floating_point_v<T>) {
        return static_cast<T>(v);
    } else {
        const double r = v >= 0 ? v + 0.5 : v - 0.5; // half away from zero
        return static_cast<T>(static_cast<int64_t>(r < lo ? lo : (r > hi ? hi : r)));
    }
}

// Writes one slice of values in output units: integers rounded and clamped
// to the type.  A NaN (no measured value) is written as 0 and its voxel index
// (`first` + i) set in the bit set `marks`, which is null when no NaN can
// occur; the lowest measured value is tracked.  Returns the NaNs.
template <class T>
std::size_t store_slice(const double *values, std::size_t n, T *out, double lo, double hi, uint64_t *marks,
                        std::size_t first, double &lowest)
{
    double low = lowest;
    std::size_t unmeasured = 0;
    if (!marks) {
        for (std::size_t i = 0; i < n; ++i) {
            low = std::min(low, values[i]);
            out[i] = output_value<T>(values[i], lo, hi);
        }
    } else {
        for (std::size_t i = 0; i < n; ++i) {
            const double v = values[i];
            if (std::isnan(v)) {
                marks[(first + i) >> 6] |= uint64_t{1} << ((first + i) & 63);
                ++unmeasured;
                out[i] = T(0);
            } else {
                low = std::min(low, v);
                out[i] = output_value<T>(v, lo, hi);
            }
        }
    }
    lowest = low;
    return unmeasured;
}

// Sets the voxels whose bits are set in `marks` to `value`.
template <class T>
void fill_marked(T *voxels, const std::vector<uint64_t> &marks, double value)
{
    for (std::size_t w = 0; w < marks.size(); ++w)
        for (uint64_t bits = marks[w]; bits; bits &= bits - 1)
            voxels[w * 64 + static_cast<std::size_t>(std::countr_zero(bits))] = static_cast<T>(value);
}

template <class F>
void with_voxel_type(arbor_voxel_type t, F &&f)
{
    switch (t) {
    case ARBOR_VOXEL_U8: f(static_cast<uint8_t *>(nullptr)); break;
    case ARBOR_VOXEL_I8: f(static_cast<int8_t *>(nullptr)); break;
    case ARBOR_VOXEL_U16: f(static_cast<uint16_t *>(nullptr)); break;
    case ARBOR_VOXEL_I16: f(static_cast<int16_t *>(nullptr)); break;
    case ARBOR_VOXEL_U32: f(static_cast<uint32_t *>(nullptr)); break;
    case ARBOR_VOXEL_I32: f(static_cast<int32_t *>(nullptr)); break;
    default: f(static_cast<float *>(nullptr)); break;
    }
}

} // namespace

SeriesVolume::SeriesVolume(const Series &series, const StackPolicy &policy)
{
    name_ = "series " + (series.uid.empty() ? series.first().path.filename().string() : series.uid);
    if (series.grouped > 1)
        notes_.push_back("no Series Instance UID in " + std::to_string(series.grouped) +
                         " files: read as one series because they share study, series number, frame of reference, "
                         "orientation, size and pixel format");
    try {
        select_images(series);
        check_consistency();
        std::array<double, 6> orientation{};
        const std::vector<Vec3> positions = frame_positions(orientation);
        const ImageRecord &first = *images_.front();
        const auto pixel = first.frames.front().geometry.pixel_spacing.value_or(std::array<double, 2>{1, 1});
        const double single = first.frame_spacing > 0 ? first.frame_spacing : 1.0;
        stack_ = plan_slice_stack(positions, orientation, pixel, single, policy);
        for (const std::string &n : stack_.notes)
            notes_.push_back(n);
        layout_.dims = {first.columns, first.rows, static_cast<int64_t>(stack_.slices.size())};
        layout_.spacing = {pixel[1], pixel[0], stack_.spacing};
        layout_.origin = stack_.origin;
        for (int a = 0; a < 3; ++a) {
            const auto row = static_cast<std::size_t>(a) * 3;
            layout_.direction[row + 0] = orientation[static_cast<std::size_t>(a)];
            layout_.direction[row + 1] = orientation[3 + static_cast<std::size_t>(a)];
            layout_.direction[row + 2] = stack_.normal[static_cast<std::size_t>(a)];
        }
        choose_values();
    } catch (const std::runtime_error &e) {
        throw std::runtime_error(name_ + ": " + e.what());
    }
}

void SeriesVolume::select_images(const Series &series)
{
    std::vector<const ImageRecord *> localizers, others;
    std::map<std::string, std::vector<const ImageRecord *>> by_instance;
    for (const ImageRecord &r : series.images) {
        if (!r.is_image())
            others.push_back(&r);
        else if (r.is_localizer())
            localizers.push_back(&r);
        else if (r.sop_instance_uid.empty())
            images_.push_back(&r);
        else
            by_instance[r.sop_instance_uid].push_back(&r);
    }
    std::size_t repeats = 0;
    std::string repeat_example;
    for (auto &[uid, copies] : by_instance) {
        std::stable_sort(copies.begin(), copies.end(), [](const ImageRecord *a, const ImageRecord *b) {
            return transfer_syntax_rank(a->transfer_syntax_uid) < transfer_syntax_rank(b->transfer_syntax_uid);
        });
        images_.push_back(copies.front());
        repeats += copies.size() - 1;
        if (copies.size() > 1 && repeat_example.empty())
            repeat_example = copies[1]->path.filename().string() + " repeats " +
                             copies.front()->path.filename().string() + " (" +
                             copies.front()->transfer_syntax_name + ")";
    }
    std::sort(images_.begin(), images_.end(),
              [](const ImageRecord *a, const ImageRecord *b) { return a->path < b->path; });
    if (!localizers.empty())
        notes_.push_back("left out " + std::to_string(localizers.size()) +
                         " localizer image(s) (Image Type LOCALIZER), first " +
                         localizers.front()->path.filename().string());
    if (repeats > 0)
        notes_.push_back("left out " + std::to_string(repeats) +
                         " file(s) holding an instance already present (same SOP Instance UID), "
                         "keeping the best-decodable copy; e.g. " + repeat_example);
    if (!others.empty())
        notes_.push_back("left out " + std::to_string(others.size()) + " object(s) without an image, first " +
                         others.front()->path.filename().string());
    if (images_.empty())
        throw std::runtime_error("has no images with pixel data");
}

void SeriesVolume::check_consistency() const
{
    std::map<std::string, std::size_t> groups;
    for (const ImageRecord *r : images_) {
        if (r->samples_per_pixel != 1 || (r->photometric != "MONOCHROME1" && r->photometric != "MONOCHROME2"))
            throw std::runtime_error(r->path.filename().string() + " is a colour image (" +
                                     std::to_string(r->samples_per_pixel) + " samples per pixel, " +
                                     r->photometric + "); Arbor reads greyscale volumes only");
        if (!can_decode_transfer_syntax(r->transfer_syntax_uid))
            throw std::runtime_error(r->path.filename().string() + ": " +
                                     undecodable_syntax_message(r->transfer_syntax_uid));
        ++groups[agreement_key(*r)];
    }
    if (groups.size() > 1) {
        std::string kinds;
        for (const auto &[key, n] : groups)
            kinds += (kinds.empty() ? "" : "; ") + std::to_string(n) + " image(s) " + key;
        throw std::runtime_error("mixes image sizes, orientations or formats (" + kinds +
                                 "); refused, as they do not form one volume");
    }
}

std::vector<Vec3> SeriesVolume::frame_positions(std::array<double, 6> &orientation)
{
    bool complete = true;
    for (const ImageRecord *r : images_)
        for (std::size_t f = 0; f < r->frames.size(); ++f) {
            const FrameGeometry &g = r->frames[f].geometry;
            const bool needs_own = r->per_frame_positions || f == 0;
            if (!g.orientation || (needs_own && !g.position))
                complete = false;
        }
    const ImageRecord &first = *images_.front();
    if (!first.frames.front().geometry.pixel_spacing)
        notes_.push_back("no Pixel Spacing; 1 mm assumed");

    std::vector<Vec3> positions;
    if (!complete) {
        // No patient geometry: frames in instance order, 1 mm (or the given
        // spacing) apart along +z.
        std::vector<const ImageRecord *> ordered = images_;
        std::stable_sort(ordered.begin(), ordered.end(), [](const ImageRecord *a, const ImageRecord *b) {
            return a->instance_number < b->instance_number;
        });
        images_ = ordered;
        orientation = {1, 0, 0, 0, 1, 0};
        const double step = first.frame_spacing > 0 ? first.frame_spacing : 1.0;
        for (const ImageRecord *r : images_)
            for (uint32_t f = 0; f < r->frames.size(); ++f) {
                frames_.push_back({r, f});
                positions.push_back({0, 0, step * static_cast<double>(positions.size())});
            }
        notes_.push_back("no patient geometry (Image Position/Orientation (Patient) missing): "
                         "frames stacked in instance order " + number(step) +
                         " mm apart with identity orientation");
        return positions;
    }

    orientation = *first.frames.front().geometry.orientation;
    const Vec3 n = slice_normal(orientation);
    bool spaced_frames = false;
    for (const ImageRecord *r : images_) {
        for (uint32_t f = 0; f < r->frames.size(); ++f) {
            frames_.push_back({r, f});
            if (r->per_frame_positions || f == 0) {
                positions.push_back(*r->frames[f].geometry.position);
                continue;
            }
            const double step = (r->frame_spacing > 0 ? r->frame_spacing : 1.0) * f;
            Vec3 p = *r->frames[0].geometry.position;
            for (int a = 0; a < 3; ++a)
                p[static_cast<std::size_t>(a)] += step * n[static_cast<std::size_t>(a)];
            positions.push_back(p);
            spaced_frames = true;
        }
    }
    if (spaced_frames)
        notes_.push_back("multi-frame image without per-frame positions: frames placed " +
                         number(first.frame_spacing > 0 ? first.frame_spacing : 1.0) +
                         " mm apart along the slice normal (Spacing Between Slices or Slice Thickness)");
    return positions;
}

void SeriesVolume::choose_values()
{
    const ImageRecord &first = *images_.front();
    const RescaleMapping &m0 = first.frames.front().mapping;
    bool uniform = true;
    for (const FrameRef &f : frames_) {
        const ImageRecord &r = *f.image;
        uniform = uniform && r.frames[f.frame].mapping == m0 && r.bits_allocated == first.bits_allocated &&
                  r.bits_stored == first.bits_stored && r.is_signed == first.is_signed;
    }
    invert_ = first.photometric == "MONOCHROME1";
    physical_ = !uniform;
    layout_.unit = m0.unit;
    if (physical_) {
        layout_.type = ARBOR_VOXEL_F32;
        layout_.value_scale = invert_ ? -1.0 : 1.0;
        layout_.value_offset = 0.0;
        notes_.push_back("frames differ in rescale slope/intercept or pixel format: voxels hold "
                         "physical values as 32-bit floats");
    } else {
        const bool s = first.is_signed;
        layout_.type = first.bits_allocated == 8    ? (s ? ARBOR_VOXEL_I8 : ARBOR_VOXEL_U8)
                       : first.bits_allocated == 16 ? (s ? ARBOR_VOXEL_I16 : ARBOR_VOXEL_U16)
                                                    : (s ? ARBOR_VOXEL_I32 : ARBOR_VOXEL_U32);
        layout_.value_scale = invert_ ? -m0.slope : m0.slope;
        layout_.value_offset = m0.intercept;
        if (invert_) {
            const double c = first.is_signed ? -1.0 : std::ldexp(1.0, static_cast<int>(first.bits_stored)) - 1;
            layout_.value_offset = m0.slope * c + m0.intercept;
        }
    }
    if (invert_)
        notes_.push_back("MONOCHROME1: values inverted so that larger is brighter (the value mapping "
                         "is negated, so physical values keep their meaning)");
}

// Decoded frames in output units, the last two kept (a slice between two
// frames is usually followed by one that shares a frame with it).
class SeriesVolume::FrameReader {
public:
    explicit FrameReader(const SeriesVolume &v) : v_(v), plane_(static_cast<std::size_t>(v.layout_.dims[0] * v.layout_.dims[1])) {}

    const std::vector<double> &frame(std::size_t index)
    {
        for (auto &slot : slots_)
            if (slot.index == index)
                return slot.values;
        Slot &slot = slots_[next_++ % 2];
        slot.index = index;
        decode(index, slot.values);
        return slot.values;
    }

    std::size_t padded = 0; // voxels that were pixel padding

private:
    struct Slot {
        std::size_t index = static_cast<std::size_t>(-1);
        std::vector<double> values;
    };

    const DecodedImage &image(const ImageRecord *r)
    {
        if (image_of_ != r) {
            decoded_.reset();
            decoded_ = std::make_unique<DecodedImage>(*r);
            image_of_ = r;
        }
        return *decoded_;
    }

    void decode(std::size_t index, std::vector<double> &out)
    {
        const FrameRef &ref = v_.frames_[index];
        const ImageRecord &r = *ref.image;
        // Without tilt the frame is decoded straight into its slot.
        const bool tilted = !v_.stack_.frame_offsets.empty();
        std::vector<double> &values = tilted ? raw_ : out;
        values.resize(plane_);
        image(&r).stored_values(ref.frame, values.data());
        const RescaleMapping &m = r.frames[ref.frame].mapping;
        double pad_lo = 1, pad_hi = 0;
        if (r.padding_value) {
            pad_lo = pad_hi = static_cast<double>(*r.padding_value);
            if (r.padding_range_limit) {
                pad_lo = std::min(pad_lo, static_cast<double>(*r.padding_range_limit));
                pad_hi = std::max(pad_hi, static_cast<double>(*r.padding_range_limit));
            }
        }
        const double c = r.is_signed ? -1.0 : std::ldexp(1.0, static_cast<int>(r.bits_stored)) - 1;
        for (std::size_t i = 0; i < plane_; ++i) {
            const double s = values[i];
            if (s >= pad_lo && s <= pad_hi) {
                values[i] = kNaN;
                ++padded;
            } else if (v_.physical_) {
                values[i] = (v_.invert_ ? -1.0 : 1.0) * (s * m.slope + m.intercept);
            } else {
                values[i] = v_.invert_ ? c - s : s;
            }
        }
        if (tilted) {
            out.resize(plane_);
            shift(index, out);
        }
    }

    // Undo a gantry tilt: sample the frame at its in-plane offset.
    void shift(std::size_t index, std::vector<double> &out) const
    {
        const auto nx = static_cast<std::size_t>(v_.layout_.dims[0]);
        const auto ny = static_cast<std::size_t>(v_.layout_.dims[1]);
        const double dx = v_.stack_.frame_offsets[index][0] / v_.layout_.spacing[0];
        const double dy = v_.stack_.frame_offsets[index][1] / v_.layout_.spacing[1];
        for (std::size_t j = 0; j < ny; ++j)
            for (std::size_t i = 0; i < nx; ++i) {
                const double x = static_cast<double>(i) - dx, y = static_cast<double>(j) - dy;
                const double fx = std::floor(x), fy = std::floor(y);
                const double tx = x - fx, ty = y - fy;
                double sum = 0.0;
                bool outside = false;
                for (int b = 0; b < 2 && !outside; ++b)
                    for (int a = 0; a < 2; ++a) {
                        const double w = (a ? tx : 1 - tx) * (b ? ty : 1 - ty);
                        if (w < 1e-9)
                            continue;
                        const double xi = fx + a, yi = fy + b;
                        if (xi < 0 || yi < 0 || xi > static_cast<double>(nx - 1) || yi > static_cast<double>(ny - 1)) {
                            outside = true;
                            break;
                        }
                        sum += w * raw_[static_cast<std::size_t>(yi) * nx + static_cast<std::size_t>(xi)];
                    }
                out[j * nx + i] = outside ? kNaN : sum; // NaN neighbours stay NaN
            }
    }

    const SeriesVolume &v_;
    std::size_t plane_;
    std::vector<double> raw_;
    Slot slots_[2];
    unsigned next_ = 0;
    const ImageRecord *image_of_ = nullptr;
    std::unique_ptr<DecodedImage> decoded_;
};

std::vector<std::string> SeriesVolume::read(void *voxels, const ScanProgress &progress) const
{
    FrameReader reader(*this);
    const auto plane = static_cast<std::size_t>(layout_.dims[0] * layout_.dims[1]);
    const std::size_t slices = stack_.slices.size();
    // Voxels with no measured value (padding, outside a tilted scan): only
    // possible when a frame declares padding or slices are shifted.
    bool may_lack_values = !stack_.frame_offsets.empty();
    for (const ImageRecord *r : images_)
        may_lack_values = may_lack_values || r->padding_value.has_value();
    std::vector<uint64_t> marks(may_lack_values ? (plane * slices + 63) / 64 : 0, 0); // one bit a voxel
    std::vector<double> blend; // allocated at the first interpolated slice
    double lowest = std::numeric_limits<double>::infinity();
    const auto range = type_range(layout_.type);
    std::size_t unfilled = 0;
    for (std::size_t k = 0; k < slices; ++k) {
        if (progress)
            progress(static_cast<double>(k) / static_cast<double>(slices));
        const SliceSource &src = stack_.slices[k];
        const double *values = reader.frame(src.a).data();
        if (src.t > 0) {
            blend.assign(values, values + plane);
            const std::vector<double> &b = reader.frame(src.b);
            for (std::size_t i = 0; i < plane; ++i)
                blend[i] = (1 - src.t) * blend[i] + src.t * b[i];
            values = blend.data();
        }
        uint64_t *marks_or_null = may_lack_values ? marks.data() : nullptr;
        with_voxel_type(layout_.type, [&](auto *tag) {
            using T = std::remove_pointer_t<decltype(tag)>;
            unfilled += store_slice(values, plane, static_cast<T *>(voxels) + k * plane,
                                    static_cast<double>(range[0]), static_cast<double>(range[1]),
                                    marks_or_null, k * plane, lowest);
        });
    }
    std::vector<std::string> notes;
    if (unfilled > 0) {
        const double fill = std::isfinite(lowest) ? (physical_ ? lowest : std::round(lowest)) : 0.0;
        with_voxel_type(layout_.type, [&](auto *tag) {
            using T = std::remove_pointer_t<decltype(tag)>;
            fill_marked(static_cast<T *>(voxels), marks, fill);
        });
        const ImageRecord &first = *images_.front();
        std::string what = std::to_string(unfilled) + " voxel(s) without a measured value (";
        if (reader.padded > 0 && first.padding_value)
            what += "Pixel Padding Value " + std::to_string(*first.padding_value);
        if (!stack_.frame_offsets.empty())
            what += std::string(reader.padded > 0 ? ", " : "") + "outside the tilted scan";
        notes.push_back(what + ") set to the lowest measured value, " + number(fill) +
                        " stored, so they add no structures to the contour tree");
    }
    if (progress)
        progress(1.0);
    return notes;
}

} // namespace arbor::dicom
