// reader_watch.hpp - observes one VTK reader for the length of a host call:
// its error and warning events go to the call's VtkMessageRoute, its progress
// goes to the host task, and a cancellation request from the host stops it.
#pragma once

#include "vtk_message_route.hpp"

#include <arbor/sdk/task.hpp>

#include <vtkSmartPointer.h>

#include <string>

class vtkAlgorithm;
class vtkCommand;

namespace arbor::importer_vtk {

class ReaderWatch {
public:
    // Reader progress [0, 1] is reported as [progress_from, progress_to].
    ReaderWatch(vtkAlgorithm &reader, VtkMessageRoute &route, const sdk::Task &task,
                double progress_from = 0.0, double progress_to = 1.0);
    ~ReaderWatch();
    ReaderWatch(const ReaderWatch &) = delete;
    ReaderWatch &operator=(const ReaderWatch &) = delete;

    // Throws ARBOR_ERROR_CANCELLED when the host asked to stop during the
    // read (VTK readers that honour AbortExecute return partial data as if
    // nothing happened), then `status` with "`what`: <VTK's reason>" when VTK
    // reported an error (or, with warnings_fail, a warning).
    void throw_if_failed(arbor_status status, const std::string &what,
                         bool warnings_fail = false) const;

    bool cancelled() const { return cancelled_; }

private:
    class Observer;
    void on_progress(double fraction);

    vtkAlgorithm &reader_;
    VtkMessageRoute &route_;
    const sdk::Task &task_;
    double from_, to_;
    bool cancelled_ = false;
    vtkSmartPointer<vtkCommand> observer_;
    unsigned long tags_[3] = {0, 0, 0};
};

} // namespace arbor::importer_vtk
