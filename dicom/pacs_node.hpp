// pacs_node.hpp - an archive Arbor talks to: a DICOM node (AE title, host,
// port; our AE title and, for C-MOVE, our storage port) or a DICOMweb
// service (base URL, HTTP basic or bearer authentication).  Nodes are named
// in a JSON file in the user's config folder, or given inline wherever a
// node name goes: `AET@host:port` or an http(s) URL.
//
// Secrets (passwords, tokens) live only in PacsNode::secret; describe() and
// every message built from a node leave them out.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace arbor::dicom {

struct PacsSecret {
    std::string user, password; // HTTP basic when user is set
    std::string token;          // HTTP bearer
    // Where the file said to read them from (kept when the file is rewritten).
    std::string password_env, token_env;
};

struct PacsNode {
    enum class Kind { Dimse, DicomWeb };
    std::string name; // empty for an inline node
    Kind kind = Kind::Dimse;
    // DIMSE
    std::string aet, host;
    uint16_t port = 0;
    std::string our_aet = "ARBOR";
    uint16_t our_port = 0; // where our storage SCP listens for C-MOVE; 0: not set
    // DICOMweb: the service root, e.g. http://host:8042/dicom-web (no trailing slash)
    std::string url;
    PacsSecret secret;

    // "ORTHANC@pacs.example:4242" or the URL; never a secret.
    std::string describe() const;
    // "basic (user arbor)", "bearer token", "none": what `arbor pacs nodes` shows.
    std::string authentication() const;
    // A folder name for this node's retrieved series: its name, or the inline
    // form made safe for a file name.
    std::string cache_key() const;
};

// `AET@host:port`, `http(s)://...`; an inline URL takes its credentials from
// ARBOR_PACS_USER and ARBOR_PACS_PASSWORD, or ARBOR_PACS_TOKEN.  Throws std::invalid_argument saying what is wrong.
PacsNode parse_inline_node(const std::string &text);
bool looks_inline(const std::string &text);

// ARBOR_CONFIG_DIR, else $XDG_CONFIG_HOME/arbor, else ~/.config/arbor; the
// file is pacs-nodes.json there.
std::filesystem::path default_nodes_file();

// The nodes of an `arbor-pacs-nodes/1` file (none when it does not exist).
// Passwords and tokens may be given directly ("password", "token") or by the
// name of an environment variable that holds them ("password_env",
// "token_env").  Throws std::runtime_error naming the file and the entry.
std::vector<PacsNode> read_nodes(const std::filesystem::path &file);
// Writes the file atomically; secrets given by variable stay variables.
void write_nodes(const std::filesystem::path &file, const std::vector<PacsNode> &nodes);

// A name from the list, or an inline node.  Throws std::invalid_argument
// listing the configured names when `text` is neither.
PacsNode find_node(const std::string &text, const std::vector<PacsNode> &nodes);

} // namespace arbor::dicom
