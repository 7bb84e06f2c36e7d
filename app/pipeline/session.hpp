// session.hpp - a Document as a file: "arbor-session/1", JSON.
//
// It holds everything an image depends on: the input (a path, the importer
// with its parameters - the DICOM series UID among them - or the phantom's
// recipe), the filter chain, every plugin's id, version and all its
// parameter values, the cut, the relationship depicted and the selected
// branch, the camera, image size, background and renderer.  Parameter values
// are written with the types their descriptions give (numbers, lists,
// booleans, choice ids), so a third party's plugin is saved and restored
// without code of ours.  Paths are stored relative to the session file's
// folder when both lie under the same top-level folder.
//
// Reading checks everything before a pipeline sees it and names the file
// and the problem: not JSON, not a session, a newer format version, a plugin
// that is not installed, a parameter out of its range, a missing input.
// A plugin whose installed version differs from the saved one, or a
// parameter the installed version no longer has, is a warning.
#pragma once

#include "document.hpp"
#include "plugin_catalog.hpp"

#include <filesystem>
#include <stdexcept>
#include <optional>
#include <string>
#include <vector>

namespace arbor::pipeline {

inline constexpr const char *kSessionFormat = "arbor-session/1";

class SessionError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// The session text of a resolved document; relative paths are made against
// `folder` (the session file's).
// The plugin isolation a session was saved with (its "plugins" object):
// read before the plugins load, so that a session runs its plugins as it
// did.  nullopt for a file without one (or not a session).
struct SessionIsolation {
    std::string mode;           // "all", "third-party", "none"; "" when absent
    double timeout_seconds = 0; // 0 when absent
};
std::optional<SessionIsolation> session_isolation(const std::filesystem::path &path);

std::string session_text(const Document &document, const PluginCatalog &catalog, const std::filesystem::path &folder);

// Writes the session atomically (an existing file survives a failed write).
void write_session(const std::filesystem::path &path, const Document &document, const PluginCatalog &catalog);

struct SessionRead {
    Document document;                 // resolved: full ids, every parameter
    std::vector<std::string> warnings; // plugin versions that differ, parameters ignored
};

// Throws SessionError.  With `require_input`, an input path that does not
// exist is refused (a front that overrides the input passes false).
SessionRead read_session(const std::filesystem::path &path, const PluginCatalog &catalog,
                         bool require_input = true);
SessionRead parse_session(const std::string &text, const std::filesystem::path &folder, const std::string &name,
                          const PluginCatalog &catalog, bool require_input = true);

} // namespace arbor::pipeline
