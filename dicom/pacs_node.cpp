#include "pacs_node.hpp"

#include "core/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <cctype>
#include <cstdlib>
#include <fstream>
#include <stdexcept>

namespace arbor::dicom {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

const char *environment(const char *name)
{
    const char *v = std::getenv(name);
    return v && *v ? v : nullptr;
}

bool is_url(const std::string &text)
{
    return text.rfind("http://", 0) == 0 || text.rfind("https://", 0) == 0;
}

uint16_t port_number(const std::string &text, const std::string &where)
{
    if (text.empty() || text.size() > 5 || text.find_first_not_of("0123456789") != std::string::npos)
        throw std::invalid_argument(where + ": the port must be a number from 1 to 65535, not '" + text + "'");
    const long v = std::strtol(text.c_str(), nullptr, 10);
    if (v < 1 || v > 65535)
        throw std::invalid_argument(where + ": the port must be a number from 1 to 65535, not '" + text + "'");
    return static_cast<uint16_t>(v);
}

// AE titles: 1-16 characters of the default repertoire, no backslash or control characters.
std::string ae_title(const std::string &text, const std::string &where)
{
    if (text.empty() || text.size() > 16)
        throw std::invalid_argument(where + ": an AE title has 1 to 16 characters, not '" + text + "'");
    for (char c : text)
        if (c < 0x20 || c > 0x7e || c == '\\')
            throw std::invalid_argument(where + ": the AE title '" + text + "' has a character DICOM does not allow");
    if (text.find_first_not_of(' ') == std::string::npos)
        throw std::invalid_argument(where + ": the AE title is all spaces");
    return text;
}

// Removes a trailing slash; refuses credentials written into the URL
// (they would end up in logs and sessions).
std::string service_url(std::string url, const std::string &where)
{
    const std::size_t scheme = url.find("://");
    const std::size_t host_end = url.find('/', scheme + 3);
    const std::size_t at = url.find('@', scheme + 3);
    if (at != std::string::npos && (host_end == std::string::npos || at < host_end))
        throw std::invalid_argument(where + ": put the user and password in the node file (or ARBOR_PACS_USER and "
                                            "ARBOR_PACS_PASSWORD), not in the URL");
    if (scheme == std::string::npos || url.size() <= scheme + 3)
        throw std::invalid_argument(where + ": '" + url + "' is not a URL");
    while (!url.empty() && url.back() == '/')
        url.pop_back();
    return url;
}

std::string text_member(const json &j, const char *key, const std::string &where, bool required)
{
    if (!j.contains(key)) {
        if (required)
            throw std::runtime_error(where + " needs \"" + key + "\"");
        return {};
    }
    if (!j.at(key).is_string())
        throw std::runtime_error(where + ": \"" + key + "\" must be a string");
    return j.at(key).get<std::string>();
}

uint16_t port_member(const json &j, const char *key, const std::string &where, bool required)
{
    if (!j.contains(key)) {
        if (required)
            throw std::runtime_error(where + " needs \"" + key + "\"");
        return 0;
    }
    const json &v = j.at(key);
    if (!v.is_number_integer() || v.get<int64_t>() < 1 || v.get<int64_t>() > 65535)
        throw std::runtime_error(where + ": \"" + key + "\" must be a port number from 1 to 65535");
    return static_cast<uint16_t>(v.get<int64_t>());
}

std::string secret_from(const json &j, const char *key, const char *env_key, std::string &env_name,
                        const std::string &where)
{
    env_name = text_member(j, env_key, where, false);
    if (!env_name.empty()) {
        const char *v = environment(env_name.c_str());
        if (!v)
            throw std::runtime_error(where + ": the environment variable " + env_name + " (\"" + env_key +
                                     "\") is not set");
        return v;
    }
    return text_member(j, key, where, false);
}

} // namespace

std::string PacsNode::describe() const
{
    if (kind == Kind::DicomWeb)
        return url;
    return aet + "@" + host + ":" + std::to_string(port);
}

std::string PacsNode::authentication() const
{
    if (kind == Kind::Dimse)
        return "none (DICOM: by AE title)";
    if (!secret.token.empty())
        return "bearer token";
    if (!secret.user.empty())
        return "basic (user " + secret.user + ")";
    return "none";
}

std::string PacsNode::cache_key() const
{
    std::string key = name.empty() ? describe() : name;
    for (char &c : key)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-' || c == '_' || c == '@'))
            c = '_';
    return key;
}

bool looks_inline(const std::string &text)
{
    return is_url(text) || text.find('@') != std::string::npos;
}

PacsNode parse_inline_node(const std::string &text)
{
    PacsNode n;
    if (is_url(text)) {
        n.kind = PacsNode::Kind::DicomWeb;
        n.url = service_url(text, text);
        if (const char *token = environment("ARBOR_PACS_TOKEN"))
            n.secret.token = token;
        if (const char *user = environment("ARBOR_PACS_USER")) {
            n.secret.user = user;
            if (const char *password = environment("ARBOR_PACS_PASSWORD"))
                n.secret.password = password;
        }
        return n;
    }
    const std::size_t at = text.find('@');
    const std::size_t colon = text.rfind(':');
    if (at == std::string::npos || colon == std::string::npos || colon < at)
        throw std::invalid_argument("'" + text + "' is not a node: give a configured name, AET@host:port or a "
                                                 "DICOMweb URL");
    n.aet = ae_title(text.substr(0, at), text);
    n.host = text.substr(at + 1, colon - at - 1);
    if (n.host.empty())
        throw std::invalid_argument(text + ": no host between '@' and ':'");
    n.port = port_number(text.substr(colon + 1), text);
    return n;
}

fs::path default_nodes_file()
{
    if (const char *dir = environment("ARBOR_CONFIG_DIR"))
        return fs::path(dir) / "pacs-nodes.json";
    if (const char *xdg = environment("XDG_CONFIG_HOME"); xdg && fs::path(xdg).is_absolute())
        return fs::path(xdg) / "arbor" / "pacs-nodes.json";
    if (const char *home = environment("HOME"))
        return fs::path(home) / ".config" / "arbor" / "pacs-nodes.json";
    throw std::runtime_error("no config folder for PACS nodes: set ARBOR_CONFIG_DIR, XDG_CONFIG_HOME or HOME");
}

std::vector<PacsNode> read_nodes(const fs::path &file)
{
    std::error_code ec;
    if (!fs::exists(file, ec))
        return {};
    std::ifstream in(file);
    json j;
    try {
        j = json::parse(in);
    } catch (const json::exception &e) {
        throw std::runtime_error(file.string() + ": not valid JSON (" + e.what() + ")");
    }
    const std::string where = file.string();
    if (!j.is_object() || j.value("format", "") != "arbor-pacs-nodes/1" || !j.contains("nodes") ||
        !j.at("nodes").is_array())
        throw std::runtime_error(where + ": expected {\"format\": \"arbor-pacs-nodes/1\", \"nodes\": [...]}");
    std::vector<PacsNode> nodes;
    for (std::size_t i = 0; i < j.at("nodes").size(); ++i) {
        const json &e = j.at("nodes")[i];
        std::string at = where + ": node " + std::to_string(i + 1);
        if (!e.is_object())
            throw std::runtime_error(at + " must be an object");
        PacsNode n;
        n.name = text_member(e, "name", at, true);
        at += " (" + n.name + ")";
        if (n.name.empty() || looks_inline(n.name) || n.name.find('/') != std::string::npos)
            throw std::runtime_error(at + ": a name may not be empty or contain '@', ':' or '/'");
        for (const PacsNode &other : nodes)
            if (other.name == n.name)
                throw std::runtime_error(at + ": the name is used twice");
        const std::string kind = e.contains("kind") ? text_member(e, "kind", at, true) : "dimse";
        try {
            if (kind == "dimse") {
                n.aet = ae_title(text_member(e, "aet", at, true), at);
                n.host = text_member(e, "host", at, true);
                n.port = port_member(e, "port", at, true);
                if (e.contains("our_aet"))
                    n.our_aet = ae_title(text_member(e, "our_aet", at, true), at);
                n.our_port = port_member(e, "our_port", at, false);
            } else if (kind == "dicomweb") {
                n.kind = PacsNode::Kind::DicomWeb;
                n.url = service_url(text_member(e, "url", at, true), at);
                if (!is_url(n.url))
                    throw std::invalid_argument(at + ": \"url\" must start with http:// or https://");
                n.secret.user = text_member(e, "user", at, false);
                n.secret.password = secret_from(e, "password", "password_env", n.secret.password_env, at);
                n.secret.token = secret_from(e, "token", "token_env", n.secret.token_env, at);
            } else {
                throw std::runtime_error(at + ": \"kind\" is \"dimse\" or \"dicomweb\", not \"" + kind + "\"");
            }
        } catch (const std::invalid_argument &x) {
            throw std::runtime_error(x.what());
        }
        nodes.push_back(std::move(n));
    }
    return nodes;
}

void write_nodes(const fs::path &file, const std::vector<PacsNode> &nodes)
{
    nlohmann::ordered_json j = {{"format", "arbor-pacs-nodes/1"}, {"nodes", nlohmann::ordered_json::array()}};
    for (const PacsNode &n : nodes) {
        nlohmann::ordered_json e = {{"name", n.name}};
        if (n.kind == PacsNode::Kind::Dimse) {
            e["kind"] = "dimse";
            e["aet"] = n.aet;
            e["host"] = n.host;
            e["port"] = n.port;
            e["our_aet"] = n.our_aet;
            if (n.our_port)
                e["our_port"] = n.our_port;
        } else {
            e["kind"] = "dicomweb";
            e["url"] = n.url;
            if (!n.secret.user.empty())
                e["user"] = n.secret.user;
            if (!n.secret.password_env.empty())
                e["password_env"] = n.secret.password_env;
            else if (!n.secret.password.empty())
                e["password"] = n.secret.password;
            if (!n.secret.token_env.empty())
                e["token_env"] = n.secret.token_env;
            else if (!n.secret.token.empty())
                e["token"] = n.secret.token;
        }
        j["nodes"].push_back(e);
    }
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    AtomicFile out(file);
    out.write(j.dump(2) + "\n");
    out.commit();
    // The file may hold passwords: readable by its owner only, like ~/.netrc.
    fs::permissions(file, fs::perms::owner_read | fs::perms::owner_write, fs::perm_options::replace, ec);
}

PacsNode find_node(const std::string &text, const std::vector<PacsNode> &nodes)
{
    for (const PacsNode &n : nodes)
        if (n.name == text)
            return n;
    if (looks_inline(text))
        return parse_inline_node(text);
    std::string names;
    for (const PacsNode &n : nodes)
        names += (names.empty() ? "" : ", ") + n.name;
    throw std::invalid_argument("no PACS node named '" + text + "' (" +
                                (names.empty() ? std::string("none are configured") : "configured: " + names) +
                                "); give a name from `arbor pacs nodes`, AET@host:port or a DICOMweb URL");
}

} // namespace arbor::dicom
