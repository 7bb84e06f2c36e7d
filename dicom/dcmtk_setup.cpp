#include "dcmtk_setup.hpp"

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcrledrg.h>
#include <dcmtk/dcmdata/dcvr.h>
#include <dcmtk/dcmjpeg/djdecode.h>
#include <dcmtk/dcmjpls/djdecode.h>
#include <dcmtk/oflog/oflog.h>

#include <mutex>

namespace arbor::dicom {

void ensure_dcmtk_ready()
{
    static std::once_flag once;
    std::call_once(once, [] {
        OFLog::configure(OFLogger::OFF_LOG_LEVEL);
        // Elements written with VR UN get their dictionary VR, so e.g. an
        // Image Position (Patient) stored as UN still reads as 3 numbers.
        dcmEnableUnknownVRConversion.set(OFTrue);
        DJDecoderRegistration::registerCodecs();   // JPEG baseline, extended, lossless
        DJLSDecoderRegistration::registerCodecs(); // JPEG-LS lossless and near-lossless
        DcmRLEDecoderRegistration::registerCodecs();
        // Deflated Explicit VR Little Endian is read by dcmdata itself (zlib).
    });
}

} // namespace arbor::dicom
