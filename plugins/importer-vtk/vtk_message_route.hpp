// vtk_message_route.hpp - where VTK's messages go while one of our host calls
// runs.
//
// VTK readers do not throw: they print errors and warnings through the
// process-wide vtkOutputWindow and vtkLogger and carry on.  While a
// VtkMessageRoute exists, our output window takes that text for the calling
// thread, passes every message to the host log at debug level and keeps the
// errors and warnings so the importer can explain a failure.  Nothing is
// printed to the terminal.
#pragma once

#include <arbor/sdk/instance.hpp>

#include <string>
#include <vector>

namespace arbor::importer_vtk {

class VtkMessageRoute {
public:
    enum class Severity { text, warning, error };

    explicit VtkMessageRoute(const sdk::Instance &instance);
    ~VtkMessageRoute();
    VtkMessageRoute(const VtkMessageRoute &) = delete;
    VtkMessageRoute &operator=(const VtkMessageRoute &) = delete;

    // One message as VTK formats it ("ERROR: In file.cxx, line 12\n
    // vtkSomething (0x...): what went wrong\n\n").
    void record(Severity severity, const char *text);

    bool has_errors() const { return !errors_.empty() || !pipeline_errors_.empty(); }
    bool has_warnings() const { return !warnings_.empty(); }

    // The errors (or, when asked, the warnings) as one sentence fragment
    // for an error message; the executive's generic "algorithm returned
    // failure" only when nothing more specific was said.  "" when none.
    std::string reason(bool include_warnings = false) const;

    // The route of the calling thread, nullptr outside our calls.
    static VtkMessageRoute *current();

private:
    const sdk::Instance &instance_;
    VtkMessageRoute *outer_;
    std::vector<std::string> errors_;
    std::vector<std::string> pipeline_errors_;
    std::vector<std::string> warnings_;
};

} // namespace arbor::importer_vtk
