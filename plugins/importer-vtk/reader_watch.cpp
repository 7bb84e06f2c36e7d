// reader_watch.cpp - VTK observers bridging a reader to the host: messages,
// progress and cancellation.
#include "reader_watch.hpp"

#include <arbor/sdk/error.hpp>

#include <vtkAlgorithm.h>
#include <vtkCommand.h>

namespace arbor::importer_vtk {

class ReaderWatch::Observer : public vtkCommand {
public:
    static Observer *New() { return new Observer; }
    ReaderWatch *watch = nullptr;

    void Execute(vtkObject *, unsigned long event, void *data) override
    {
        if (!watch)
            return;
        switch (event) {
        case vtkCommand::ErrorEvent:
            watch->route_.record(VtkMessageRoute::Severity::error, static_cast<const char *>(data));
            break;
        case vtkCommand::WarningEvent:
            watch->route_.record(VtkMessageRoute::Severity::warning,
                                 static_cast<const char *>(data));
            break;
        case vtkCommand::ProgressEvent:
            if (data)
                watch->on_progress(*static_cast<const double *>(data));
            break;
        default:
            break;
        }
    }
};

ReaderWatch::ReaderWatch(vtkAlgorithm &reader, VtkMessageRoute &route, const sdk::Task &task,
                         double progress_from, double progress_to)
    : reader_(reader), route_(route), task_(task), from_(progress_from), to_(progress_to)
{
    vtkSmartPointer<Observer> observer = vtkSmartPointer<Observer>::Take(Observer::New());
    observer->watch = this;
    observer_ = observer;
    tags_[0] = reader_.AddObserver(vtkCommand::ErrorEvent, observer_);
    tags_[1] = reader_.AddObserver(vtkCommand::WarningEvent, observer_);
    tags_[2] = reader_.AddObserver(vtkCommand::ProgressEvent, observer_);
}

ReaderWatch::~ReaderWatch()
{
    for (unsigned long tag : tags_)
        reader_.RemoveObserver(tag);
    static_cast<Observer *>(observer_.Get())->watch = nullptr;
}

void ReaderWatch::on_progress(double fraction)
{
    if (cancelled_)
        return;
    // Runs inside VTK's read loop: no exception may unwind through it, so a
    // cancellation becomes VTK's abort flag and is reported after the read.
    try {
        task_.progress(from_ + (to_ - from_) * fraction);
    } catch (const sdk::Error &) {
        cancelled_ = true;
        reader_.AbortExecuteOn();
    }
}

void ReaderWatch::throw_if_failed(arbor_status status, const std::string &what,
                                  bool warnings_fail) const
{
    if (cancelled_ || task_.cancelled())
        sdk::fail(ARBOR_ERROR_CANCELLED, what + ": cancelled");
    if (route_.has_errors() || (warnings_fail && route_.has_warnings()))
        sdk::fail(status, what + ": " + route_.reason(warnings_fail));
}

} // namespace arbor::importer_vtk
