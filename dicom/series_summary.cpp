#include "series_summary.hpp"

namespace arbor::dicom {

SeriesSummary summarise_series(const Series &s)
{
    SeriesSummary out{&s, std::nullopt, {}, {}};
    if (s.frame_count() == 0) {
        out.refusal = "no images (" + (s.first().modality.empty() ? std::string("no modality") : s.first().modality) +
                      " object)";
        return out;
    }
    try {
        const SeriesVolume v(s, StackPolicy{});
        out.layout = v.layout();
        out.notes = v.notes();
    } catch (const std::runtime_error &e) {
        out.refusal = e.what();
    }
    return out;
}

} // namespace arbor::dicom
