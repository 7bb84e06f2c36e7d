// job_panel.hpp - the background jobs (import, filter, contour tree, ...):
// a progress bar per running stage with its activity and a Cancel button,
// Cancel all (then Resume), and the latest messages.  The UI never waits on a job: it draws from the
// jobs' snapshots every frame.
#pragma once

namespace arbor::workstation {

class Workstation;

class JobPanel {
public:
    void draw(Workstation &workstation);
};

} // namespace arbor::workstation
