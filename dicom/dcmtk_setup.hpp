// dcmtk_setup.hpp - process-wide DCMTK set-up, done once: its own logging
// is silenced (Arbor reports every problem itself, with the file named) and
// the decoders for compressed transfer syntaxes are registered.
#pragma once

namespace arbor::dicom {

// Safe to call from any thread, any number of times.
void ensure_dcmtk_ready();

} // namespace arbor::dicom
