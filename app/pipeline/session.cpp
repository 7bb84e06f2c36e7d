#include "session.hpp"

#include "core/atomic_file.hpp"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

namespace arbor::pipeline {

namespace fs = std::filesystem;
using nlohmann::json;
// Written in the order people read it (format first), not sorted.
using ordered = nlohmann::ordered_json;

namespace {

// --- writing ---------------------------------------------------------------

std::string stored_path(const fs::path &p, const fs::path &folder)
{
    if (p.empty())
        return {};
    if (is_input_uri(p.string()))
        return p.string(); // pacs://NODE/SERIES: the same wherever the session is
    std::error_code ec;
    const fs::path absolute = fs::weakly_canonical(fs::absolute(p, ec), ec);
    const fs::path base = fs::weakly_canonical(fs::absolute(folder.empty() ? fs::path(".") : folder, ec), ec);
    const auto top = [](const fs::path &x) {
        auto it = x.begin();
        return it != x.end() && ++it != x.end() ? *it : fs::path();
    };
    if (!ec && !top(absolute).empty() && top(absolute) == top(base)) {
        const fs::path relative = absolute.lexically_relative(base);
        if (!relative.empty())
            return relative.generic_string();
    }
    return (ec ? p : absolute).generic_string();
}

ordered typed_value(const arbor_param_desc *d, const std::string &text, const fs::path &folder)
{
    if (!d)
        return text;
    switch (d->type) {
    case ARBOR_PARAM_BOOL: return text == "true";
    case ARBOR_PARAM_CHOICE:
    case ARBOR_PARAM_STRING: return text;
    case ARBOR_PARAM_PATH: return stored_path(text, folder);
    default: {
        std::vector<double> numbers;
        std::istringstream in(text);
        for (std::string part; std::getline(in, part, ',');) {
            double x = 0;
            std::from_chars(part.data(), part.data() + part.size(), x);
            numbers.push_back(x);
        }
        ordered out = ordered::array();
        for (const double x : numbers)
            out.push_back(d->type == ARBOR_PARAM_INT ? ordered(static_cast<int64_t>(x)) : ordered(x));
        return d->components == 1 && out.size() == 1 ? out[0] : out;
    }
    }
}

ordered plugin_json(const PluginSetting &s, const PluginCatalog &catalog, const fs::path &folder)
{
    if (s.empty() && s.params.empty())
        return nullptr;
    ordered j = ordered::object();
    if (!s.id.empty()) {
        j["id"] = s.id;
        j["version"] = s.version;
    }
    const std::vector<const arbor_param_desc *> descs =
        s.id.empty() ? std::vector<const arbor_param_desc *>{} : catalog.descriptions(s.id);
    ordered params = ordered::object();
    for (const auto &[key, text] : s.params) {
        const arbor_param_desc *d = nullptr;
        for (const arbor_param_desc *x : descs)
            if (key == x->id)
                d = x;
        params[key] = typed_value(d, text, folder);
    }
    j["parameters"] = params;
    return j;
}

// --- reading ---------------------------------------------------------------

class Reader {
public:
    Reader(std::string name, fs::path folder, const PluginCatalog &catalog, std::vector<std::string> &warnings)
        : name_(std::move(name)), folder_(std::move(folder)), catalog_(catalog), warnings_(warnings)
    {
    }

    [[noreturn]] void fail(const std::string &what) const { throw SessionError(name_ + ": " + what); }

    const json &member(const json &j, const char *key, const std::string &where) const
    {
        if (!j.is_object() || !j.contains(key))
            fail(where + " has no \"" + key + "\"");
        return j.at(key);
    }

    double number(const json &j, const std::string &where) const
    {
        if (!j.is_number())
            fail(where + " must be a number, not " + j.dump());
        return j.get<double>();
    }

    // A whole number in [lo, hi] (both exact in a double), so that the
    // caller's conversion to an integer type is defined.
    double whole(const json &j, const std::string &where, double lo, double hi) const
    {
        const double x = number(j, where);
        if (!(x >= lo && x <= hi) || x != std::floor(x))
            fail(where + " must be a whole number from " + std::to_string(static_cast<int64_t>(lo)) + " to " +
                 std::to_string(static_cast<int64_t>(hi)) + ", not " + j.dump());
        return x;
    }

    std::string text(const json &j, const std::string &where) const
    {
        if (!j.is_string())
            fail(where + " must be a string, not " + j.dump());
        return j.get<std::string>();
    }

    fs::path path(const json &j, const std::string &where) const
    {
        const fs::path p = text(j, where);
        return p.is_absolute() || p.empty() || is_input_uri(p.string()) ? p : (folder_ / p).lexically_normal();
    }

    // A plugin of `kind` as saved: installed, every value within its domain.
    PluginSetting plugin(const json &j, std::string_view kind, const std::string &where) const
    {
        if (!j.is_object())
            fail(where + " must be an object with \"id\", \"version\" and \"parameters\"");
        PluginSetting s;
        if (j.contains("id"))
            s.id = text(j.at("id"), where + ".id");
        const std::string saved_version = j.contains("version") ? text(j.at("version"), where + ".version") : "";
        const json params = j.contains("parameters") ? j.at("parameters") : json::object();
        if (!params.is_object())
            fail(where + ".parameters must be an object");
        std::vector<const arbor_param_desc *> descs;
        if (!s.id.empty()) {
            if (!catalog_.registry().find(s.id))
                fail("the " + kind_noun(kind) + " " + s.id + (saved_version.empty() ? "" : " " + saved_version) +
                     " is not installed (see `arbor plugins`)");
            descs = catalog_.descriptions(s.id);
        }
        for (const auto &[key, value] : params.items()) {
            const arbor_param_desc *d = nullptr;
            for (const arbor_param_desc *x : descs)
                if (key == x->id)
                    d = x;
            if (!s.id.empty() && !d) {
                warnings_.push_back(name_ + ": " + s.id + " has no parameter '" + key + "' any more; ignored");
                continue;
            }
            s.params[key] = value_text(value, d, where + ".parameters." + key);
        }
        if (s.id.empty())
            return s; // an importer chosen by probing: checked when it is chosen
        try {
            PluginSetting resolved = catalog_.resolve(kind, s);
            if (!saved_version.empty() && saved_version != resolved.version)
                warnings_.push_back(name_ + " was saved with " + s.id + " " + saved_version + "; " +
                                    resolved.version + " is installed");
            return resolved;
        } catch (const std::invalid_argument &e) {
            fail(where + ": " + e.what());
        }
    }

    PluginSetting optional_plugin(const json &parent, const char *key, std::string_view kind,
                                  const std::string &where) const
    {
        if (!parent.contains(key) || parent.at(key).is_null())
            return {};
        return plugin(parent.at(key), kind, where + "." + key);
    }

private:
    std::string value_text(const json &v, const arbor_param_desc *d, const std::string &where) const
    {
        const auto number_text = [](double x) {
            char buf[40];
            return std::string(buf, std::to_chars(buf, buf + sizeof buf, x).ptr);
        };
        if (v.is_boolean())
            return v.get<bool>() ? "true" : "false";
        if (v.is_number())
            return number_text(v.get<double>());
        if (v.is_array()) {
            std::string out;
            for (const json &x : v) {
                if (!x.is_number())
                    fail(where + " must list numbers, not " + v.dump());
                out += (out.empty() ? "" : ",") + number_text(x.get<double>());
            }
            return out;
        }
        if (v.is_string()) {
            if (d && d->type == ARBOR_PARAM_PATH)
                return path(v, where).string();
            return v.get<std::string>();
        }
        fail(where + " has a value of the wrong kind: " + v.dump());
    }

    std::string name_;
    fs::path folder_;
    const PluginCatalog &catalog_;
    std::vector<std::string> &warnings_;
};

} // namespace

std::string session_text(const Document &d, const PluginCatalog &catalog, const fs::path &folder)
{
    ordered j = ordered::object();
    j["format"] = kSessionFormat;
    j["written_by"] = std::string("arbor ") + ARBOR_HOST_VERSION;

    // How plugins ran: `arbor run --session` and `arbor view` start with the
    // same isolation unless their command line says otherwise.
    const IsolationPolicy &isolation = catalog.registry().isolation();
    j["plugins"] = {{"isolate", isolation_mode_name(isolation.mode)},
                    {"timeout_s", isolation.settings.timeout_seconds}};

    ordered input = ordered::object();
    if (d.input.phantom) {
        const PhantomInput &p = *d.input.phantom;
        input["phantom"] = {{"kind", p.kind}, {"size", p.size}, {"noise", p.noise}, {"blobs", p.blobs},
                            {"seed", p.seed}};
    } else {
        input["path"] = stored_path(d.input.path, folder);
        input["importer"] = plugin_json(d.input.importer, catalog, folder);
    }
    j["input"] = input;

    j["filters"] = ordered::array();
    for (const PluginSetting &f : d.filters)
        j["filters"].push_back(plugin_json(f, catalog, folder));
    j["auto_denoise"] = d.auto_denoise;
    j["simplifier"] = plugin_json(d.simplifier, catalog, folder);
    if (d.cut.keep)
        j["cut"] = {{"keep", *d.cut.keep}};
    else if (d.cut.threshold)
        j["cut"] = {{"threshold", *d.cut.threshold}};
    else
        j["cut"] = {{"knee", true}};
    j["cut"]["keep_background"] = d.cut.keep_background;

    const Appearance &a = d.appearance;
    ordered look = ordered::object();
    look["relation"] = plugin_json(a.depictor, catalog, folder);
    look["selected_branch"] = a.selected ? ordered(*a.selected) : ordered(nullptr);
    look["generator"] = plugin_json(a.generator, catalog, folder);
    look["lut_size"] = a.lut_size;
    look["transfer_functions_file"] =
        a.transfer_functions_file.empty() ? ordered(nullptr) : ordered(stored_path(a.transfer_functions_file, folder));
    look["legend"] = plugin_json(a.legend, catalog, folder);
    look["legend_size"] = a.legend_size;
    look["balance_visibility"] = a.balance_visibility;
    j["appearance"] = look;

    const ViewChoice &v = d.view;
    ordered view = ordered::object();
    view["camera"] = {{"azimuth", v.orbit.azimuth},
                      {"elevation", v.orbit.elevation},
                      {"zoom", v.orbit.zoom},
                      {"projection", v.orbit.perspective ? "perspective" : "orthographic"},
                      {"view_angle", v.orbit.view_angle},
                      {"direction", v.auto_view ? "auto" : "fixed"},
                      {"framing", v.frame_content ? "content" : "volume"},
                      {"pan", {v.orbit.pan_right, v.orbit.pan_up}}};
    view["image"] = {{"width", v.width}, {"height", v.height}};
    view["background"] = v.background;
    view["renderer"] = plugin_json(v.renderer, catalog, folder);
    if (!v.branch_styles.empty()) {
        ordered styles = ordered::array();
        for (const auto &[vertex, style] : v.branch_styles) {
            ordered e = {{"extremum_vertex", vertex}, {"visible", style.visible}, {"opacity", style.opacity}};
            if (style.color)
                e["color"] = *style.color;
            styles.push_back(e);
        }
        view["branch_styles"] = styles;
    }
    j["view"] = view;
    try {
        return j.dump(2) + "\n";
    } catch (const ordered::type_error &) {
        // A replaced byte would make the session name a file that does not exist.
        throw SessionError("a session stores its paths as UTF-8, and " +
                           (d.input.path.empty() ? std::string("a parameter's text") : d.input.path.string()) +
                           " is not: rename it, or run without --save-session");
    }
}

void write_session(const fs::path &path, const Document &document, const PluginCatalog &catalog)
{
    const std::string text = session_text(document, catalog, path.parent_path());
    AtomicFile out(path);
    out.write(text);
    out.commit();
}

SessionRead parse_session(const std::string &text, const fs::path &folder, const std::string &name,
                          const PluginCatalog &catalog, bool require_input)
{
    SessionRead out;
    const Reader r(name, folder, catalog, out.warnings);
    json j;
    try {
        j = json::parse(text);
    } catch (const json::exception &e) { // parse_error, or out_of_range for a number like 1e999
        r.fail(std::string("not JSON: ") + e.what());
    }
    if (!j.is_object() || !j.contains("format") || !j.at("format").is_string())
        r.fail("not an Arbor session (no \"format\": \"" + std::string(kSessionFormat) + "\")");
    const std::string format = j.at("format").get<std::string>();
    if (format != kSessionFormat) {
        const std::string prefix = "arbor-session/";
        if (format.rfind(prefix, 0) == 0)
            r.fail("it is an " + format + " document, written by a newer Arbor; this one reads " + kSessionFormat);
        r.fail("not an Arbor session (its format is \"" + format + "\")");
    }

    Document &d = out.document;
    const json &input = r.member(j, "input", "the session");
    if (input.contains("phantom")) {
        const json &p = input.at("phantom");
        PhantomInput ph;
        ph.kind = r.text(r.member(p, "kind", "input.phantom"), "input.phantom.kind");
        ph.size = static_cast<int64_t>(r.whole(r.member(p, "size", "input.phantom"), "input.phantom.size", 8, 1024));
        ph.noise = p.contains("noise") ? r.number(p.at("noise"), "input.phantom.noise") : 0.0;
        ph.blobs = p.contains("blobs") ? static_cast<int>(r.whole(p.at("blobs"), "input.phantom.blobs", 0, 1e6)) : 0;
        ph.seed = p.contains("seed") ? static_cast<uint64_t>(r.whole(p.at("seed"), "input.phantom.seed", 0, 9.0e15))
                                     : 1;
        d.input.phantom = ph;
    } else {
        const std::string saved = r.text(r.member(input, "path", "input"), "input.path");
        d.input.path = r.path(input.at("path"), "input.path");
        if (require_input && !is_input_uri(d.input.path.string()) && !fs::exists(d.input.path))
            r.fail("the input " + d.input.path.string() + " does not exist" +
                   (saved != d.input.path.string() ? " (saved as " + saved + ")" : ""));
        d.input.importer = r.optional_plugin(input, "importer", ARBOR_KIND_IMPORTER, "input");
    }

    if (j.contains("filters")) {
        const json &filters = j.at("filters");
        if (!filters.is_array())
            r.fail("filters must be a list");
        for (std::size_t i = 0; i < filters.size(); ++i)
            d.filters.push_back(r.plugin(filters[i], ARBOR_KIND_FILTER, "filters[" + std::to_string(i) + "]"));
    }
    if (j.contains("auto_denoise")) {
        if (!j.at("auto_denoise").is_boolean())
            r.fail("auto_denoise must be true or false");
        d.auto_denoise = j.at("auto_denoise").get<bool>();
    }
    d.simplifier = r.plugin(r.member(j, "simplifier", "the session"), ARBOR_KIND_SIMPLIFIER, "simplifier");

    const json &cut = r.member(j, "cut", "the session");
    if (cut.contains("keep")) {
        const double keep = r.number(cut.at("keep"), "cut.keep");
        if (!(keep >= 1) || keep != static_cast<double>(static_cast<std::size_t>(keep)))
            r.fail("cut.keep must be a whole number >= 1, not " + cut.at("keep").dump());
        d.cut.keep = static_cast<std::size_t>(keep);
    } else if (cut.contains("threshold")) {
        d.cut.threshold = r.number(cut.at("threshold"), "cut.threshold");
        if (!(*d.cut.threshold >= 0 && *d.cut.threshold <= 1))
            r.fail("cut.threshold must lie in [0, 1], not " + cut.at("threshold").dump());
    } else if (!cut.contains("knee")) {
        r.fail("cut must be {\"keep\": N}, {\"threshold\": T} or {\"knee\": true}");
    }
    if (cut.contains("keep_background")) {
        if (!cut.at("keep_background").is_boolean())
            r.fail("cut.keep_background must be true or false");
        d.cut.keep_background = cut.at("keep_background").get<bool>();
    }

    const json &look = r.member(j, "appearance", "the session");
    Appearance &a = d.appearance;
    a.depictor = r.optional_plugin(look, "relation", ARBOR_KIND_DEPICTOR, "appearance");
    if (look.contains("selected_branch") && !look.at("selected_branch").is_null()) {
        const double b = r.number(look.at("selected_branch"), "appearance.selected_branch");
        if (!(b >= 0 && b < 1e9) || b != static_cast<double>(static_cast<int32_t>(b)))
            r.fail("appearance.selected_branch must be a branch label (0, 1, ...), not " +
                   look.at("selected_branch").dump());
        a.selected = static_cast<int32_t>(b);
    }
    a.generator = r.plugin(r.member(look, "generator", "appearance"), ARBOR_KIND_TF_GENERATOR, "appearance.generator");
    if (look.contains("lut_size")) {
        const double n = r.number(look.at("lut_size"), "appearance.lut_size");
        if (!(n >= 2 && n <= 65536) || n != static_cast<double>(static_cast<uint32_t>(n)))
            r.fail("appearance.lut_size must be a whole number in [2, 65536]");
        a.lut_size = static_cast<uint32_t>(n);
    }
    if (look.contains("transfer_functions_file") && !look.at("transfer_functions_file").is_null()) {
        a.transfer_functions_file = r.path(look.at("transfer_functions_file"), "appearance.transfer_functions_file");
        if (!fs::exists(a.transfer_functions_file))
            r.fail("the transfer functions file " + a.transfer_functions_file.string() + " does not exist");
    }
    a.legend = r.optional_plugin(look, "legend", ARBOR_KIND_DEPICTOR, "appearance");
    if (look.contains("balance_visibility")) {
        if (!look.at("balance_visibility").is_boolean())
            r.fail("appearance.balance_visibility must be true or false");
        a.balance_visibility = look.at("balance_visibility").get<bool>();
    }
    if (look.contains("legend_size")) {
        const double n = r.number(look.at("legend_size"), "appearance.legend_size");
        if (!(n >= 16 && n <= 8192) || n != static_cast<double>(static_cast<uint32_t>(n)))
            r.fail("appearance.legend_size must be a whole number in [16, 8192]");
        a.legend_size = static_cast<uint32_t>(n);
    }

    const json &view = r.member(j, "view", "the session");
    ViewChoice &v = d.view;
    if (view.contains("camera")) {
        const json &c = view.at("camera");
        v.orbit.azimuth = r.number(r.member(c, "azimuth", "view.camera"), "view.camera.azimuth");
        v.orbit.elevation = r.number(r.member(c, "elevation", "view.camera"), "view.camera.elevation");
        v.orbit.zoom = r.number(r.member(c, "zoom", "view.camera"), "view.camera.zoom");
        if (!(v.orbit.zoom > 0 && v.orbit.zoom <= 1000))
            r.fail("view.camera.zoom must lie in (0, 1000]");
        if (c.contains("projection")) {
            const std::string p = r.text(c.at("projection"), "view.camera.projection");
            if (p != "perspective" && p != "orthographic")
                r.fail("view.camera.projection must be \"perspective\" or \"orthographic\", not \"" + p + "\"");
            v.orbit.perspective = p == "perspective";
        }
        const auto word = [&](const char *key, const char *yes, const char *no, bool &out) {
            if (!c.contains(key))
                return;
            const std::string w = r.text(c.at(key), std::string("view.camera.") + key);
            if (w != yes && w != no)
                r.fail(std::string("view.camera.") + key + " must be \"" + yes + "\" or \"" + no + "\", not \"" + w +
                       "\"");
            out = w == yes;
        };
        word("direction", "auto", "fixed", v.auto_view);
        word("framing", "content", "volume", v.frame_content);
        if (c.contains("view_angle")) {
            v.orbit.view_angle = r.number(c.at("view_angle"), "view.camera.view_angle");
            if (!(v.orbit.view_angle > 0 && v.orbit.view_angle < 180))
                r.fail("view.camera.view_angle must lie in (0, 180) degrees");
        }
        if (c.contains("pan")) { // [right, up] in mm; older sessions have none
            const json &p = c.at("pan");
            if (!p.is_array() || p.size() != 2)
                r.fail("view.camera.pan must be [right, up] in mm");
            v.orbit.pan_right = r.number(p.at(0), "view.camera.pan[0]");
            v.orbit.pan_up = r.number(p.at(1), "view.camera.pan[1]");
        }
    }
    if (view.contains("image")) {
        const json &im = view.at("image");
        const auto side = [&](const char *key) {
            const double n = r.number(r.member(im, key, "view.image"), std::string("view.image.") + key);
            if (!(n >= 1 && n <= 16384) || n != static_cast<double>(static_cast<uint32_t>(n)))
                r.fail(std::string("view.image.") + key + " must be a whole number of pixels in [1, 16384]");
            return static_cast<uint32_t>(n);
        };
        v.width = side("width");
        v.height = side("height");
    }
    if (view.contains("branch_styles")) {
        const json &styles = view.at("branch_styles");
        if (!styles.is_array())
            r.fail("view.branch_styles must be a list");
        for (const json &e : styles) {
            const std::string where = "view.branch_styles[" + std::to_string(v.branch_styles.size()) + "]";
            const double vertex = r.number(r.member(e, "extremum_vertex", where), where + ".extremum_vertex");
            if (!(vertex >= 0 && vertex < 9.0e15) || vertex != std::floor(vertex))
                r.fail(where + ".extremum_vertex must be a voxel index");
            BranchStyle style;
            if (e.contains("visible")) {
                if (!e.at("visible").is_boolean())
                    r.fail(where + ".visible must be true or false");
                style.visible = e.at("visible").get<bool>();
            }
            if (e.contains("opacity")) {
                style.opacity = r.number(e.at("opacity"), where + ".opacity");
                if (!(style.opacity >= 0 && style.opacity <= 100))
                    r.fail(where + ".opacity must lie in [0, 100]");
            }
            if (e.contains("color")) {
                const json &c = e.at("color");
                if (!c.is_array() || c.size() != 3)
                    r.fail(where + ".color must be [r, g, b] in [0, 1]");
                std::array<double, 3> rgb{};
                for (std::size_t k = 0; k < 3; ++k) {
                    rgb[k] = r.number(c.at(k), where + ".color");
                    if (!(rgb[k] >= 0 && rgb[k] <= 1))
                        r.fail(where + ".color must be [r, g, b] in [0, 1]");
                }
                style.color = rgb;
            }
            v.branch_styles[static_cast<int64_t>(vertex)] = style;
        }
    }
    if (view.contains("background")) {
        const json &bg = view.at("background");
        if (!bg.is_array() || bg.size() != 4)
            r.fail("view.background must be [r, g, b, a]");
        for (std::size_t c = 0; c < 4; ++c) {
            const double x = r.number(bg[c], "view.background");
            if (!(x >= 0 && x <= 1))
                r.fail("view.background values lie in [0, 1]");
            v.background[c] = x;
        }
    }
    v.renderer = r.plugin(r.member(view, "renderer", "view"), ARBOR_KIND_RENDERER, "view.renderer");
    return out;
}

SessionRead read_session(const fs::path &path, const PluginCatalog &catalog, bool require_input)
{
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw SessionError(path.string() + ": cannot open the session file");
    std::ostringstream text;
    text << in.rdbuf();
    return parse_session(text.str(), path.parent_path(), path.string(), catalog, require_input);
}

std::optional<SessionIsolation> session_isolation(const fs::path &path)
{
    std::ifstream in(path);
    if (!in)
        return std::nullopt;
    const json j = json::parse(in, nullptr, false);
    if (j.is_discarded() || !j.is_object() || !j.contains("plugins") || !j.at("plugins").is_object())
        return std::nullopt;
    const json &p = j.at("plugins");
    SessionIsolation out;
    if (p.contains("isolate") && p.at("isolate").is_string())
        out.mode = p.at("isolate").get<std::string>();
    if (p.contains("timeout_s") && p.at("timeout_s").is_number())
        out.timeout_seconds = p.at("timeout_s").get<double>();
    return out;
}

} // namespace arbor::pipeline
