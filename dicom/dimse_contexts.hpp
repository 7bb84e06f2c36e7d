// dimse_contexts.hpp - the presentation contexts Arbor proposes (C-GET, as
// storage SCP within the association) and accepts (its C-MOVE storage SCP),
// and the words for a retrieve's final status.
//
// The archive should send what it holds, not transcode it (Orthanc cannot
// encode or decode JPEG 2000 itself), so for the image classes of volumes
// each compression family gets a context of its own: the archive finds one
// matching each stored instance.  Other storage classes are proposed
// uncompressed, as many as fit in the 128 contexts of an association.
#pragma once

#include "dicom/pacs_node.hpp"

#include <dcmtk/dcmnet/scp.h>
#include <dcmtk/dcmnet/scu.h>

#include <string>
#include <vector>

namespace arbor::dicom {

struct RetrieveCounts {
    Uint16 status = 0;
    int remaining = 0, completed = 0, failed = 0, warning = 0;
};

// Requestor side (C-GET): one context per (image class, syntax family) and
// one per other storage class, in `role`; `reserved` contexts stay free.
void add_storage_contexts(DcmSCU &scu, T_ASC_SC_ROLE role, int reserved = 4);
// Acceptor side (C-MOVE's storage SCP): every storage class, every syntax we read.
void add_storage_contexts(DcmSCP &scp);

// "the archive could not send 3 of 120 images (C-GET status 0xB000: ...)".
std::string describe_retrieve_status(const PacsNode &node, const char *what, const RetrieveCounts &counts,
                                     int stored_failures);

} // namespace arbor::dicom
