// vtk_message_route.cpp - the output window that hands VTK's text to the
// route of the calling thread, installed only while one of our calls runs.
#include "vtk_message_route.hpp"

#include <vtkLogger.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>

#include <algorithm>
#include <mutex>

namespace arbor::importer_vtk {

namespace {

thread_local VtkMessageRoute *t_route = nullptr;

class RoutedOutputWindow : public vtkOutputWindow {
public:
    static RoutedOutputWindow *New();
    vtkTypeMacro(RoutedOutputWindow, vtkOutputWindow);

    void DisplayText(const char *text) override { route(VtkMessageRoute::Severity::text, text); }
    void DisplayErrorText(const char *text) override
    {
        route(VtkMessageRoute::Severity::error, text);
    }
    void DisplayWarningText(const char *text) override
    {
        route(VtkMessageRoute::Severity::warning, text);
    }
    void DisplayGenericWarningText(const char *text) override
    {
        route(VtkMessageRoute::Severity::warning, text);
    }
    void DisplayDebugText(const char *text) override
    {
        route(VtkMessageRoute::Severity::text, text);
    }

protected:
    RoutedOutputWindow() = default;
    ~RoutedOutputWindow() override = default;

private:
    // Text from threads that are not inside one of our calls (another VTK
    // user in the process) is dropped rather than printed.
    static void route(VtkMessageRoute::Severity severity, const char *text)
    {
        if (VtkMessageRoute *r = VtkMessageRoute::current())
            r->record(severity, text);
    }
};

vtkStandardNewMacro(RoutedOutputWindow);

// The output window and the logger are process-wide: the first of our calls
// to start installs the routing, the last to finish puts back what was there,
// so nothing of ours stays referenced by VTK once this library is unloaded.
std::mutex g_install_mutex;
int g_active_calls = 0;
vtkOutputWindow *g_saved_window = nullptr;
vtkLogger::Verbosity g_saved_stderr_verbosity = vtkLogger::VERBOSITY_INFO;

void install_routing()
{
    std::lock_guard lock(g_install_mutex);
    if (g_active_calls++ > 0)
        return;
    g_saved_window = vtkOutputWindow::GetInstance();
    g_saved_window->Register(nullptr);
    RoutedOutputWindow *window = RoutedOutputWindow::New();
    vtkOutputWindow::SetInstance(window);
    window->Delete();
    // vtkLogger writes every unobserved error to stderr on its own, beside
    // the output window.  It has no getter for the stderr level; with no log
    // file or callback registered the cutoff equals it.
    g_saved_stderr_verbosity = vtkLogger::GetCurrentVerbosityCutoff();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
}

void remove_routing()
{
    std::lock_guard lock(g_install_mutex);
    if (--g_active_calls > 0)
        return;
    vtkLogger::SetStderrVerbosity(g_saved_stderr_verbosity);
    vtkOutputWindow::SetInstance(g_saved_window);
    g_saved_window->UnRegister(nullptr);
    g_saved_window = nullptr;
}

// "ERROR: In /src/vtkXMLParser.cxx, line 375\nvtkXMLDataParser (0x55d0): Error
// parsing XML ...\n\n" -> "Error parsing XML ..."; `source` gets the class.
std::string plain_text(const char *text, std::string &source)
{
    std::string s = text ? text : "";
    for (const char *lead : {"ERROR: In ", "Warning: In ", "Generic Warning: In ", "Debug: In "}) {
        if (s.rfind(lead, 0) == 0) {
            const std::size_t eol = s.find('\n');
            s.erase(0, eol == std::string::npos ? s.size() : eol + 1);
            break;
        }
    }
    // The executive appends a dump of the pipeline request; the first line
    // says all there is to say.
    if (const std::size_t eol = s.find('\n'); eol != std::string::npos)
        s.erase(eol);
    const std::size_t mark = s.find(" (0x");
    const std::size_t colon = s.find("): ");
    if (mark != std::string::npos && colon != std::string::npos && mark < colon &&
        s.find(' ') == mark) {
        source = s.substr(0, mark);
        s.erase(0, colon + 3);
    }
    while (!s.empty() && (s.back() == ' ' || s.back() == '\r' || s.back() == '\t'))
        s.pop_back();
    return s;
}

bool is_pipeline_class(const std::string &source)
{
    return source.find("Pipeline") != std::string::npos ||
           source.find("Executive") != std::string::npos;
}

void add_once(std::vector<std::string> &list, std::string text)
{
    if (!text.empty() && std::find(list.begin(), list.end(), text) == list.end())
        list.push_back(std::move(text));
}

std::string joined(const std::vector<std::string> &parts)
{
    // A reader in trouble tends to repeat itself; the first few say it.
    constexpr std::size_t kMaxParts = 3;
    std::string out;
    for (std::size_t i = 0; i < parts.size() && i < kMaxParts; ++i)
        out += (i ? "; " : "") + parts[i];
    return out;
}

} // namespace

VtkMessageRoute::VtkMessageRoute(const sdk::Instance &instance)
    : instance_(instance), outer_(t_route)
{
    install_routing();
    t_route = this;
}

VtkMessageRoute::~VtkMessageRoute()
{
    t_route = outer_;
    remove_routing();
}

VtkMessageRoute *VtkMessageRoute::current()
{
    return t_route;
}

void VtkMessageRoute::record(Severity severity, const char *text)
{
    std::string source;
    std::string message = plain_text(text, source);
    if (message.empty())
        return;
    const char *label = severity == Severity::error     ? "VTK error: "
                        : severity == Severity::warning ? "VTK warning: "
                                                        : "VTK: ";
    instance_.log(ARBOR_LOG_DEBUG, label + (source.empty() ? "" : source + ": ") + message);
    if (severity == Severity::error)
        add_once(is_pipeline_class(source) ? pipeline_errors_ : errors_, std::move(message));
    else if (severity == Severity::warning)
        add_once(warnings_, std::move(message));
}

std::string VtkMessageRoute::reason(bool include_warnings) const
{
    std::vector<std::string> parts = errors_;
    if (include_warnings)
        for (const std::string &w : warnings_)
            add_once(parts, w);
    if (parts.empty())
        parts = pipeline_errors_;
    return joined(parts);
}

} // namespace arbor::importer_vtk
