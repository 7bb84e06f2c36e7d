#include "dimse_contexts.hpp"

#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmnet/diutil.h>

#include <algorithm>
#include <cstdio>
#include <set>

namespace arbor::dicom {

namespace {

// The classes volumes come in.
const char *const kVolumeClasses[] = {
    UID_CTImageStorage,
    UID_MRImageStorage,
    UID_EnhancedCTImageStorage,
    UID_EnhancedMRImageStorage,
    UID_LegacyConvertedEnhancedCTImageStorage,
    UID_LegacyConvertedEnhancedMRImageStorage,
    UID_PositronEmissionTomographyImageStorage,
    UID_NuclearMedicineImageStorage,
    UID_SecondaryCaptureImageStorage,
    UID_MultiframeGrayscaleWordSecondaryCaptureImageStorage,
    UID_MultiframeGrayscaleByteSecondaryCaptureImageStorage,
    UID_RTDoseStorage,
    UID_XRayAngiographicImageStorage,
};

// Syntax families: each one context per volume class.
const std::vector<std::vector<const char *>> kFamilies = {
    {UID_LittleEndianExplicitTransferSyntax, UID_LittleEndianImplicitTransferSyntax},
    {UID_JPEG2000LosslessOnlyTransferSyntax, UID_JPEG2000TransferSyntax},
    {UID_JPEGProcess14SV1TransferSyntax, UID_JPEGProcess14TransferSyntax},
    {UID_JPEGProcess1TransferSyntax, UID_JPEGProcess2_4TransferSyntax},
    {UID_JPEGLSLosslessTransferSyntax, UID_JPEGLSLossyTransferSyntax},
    {UID_RLELosslessTransferSyntax},
    {UID_DeflatedExplicitVRLittleEndianTransferSyntax},
};

OFList<OFString> list_of(const std::vector<const char *> &uids)
{
    OFList<OFString> out;
    for (const char *u : uids)
        out.push_back(u);
    return out;
}

} // namespace

void add_storage_contexts(DcmSCU &scu, T_ASC_SC_ROLE role, int reserved)
{
    int left = 128 - reserved;
    std::set<std::string> done;
    for (const char *sop : kVolumeClasses) {
        for (const auto &family : kFamilies)
            if (left-- > 0)
                scu.addPresentationContext(sop, list_of(family), role);
        done.insert(sop);
    }
    for (int i = 0; i < numberOfDcmLongSCUStorageSOPClassUIDs && left > 0; ++i)
        if (done.insert(dcmLongSCUStorageSOPClassUIDs[i]).second) {
            scu.addPresentationContext(dcmLongSCUStorageSOPClassUIDs[i], list_of(kFamilies.front()), role);
            --left;
        }
}

void add_storage_contexts(DcmSCP &scp)
{
    std::vector<const char *> all;
    for (const auto &family : kFamilies)
        all.insert(all.end(), family.begin(), family.end());
    const OFList<OFString> syntaxes = list_of(all);
    for (int i = 0; i < numberOfDcmAllStorageSOPClassUIDs; ++i)
        scp.addPresentationContext(dcmAllStorageSOPClassUIDs[i], syntaxes);
}

std::string describe_retrieve_status(const PacsNode &node, const char *what, const RetrieveCounts &n,
                                     int stored_failures)
{
    char code[16];
    std::snprintf(code, sizeof code, "0x%04X", n.status);
    std::string meaning;
    switch (n.status) {
    case 0xA801: meaning = "the archive does not know the move destination " + node.our_aet +
                           ": add it to the archive's modalities with this machine's address and port " +
                           std::to_string(node.our_port); break;
    case 0xA701: case 0xA702: meaning = "the archive is out of resources"; break;
    case 0xA900: meaning = "the request does not match the archive's query model"; break;
    case 0xFE00: meaning = "the archive cancelled the retrieve"; break;
    case 0xB000: meaning = "some sub-operations failed"; break;
    case 0x0000: meaning = "success reported"; break;
    default: meaning = (n.status & 0xF000) == 0xC000 ? "the archive could not process the request" : "failure";
    }
    if (std::string(what) == "C-MOVE" && (n.status & 0xF000) == 0xC000)
        meaning += "; for C-MOVE this is often the archive failing to connect to " + node.our_aet +
                   ": check the address and port it has for that AE title (we listen on " +
                   std::to_string(node.our_port) + ")";
    std::string text = node.describe() + ": " + what + " ended with status " + code + " (" + meaning + ")";
    if (n.failed > 0)
        text += "; the archive failed to send " + std::to_string(n.failed) + " image(s)";
    if (stored_failures > 0)
        text += "; " + std::to_string(stored_failures) + " image(s) that arrived could not be kept";
    return text;
}

} // namespace arbor::dicom
