#include "conformance_checks.hpp"

#include "conformance_cancel.hpp"
#include "conformance_fixtures.hpp"
#include "descriptor_rules.hpp"
#include "host_services.hpp"
#include "tf_generation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

namespace arbor {

namespace fs = std::filesystem;

namespace {

// A check body returns "" when it passed, otherwise the first problem.
using Body = std::function<std::string()>;

// Cancellation: the task is cancelled this long into a call on a large
// input, and the plugin must return within the grace after that (host.h
// asks for a poll every tenth of a second; the grace allows a loaded machine).
constexpr std::chrono::milliseconds kCancelAfter{50};
constexpr double kCancelGraceSeconds = 1.0;

// A number in a message: "NaN" whatever its sign bit, "infinity", or %.9g.
std::string number_text(double x)
{
    if (std::isnan(x))
        return "NaN";
    if (std::isinf(x))
        return x > 0 ? "infinity" : "-infinity";
    char text[32];
    std::snprintf(text, sizeof text, "%.9g", x);
    return text;
}

std::string status_text(arbor_status s)
{
    return std::string(arbor_status_name(s)) + " (" + std::to_string(s) + ")";
}

class PluginChecks {
public:
    PluginChecks(const arbor_plugin_entry &entry, const arbor_host *host,
                 const arbor_plugin_descriptor &d, fs::path scratch, CheckSink &sink)
        : entry_(entry), host_(host), d_(d), id_(d.id), scratch_(std::move(scratch)), sink_(sink)
    {
    }

    void run_all()
    {
        run("descriptor", [&] { return check_descriptor(&d_); });
        const bool created = run("create", [&] { return create(); });
        run("create with NULL output", [&] {
            const arbor_status s = entry_.create_plugin(host_, id_.c_str(), nullptr);
            return s == ARBOR_OK ? "returned ok for a NULL output pointer" : "";
        });
        if (!created)
            return;
        run("interfaces", [&] { return interfaces(); });
        if (params_) {
            run("parameter descriptions", [&] {
                const auto problems = check_param_set(p_, *params_);
                return problems.empty() ? std::string() : problems.front();
            });
            run("parameter values", [&] { return parameter_values(); });
            run("parameter invalid arguments", [&] { return parameter_invalid_arguments(); });
        }
        const std::string kind = d_.kind;
        if (kind == ARBOR_KIND_IMPORTER)
            importer_checks();
        else if (kind == ARBOR_KIND_FILTER)
            filter_checks();
        else if (kind == ARBOR_KIND_SIMPLIFIER)
            simplifier_checks();
        else if (kind == ARBOR_KIND_DEPICTOR)
            depictor_checks();
        else if (kind == ARBOR_KIND_TF_GENERATOR)
            tf_checks();
        else if (kind == ARBOR_KIND_RENDERER)
            renderer_checks();
        run("destroy", [&] {
            p_->destroy(p_);
            p_ = nullptr;
            return std::string();
        });
    }

private:
    bool run(const std::string &name, const Body &body)
    {
        sink_.begin(id_, name);
        std::string problem;
        try {
            problem = body();
        } catch (const std::exception &e) {
            problem = std::string("host-side exception: ") + e.what();
        }
        // What the plugin last said, on every failure: often the reason.
        if (!problem.empty() && p_) {
            const std::string said = message();
            if (said.empty())
                problem += " (last_error: empty)";
            else if (problem.find(said) == std::string::npos)
                problem += " (last_error: \"" + said + "\")";
        }
        sink_.result(id_, name, problem.empty(), problem);
        return problem.empty();
    }

    // "" unless `got` is an error (other than CANCELLED) that came without
    // a message: users would see only the status's name.
    std::string unexplained(arbor_status got, const std::string &call) const
    {
        if (got == ARBOR_OK || got == ARBOR_ERROR_CANCELLED || !message().empty())
            return "";
        return call + " returned " + status_text(got) + " without a last_error message";
    }

    // "" when a call that succeeded left last_error empty: a message from an
    // earlier call would otherwise stand for the next error that has none.
    std::string cleared(const std::string &call) const
    {
        const std::string said = message();
        if (said.empty())
            return "";
        return call + " succeeded but last_error still says \"" + said +
               "\"; clear it at the start of every call";
    }

    // Calls `call` with a task cancelled soon after it starts; "" when it
    // returned before the cancel came, or soon after it with CANCELLED (or
    // OK: the work was done).
    // `refused` (when given) is set when the plugin turned the input down
    // as UNSUPPORTED, with a message: the caller may try another.
    std::string cancellation(const std::string &call, const std::function<arbor_status(arbor_task *)> &body,
                             bool *refused = nullptr)
    {
        const CancelOutcome r = cancel_mid_call(body, kCancelAfter);
        if (refused)
            *refused = r.status == ARBOR_ERROR_UNSUPPORTED && !message().empty();
        if (refused && *refused)
            return "";
        const auto ms = [](double s) { return std::to_string(static_cast<long>(s * 1000 + 0.5)) + " ms"; };
        if (r.cancelled && r.seconds_after > kCancelGraceSeconds)
            return call + " went on for " + ms(r.seconds_after) +
                   " after its task was cancelled; poll task->cancelled at least every 0.1 s of work and return "
                   "ARBOR_ERROR_CANCELLED";
        if (r.status != ARBOR_OK && r.status != ARBOR_ERROR_CANCELLED)
            return call + (r.cancelled ? " cancelled after " + ms(r.seconds - r.seconds_after) : "") +
                   " returned " + status_text(r.status) + ": " + message();
        return "";
    }

    std::string message() const
    {
        const char *m = p_->last_error(p_);
        return m ? m : "";
    }

    // "" when `got` equals `want` and a failure came with a message.
    std::string expect(arbor_status got, arbor_status want, const std::string &call) const
    {
        if (got != want)
            return call + " returned " + status_text(got) + ", expected " + status_text(want);
        if (want != ARBOR_OK && message().empty())
            return call + " failed without a last_error message";
        return "";
    }

    // "" when `got` is any failure and came with a message.
    std::string expect_failure(arbor_status got, const std::string &call) const
    {
        if (got == ARBOR_OK)
            return call + " returned ok, expected an error";
        if (message().empty())
            return call + " failed without a last_error message";
        return "";
    }

    std::string create()
    {
        const arbor_status s = entry_.create_plugin(host_, id_.c_str(), &p_);
        if (s != ARBOR_OK)
            return "create_plugin returned " + status_text(s);
        if (!p_)
            return "create_plugin returned ok but no instance";
        if (p_->struct_size < ARBOR_MIN_SIZE(arbor_plugin))
            return "instance struct_size is too small";
        if (!p_->destroy || !p_->get_interface || !p_->last_error)
            return "instance has NULL functions";
        if (!p_->descriptor || !p_->descriptor->id || id_ != p_->descriptor->id)
            return "instance descriptor does not match the plugin";
        params_ = static_cast<const arbor_params_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_PARAMS));
        arbor_plugin *unknown = nullptr;
        const arbor_status u = entry_.create_plugin(host_, "org.invalid.no-such-plugin", &unknown);
        if (u == ARBOR_OK || unknown)
            return "create_plugin accepted an unknown id";
        return "";
    }

    std::string interfaces()
    {
        const void *t = p_->get_interface(p_, kind_interface_id(d_.kind));
        if (!t)
            return std::string("missing interface ") + kind_interface_id(d_.kind);
        if (p_->get_interface(p_, "arbor.no-such-interface/1"))
            return "returned a table for an unknown interface id";
        if (p_->get_interface(p_, nullptr))
            return "returned a table for a NULL interface id";
        if (!p_->last_error(p_))
            return "last_error returned NULL";
        // Every function pointer of the kind's table must be set.
        std::size_t functions = 0;
        const std::string kind = d_.kind;
        if (kind == ARBOR_KIND_IMPORTER) {
            const auto *i = static_cast<const arbor_importer_v1 *>(t);
            if (!i->suffixes)
                return "importer suffixes is NULL";
            functions = (i->probe && i->read_header && i->read_voxels) ? 3 : 0;
        } else if (kind == ARBOR_KIND_FILTER) {
            const auto *i = static_cast<const arbor_filter_v1 *>(t);
            functions = (i->output_type && i->apply) ? 2 : 0;
        } else if (kind == ARBOR_KIND_SIMPLIFIER) {
            const auto *i = static_cast<const arbor_simplifier_v1 *>(t);
            functions = (i->prepare && i->importance) ? 2 : 0;
        } else if (kind == ARBOR_KIND_DEPICTOR) {
            const auto *i = static_cast<const arbor_depictor_v1 *>(t);
            functions = (i->depict && i->related && i->legend) ? 3 : 0;
        } else if (kind == ARBOR_KIND_TF_GENERATOR) {
            functions = static_cast<const arbor_tf_generator_v1 *>(t)->generate ? 1 : 0;
        } else if (kind == ARBOR_KIND_RENDERER) {
            functions = static_cast<const arbor_renderer_v1 *>(t)->render ? 1 : 0;
        }
        return functions ? "" : "the interface table has NULL functions";
    }

    arbor_param_value value_of(const arbor_param_desc &d) const
    {
        arbor_param_value v{};
        v.struct_size = sizeof(v);
        v.type = d.type;
        v.components = d.components;
        return v;
    }

    std::string parameter_values()
    {
        for (uint32_t i = 0, n = params_->count(p_); i < n; ++i) {
            const arbor_param_desc *d = params_->describe(p_, i);
            const std::string who = std::string("parameter '") + d->id + "'";
            arbor_param_value v = value_of(*d);
            if (auto e = expect(params_->get(p_, d->id, &v), ARBOR_OK, "get " + who); !e.empty())
                return e;
            if (v.type != d->type || v.components != d->components)
                return "get " + who + " returned another type or component count";
            if (d->type == ARBOR_PARAM_STRING || d->type == ARBOR_PARAM_PATH) {
                if (!v.text || std::strcmp(v.text, d->default_text) != 0)
                    return "get " + who + " does not return the default text";
            } else {
                for (uint32_t c = 0; c < d->components; ++c)
                    if (v.number[c] != d->default_value[c])
                        return "get " + who + " does not return the default value";
            }
            std::string text = v.text ? v.text : "";
            v.text = text.c_str();
            if (auto e = expect(params_->set(p_, d->id, &v), ARBOR_OK, "set " + who + " to its default");
                !e.empty())
                return e;
        }
        return "";
    }

    std::string parameter_invalid_arguments()
    {
        for (uint32_t i = 0, n = params_->count(p_); i < n; ++i) {
            const arbor_param_desc *d = params_->describe(p_, i);
            const std::string who = std::string("parameter '") + d->id + "'";
            arbor_param_value before = value_of(*d);
            params_->get(p_, d->id, &before);
            const std::string before_text = before.text ? before.text : "";

            arbor_param_value wrong = value_of(*d);
            wrong.type = d->type == ARBOR_PARAM_FLOAT ? ARBOR_PARAM_INT : ARBOR_PARAM_FLOAT;
            if (auto e = expect(params_->set(p_, d->id, &wrong), ARBOR_ERROR_INVALID_ARGUMENT,
                                "set " + who + " with the wrong type");
                !e.empty())
                return e;
            if (d->type == ARBOR_PARAM_STRING || d->type == ARBOR_PARAM_PATH) {
                arbor_param_value null_text = value_of(*d);
                if (auto e = expect(params_->set(p_, d->id, &null_text), ARBOR_ERROR_INVALID_ARGUMENT,
                                    "set " + who + " with NULL text");
                    !e.empty())
                    return e;
                continue;
            }
            arbor_param_value comps = value_of(*d);
            comps.components = d->components == 1 ? 2 : d->components - 1;
            if (auto e = expect(params_->set(p_, d->id, &comps), ARBOR_ERROR_INVALID_ARGUMENT,
                                "set " + who + " with the wrong component count");
                !e.empty())
                return e;
            arbor_param_value high = value_of(*d);
            for (uint32_t c = 0; c < d->components; ++c)
                high.number[c] = d->max_value + std::max(1.0, std::fabs(d->max_value));
            if (auto e = expect(params_->set(p_, d->id, &high), ARBOR_ERROR_OUT_OF_RANGE,
                                "set " + who + " above its maximum");
                !e.empty())
                return e;
            arbor_param_value nan = value_of(*d);
            for (uint32_t c = 0; c < d->components; ++c)
                nan.number[c] = std::nan("");
            if (auto e = expect(params_->set(p_, d->id, &nan), ARBOR_ERROR_OUT_OF_RANGE,
                                "set " + who + " to NaN");
                !e.empty())
                return e;
            if (d->type != ARBOR_PARAM_FLOAT && d->min_value + 0.5 <= d->max_value) {
                arbor_param_value half = value_of(*d);
                for (uint32_t c = 0; c < d->components; ++c)
                    half.number[c] = d->min_value + 0.5;
                if (auto e = expect(params_->set(p_, d->id, &half), ARBOR_ERROR_OUT_OF_RANGE,
                                    "set " + who + " to a fraction");
                    !e.empty())
                    return e;
            }
            arbor_param_value after = value_of(*d);
            params_->get(p_, d->id, &after);
            for (uint32_t c = 0; c < d->components; ++c)
                if (after.number[c] != before.number[c])
                    return "a refused set changed " + who;
        }
        arbor_param_value any{};
        any.struct_size = sizeof(any);
        any.type = ARBOR_PARAM_FLOAT;
        any.components = 1;
        if (auto e = expect(params_->set(p_, "no-such-parameter", &any), ARBOR_ERROR_NOT_FOUND,
                            "set of an unknown parameter");
            !e.empty())
            return e;
        if (auto e = expect(params_->get(p_, "no-such-parameter", &any), ARBOR_ERROR_NOT_FOUND,
                            "get of an unknown parameter");
            !e.empty())
            return e;
        if (auto e = expect(params_->set(p_, nullptr, &any), ARBOR_ERROR_INVALID_ARGUMENT,
                            "set with a NULL id");
            !e.empty())
            return e;
        if (params_->count(p_) > 0) {
            const char *first = params_->describe(p_, 0)->id;
            if (auto e = expect(params_->set(p_, first, nullptr), ARBOR_ERROR_INVALID_ARGUMENT,
                                "set with a NULL value");
                !e.empty())
                return e;
            if (auto e = expect(params_->get(p_, first, nullptr), ARBOR_ERROR_INVALID_ARGUMENT,
                                "get into a NULL value");
                !e.empty())
                return e;
            arbor_param_value small = any;
            small.struct_size = 4;
            if (auto e = expect(params_->get(p_, first, &small), ARBOR_ERROR_INVALID_ARGUMENT,
                                "get into a record whose struct_size is 4");
                !e.empty())
                return e;
        }
        return "";
    }

    // ---- importer -----------------------------------------------------------

    fs::path write_file(const std::string &name, std::size_t bytes, bool garbage)
    {
        const fs::path p = scratch_ / name;
        std::ofstream out(p, std::ios::binary);
        uint64_t x = 0x9e3779b97f4a7c15ULL;
        for (std::size_t i = 0; i < bytes; ++i) {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            const char c = garbage ? static_cast<char>(x & 0xff) : '\0';
            out.put(c);
        }
        return p;
    }

    std::vector<std::string> suffixes(const char *list) const
    {
        std::vector<std::string> out;
        std::stringstream ss(list ? list : "");
        std::string s;
        while (std::getline(ss, s, ';'))
            if (!s.empty() && out.size() < 4)
                out.push_back(s);
        if (out.empty())
            out.push_back(".dat");
        return out;
    }

    void importer_checks()
    {
        const auto &t = *static_cast<const arbor_importer_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_IMPORTER));
        const fs::path garbage = write_file("garbage.bin", 4096, true);
        std::vector<uint8_t> head(64, 7);
        Task task;
        run("importer probe invalid arguments", [&] {
            int32_t c = 0;
            if (auto e = expect(t.probe(p_, nullptr, head.data(), head.size(), &c),
                                ARBOR_ERROR_INVALID_ARGUMENT, "probe(NULL path)"); !e.empty())
                return e;
            if (auto e = expect(t.probe(p_, garbage.c_str(), nullptr, 10, &c),
                                ARBOR_ERROR_INVALID_ARGUMENT, "probe(NULL head, size 10)"); !e.empty())
                return e;
            return expect(t.probe(p_, garbage.c_str(), head.data(), head.size(), nullptr),
                          ARBOR_ERROR_INVALID_ARGUMENT, "probe(NULL confidence)");
        });
        run("importer probe of garbage", [&] {
            int32_t c = -1;
            const arbor_status s = t.probe(p_, garbage.c_str(), head.data(), head.size(), &c);
            if (s != ARBOR_OK)
                return "probe of a garbage file returned " + status_text(s) + ", expected ok";
            if (c < 0 || c > 100)
                return std::string("confidence outside [0, 100]");
            return cleared("probe of a garbage file, after the failed calls before it,");
        });
        run("importer read_header invalid arguments", [&] {
            arbor_volume v{};
            v.struct_size = sizeof(v);
            if (auto e = expect(t.read_header(p_, nullptr, task.get(), &v), ARBOR_ERROR_INVALID_ARGUMENT,
                                "read_header(NULL path)"); !e.empty())
                return e;
            if (auto e = expect(t.read_header(p_, garbage.c_str(), task.get(), nullptr),
                                ARBOR_ERROR_INVALID_ARGUMENT, "read_header(NULL volume)"); !e.empty())
                return e;
            v.struct_size = 0;
            return expect(t.read_header(p_, garbage.c_str(), task.get(), &v),
                          ARBOR_ERROR_INVALID_ARGUMENT, "read_header(struct_size 0)");
        });
        run("importer missing file", [&] {
            arbor_volume v{};
            v.struct_size = sizeof(v);
            const fs::path missing = scratch_ / "no-such-file.nrrd";
            return expect_failure(t.read_header(p_, missing.c_str(), task.get(), &v),
                                  "read_header of a missing file");
        });
        run("importer garbage and empty files", [&] {
            for (const std::string &suffix : suffixes(t.suffixes)) {
                fs::path bad, empty;
                if (suffix == "/") {
                    bad = scratch_ / "garbage-folder";
                    fs::create_directories(bad);
                    std::ofstream(bad / "garbage.bin") << "not a volume";
                    empty = scratch_ / "empty-folder";
                    fs::create_directories(empty);
                } else {
                    bad = write_file("garbage" + suffix, 4096, true);
                    empty = write_file("empty" + suffix, 0, false);
                }
                arbor_volume v{};
                v.struct_size = sizeof(v);
                if (auto e = expect_failure(t.read_header(p_, bad.c_str(), task.get(), &v),
                                            "read_header of " + bad.filename().string());
                    !e.empty())
                    return e;
                v = arbor_volume{};
                v.struct_size = sizeof(v);
                if (auto e = expect_failure(t.read_header(p_, empty.c_str(), task.get(), &v),
                                            "read_header of " + empty.filename().string());
                    !e.empty())
                    return e;
            }
            return std::string();
        });
        run("importer read_voxels invalid arguments", [&] {
            FixtureVolume fixture(ARBOR_VOXEL_U8, 4);
            arbor_volume v = fixture.record();
            if (auto e = expect(t.read_voxels(p_, nullptr, task.get(), &v), ARBOR_ERROR_INVALID_ARGUMENT,
                                "read_voxels(NULL path)"); !e.empty())
                return e;
            if (auto e = expect(t.read_voxels(p_, garbage.c_str(), task.get(), nullptr),
                                ARBOR_ERROR_INVALID_ARGUMENT, "read_voxels(NULL volume)"); !e.empty())
                return e;
            v.voxels = nullptr;
            return expect(t.read_voxels(p_, garbage.c_str(), task.get(), &v),
                          ARBOR_ERROR_INVALID_ARGUMENT, "read_voxels(volume without voxels)");
        });
    }

    // ---- filter -------------------------------------------------------------

    void filter_checks()
    {
        const auto &t = *static_cast<const arbor_filter_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_FILTER));
        Task task;
        run("filter invalid arguments", [&] {
            FixtureVolume in(ARBOR_VOXEL_U8, 8), out(ARBOR_VOXEL_U8, 8), small(ARBOR_VOXEL_U8, 4);
            arbor_voxel_type type = 0;
            if (auto e = expect(t.output_type(p_, nullptr, &type), ARBOR_ERROR_INVALID_ARGUMENT,
                                "output_type(NULL input)"); !e.empty())
                return e;
            if (auto e = expect(t.output_type(p_, &in.record(), nullptr), ARBOR_ERROR_INVALID_ARGUMENT,
                                "output_type(NULL out)"); !e.empty())
                return e;
            if (auto e = expect(t.apply(p_, nullptr, &out.record(), task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "apply(NULL input)"); !e.empty())
                return e;
            if (auto e = expect(t.apply(p_, &in.record(), nullptr, task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "apply(NULL output)"); !e.empty())
                return e;
            if (auto e = expect(t.apply(p_, &in.record(), &small.record(), task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "apply with output dims that differ");
                !e.empty())
                return e;
            arbor_volume no_voxels = out.record();
            no_voxels.voxels = nullptr;
            return expect(t.apply(p_, &in.record(), &no_voxels, task.get()),
                          ARBOR_ERROR_INVALID_ARGUMENT, "apply with an output without voxels");
        });
        run("filter on every voxel type", [&] {
            int accepted = 0;
            for (arbor_voxel_type vt = ARBOR_VOXEL_U8; vt <= ARBOR_VOXEL_F64; ++vt) {
                bool refused = false;
                if (auto e = filter_once(t, task, vt, 8, 8, 8, refused); !e.empty())
                    return e;
                accepted += refused ? 0 : 1;
            }
            return accepted ? std::string() : std::string("accepted no voxel type at all");
        });
        run("filter on tiny and thin volumes", [&] {
            const int64_t shapes[][3] = {{1, 1, 1}, {2, 2, 2}, {1, 9, 7}, {9, 1, 7}, {9, 7, 1}};
            for (arbor_voxel_type vt = ARBOR_VOXEL_U8; vt <= ARBOR_VOXEL_F64; ++vt)
                for (const auto &d : shapes) {
                    bool refused = false;
                    if (auto e = filter_once(t, task, vt, d[0], d[1], d[2], refused); !e.empty())
                        return e;
                }
            return std::string();
        });
        run("filter cancelled mid-call", [&] {
            // A CT-sized slab in the first type the filter takes.
            for (const arbor_voxel_type vt : {ARBOR_VOXEL_I16, ARBOR_VOXEL_U16, ARBOR_VOXEL_F32, ARBOR_VOXEL_U8}) {
                FixtureVolume in(vt, 192, 192, 128);
                arbor_voxel_type out_type = 0;
                if (t.output_type(p_, &in.record(), &out_type) != ARBOR_OK || arbor_voxel_size(out_type) == 0)
                    continue;
                FixtureVolume out(out_type, 192, 192, 128);
                bool refused = false;
                const std::string problem = cancellation(
                    std::string("apply on 192x192x128 ") + arbor_voxel_type_name(vt),
                    [&](arbor_task *task) { return t.apply(p_, &in.record(), &out.record(), task); }, &refused);
                if (!refused)
                    return problem;
            }
            return std::string();
        });
    }

    // One filter run on an nx*ny*nz volume of `vt`: "" when it worked (its
    // floating-point output finite) or was refused with a message: as
    // UNSUPPORTED, or any error for a volume thinner than 3 voxels (`refused`
    // says which).
    std::string filter_once(const arbor_filter_v1 &t, Task &task, arbor_voxel_type vt, int64_t nx, int64_t ny,
                            int64_t nz, bool &refused)
    {
        const std::string what = std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) + " " +
                                 arbor_voxel_type_name(vt);
        FixtureVolume in(vt, nx, ny, nz);
        arbor_voxel_type out_type = 0;
        const arbor_status s = t.output_type(p_, &in.record(), &out_type);
        refused = s != ARBOR_OK;
        if (auto e = unexplained(s, "output_type(" + what + ")"); !e.empty())
            return e;
        if (s == ARBOR_ERROR_UNSUPPORTED)
            return "";
        if (s != ARBOR_OK)
            return "output_type(" + what + ") returned " + status_text(s) + ": " + message();
        if (arbor_voxel_size(out_type) == 0)
            return "output_type(" + what + ") gave an unknown type";
        FixtureVolume out(out_type, nx, ny, nz);
        const arbor_status a = t.apply(p_, &in.record(), &out.record(), task.get());
        refused = a != ARBOR_OK;
        if (auto e = unexplained(a, "apply on " + what); !e.empty())
            return e;
        if (a == ARBOR_ERROR_UNSUPPORTED || (a != ARBOR_OK && std::min({nx, ny, nz}) < 3))
            return ""; // refused (a volume thinner than a kernel, say), and said why
        if (a != ARBOR_OK)
            return "apply on " + what + " returned " + status_text(a) + ": " + message();
        if (!out.all_finite())
            return "apply on " + what + " wrote values that are not finite";
        return cleared("apply on " + what);
    }

    // ---- simplifier -----------------------------------------------------------

    void simplifier_checks()
    {
        const auto &t = *static_cast<const arbor_simplifier_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_SIMPLIFIER));
        FixtureTree tree;
        run("simplifier invalid arguments", [&] {
            const arbor_measure_rows rows = tree.rows();
            double out[3];
            if (auto e = expect(t.prepare(p_, nullptr), ARBOR_ERROR_INVALID_ARGUMENT, "prepare(NULL)"); !e.empty())
                return e;
            if (auto e = expect(t.importance(p_, nullptr, out), ARBOR_ERROR_INVALID_ARGUMENT,
                                "importance(NULL rows)"); !e.empty())
                return e;
            return expect(t.importance(p_, &rows, nullptr), ARBOR_ERROR_INVALID_ARGUMENT,
                          "importance(NULL out)");
        });
        run("simplifier on host measures", [&] {
            const arbor_measure_rows schema = tree.schema();
            if (auto e = expect(t.prepare(p_, &schema), ARBOR_OK, "prepare with the host's measures"); !e.empty())
                return e;
            const arbor_measure_rows rows = tree.rows();
            double out[3] = {-1, -1, -1};
            if (auto e = expect(t.importance(p_, &rows, out), ARBOR_OK, "importance"); !e.empty())
                return e;
            for (double v : out)
                if (!std::isfinite(v) || v < 0)
                    return std::string("importance is not a finite non-negative number");
            return cleared("importance");
        });
        // Batches as the host makes them (simplifier.h): one row (a
        // comparison of a tree with one branch below its root), rows of
        // branches far down a big tree, up to 4096 at once; each row's
        // importance its own.
        run("simplifier on one row", [&] {
            const FixtureTree two(2);
            for (uint32_t first : {0u, 1u})
                if (auto e = importances(t, two.rows(first, 1), first == 0 ? "the root's row alone" : "one branch alone");
                    !e.empty())
                    return e;
            return std::string();
        });
        run("simplifier on 4096 rows", [&] {
            const FixtureTree big(4097);
            return importances(t, big.rows(1, 4096), "4096 branches of a tree 6 levels deep");
        });
        run("simplifier rows are independent", [&] {
            const FixtureTree big(64);
            const arbor_measure_rows batch = big.rows(1, 63);
            std::vector<double> together(63, -1.0);
            if (auto e = expect(t.importance(p_, &batch, together.data()), ARBOR_OK, "importance of 63 rows");
                !e.empty())
                return e;
            for (uint32_t r = 0; r < 63; ++r) {
                const arbor_measure_rows one = big.rows(1 + r, 1);
                double alone = -1.0;
                if (auto e = expect(t.importance(p_, &one, &alone), ARBOR_OK, "importance of one row"); !e.empty())
                    return e;
                if (!(alone == together[r]) && !(std::isnan(alone) && std::isnan(together[r])))
                    return "the importance of row " + std::to_string(r) + " is " + number_text(together[r]) +
                           " among 63 rows but " + number_text(alone) +
                           " alone; it must depend on its own row only (simplifier.h)";
            }
            return std::string();
        });
    }

    // "" when every importance of `rows` is a finite number >= 0.
    std::string importances(const arbor_simplifier_v1 &t, const arbor_measure_rows &rows, const std::string &what)
    {
        std::vector<double> out(rows.row_count, std::nan(""));
        if (auto e = expect(t.importance(p_, &rows, out.data()), ARBOR_OK, "importance of " + what); !e.empty())
            return e;
        for (uint32_t r = 0; r < rows.row_count; ++r)
            if (!std::isfinite(out[r]) || out[r] < 0)
                return "importance of " + what + ": row " + std::to_string(r) + " got " + number_text(out[r]) +
                       ", not a finite number >= 0";
        return "";
    }

    // ---- depictor -------------------------------------------------------------

    void depictor_checks()
    {
        const auto &t = *static_cast<const arbor_depictor_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_DEPICTOR));
        FixtureTree tree;
        Task task;
        arbor_depiction_request request{};
        request.struct_size = sizeof(request);
        request.selected_branch = 1;
        request.tree = &tree.record();
        run("depictor invalid arguments", [&] {
            DepictionRecord out(3);
            FixtureImage image(16, 16);
            arbor_bool32 related = 0;
            if (auto e = expect(t.depict(p_, nullptr, &out.record(), task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "depict(NULL request)"); !e.empty())
                return e;
            if (auto e = expect(t.depict(p_, &request, nullptr, task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "depict(NULL output)"); !e.empty())
                return e;
            if (auto e = expect(t.related(p_, nullptr, 0, 0, &related), ARBOR_ERROR_INVALID_ARGUMENT,
                                "related(NULL tree)"); !e.empty())
                return e;
            if (auto e = expect(t.related(p_, &tree.record(), 7, 0, &related),
                                ARBOR_ERROR_INVALID_ARGUMENT, "related(branch out of range)"); !e.empty())
                return e;
            if (auto e = expect(t.related(p_, &tree.record(), 0, 1, nullptr),
                                ARBOR_ERROR_INVALID_ARGUMENT, "related(NULL out)"); !e.empty())
                return e;
            const arbor_status s = t.legend(p_, nullptr, &image.record(), task.get());
            if (s != ARBOR_ERROR_INVALID_ARGUMENT && s != ARBOR_ERROR_UNSUPPORTED)
                return "legend(NULL request) returned " + status_text(s);
            return std::string();
        });
        run("depictor on a small tree", [&] {
            DepictionRecord out(3);
            if (auto e = expect(t.depict(p_, &request, &out.record(), task.get()), ARBOR_OK, "depict");
                !e.empty())
                return e;
            if (auto e = depiction_problem(out.record()); !e.empty())
                return e;
            if (auto e = cleared("depict"); !e.empty())
                return e;
            for (uint32_t a = 0; a < 3; ++a)
                for (uint32_t b = 0; b < 3; ++b) {
                    arbor_bool32 r = 0;
                    if (auto e = expect(t.related(p_, &tree.record(), a, b, &r), ARBOR_OK, "related");
                        !e.empty())
                        return e;
                }
            FixtureImage image(64, 64);
            const arbor_status s = t.legend(p_, &request, &image.record(), task.get());
            if (s == ARBOR_OK && !image.all_in_unit_range())
                return std::string("legend pixels outside [0, 1]");
            if (s != ARBOR_OK && s != ARBOR_ERROR_UNSUPPORTED)
                return "legend returned " + status_text(s) + ": " + message();
            return unexplained(s, "legend");
        });
        run("depictor on a one-branch tree", [&] {
            const FixtureTree lone(1);
            for (const int32_t selected : {0, -1}) {
                arbor_depiction_request r = request;
                r.tree = &lone.record();
                r.selected_branch = selected;
                DepictionRecord out(1);
                const std::string call = "depict(the root alone, selected " + std::to_string(selected) + ")";
                if (auto e = expect(t.depict(p_, &r, &out.record(), task.get()), ARBOR_OK, call); !e.empty())
                    return e;
                if (auto e = depiction_problem(out.record()); !e.empty())
                    return call + ": " + e;
                arbor_bool32 related = 0;
                if (auto e = expect(t.related(p_, &lone.record(), 0, 0, &related), ARBOR_OK, "related(0, 0)");
                    !e.empty())
                    return e;
            }
            return std::string();
        });
        run("depictor cancelled mid-call", [&] {
            const FixtureTree big(20000);
            arbor_depiction_request r = request;
            r.tree = &big.record();
            r.selected_branch = 7;
            DepictionRecord out(20000);
            return cancellation("depict(20000 branches)",
                                [&](arbor_task *task) { return t.depict(p_, &r, &out.record(), task); });
        });
    }

    // "" when every branch's opacities and saturation lie in [0, 1] and its
    // hue in [0, 360) (or NaN: none).
    static std::string depiction_problem(const arbor_depiction &d)
    {
        for (uint32_t b = 0; b < d.branch_count; ++b) {
            const float values[] = {d.opacity_at_saddle[b], d.opacity_at_extremum[b], d.saturation[b]};
            for (float v : values)
                if (!(v >= 0.0f && v <= 1.0f))
                    return "branch " + std::to_string(b) + ": opacity or saturation outside [0, 1]";
            if (!std::isnan(d.hue[b]) && !(d.hue[b] >= 0.0f && d.hue[b] < 360.0f))
                return "branch " + std::to_string(b) + ": hue outside [0, 360)";
        }
        return "";
    }

    // ---- transfer-function generator ----------------------------------------

    void tf_checks()
    {
        const auto &t = *static_cast<const arbor_tf_generator_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_TF_GENERATOR));
        FixtureTree tree;
        FixtureVolume volume(ARBOR_VOXEL_U8, 8);
        Task task;
        arbor_tf_request request{};
        request.struct_size = sizeof(request);
        request.tree = &tree.record();
        request.volume = &volume.record();
        request.value_range[0] = 0;
        request.value_range[1] = 99;
        request.min_spacing = 1.0;
        run("tf-generator invalid arguments", [&] {
            FixtureTfSet out(3, 16);
            if (auto e = expect(t.generate(p_, nullptr, &out.record(), task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "generate(NULL request)"); !e.empty())
                return e;
            return expect(t.generate(p_, &request, nullptr, task.get()), ARBOR_ERROR_INVALID_ARGUMENT,
                          "generate(NULL output)");
        });
        run("tf-generator on a small tree", [&] {
            if (auto e = generate_once(t, task, request, "generate"); !e.empty())
                return e;
            return cleared("generate");
        });
        run("tf-generator on a one-branch tree", [&] {
            const FixtureTree lone(1);
            arbor_tf_request r = request;
            r.tree = &lone.record();
            r.value_range[1] = 1000; // the lone root's values
            return generate_once(t, task, r, "generate(the root alone)");
        });
        run("tf-generator without a volume", [&] {
            arbor_tf_request r = request;
            r.volume = nullptr; // allowed: the host regenerates from the tree alone
            FixtureTfSet out(3, 16);
            const arbor_status s = t.generate(p_, &r, &out.record(), task.get());
            if (s == ARBOR_ERROR_INVALID_ARGUMENT) // a generator that needs the volume (transfer_function.h)
                return unexplained(s, "generate(NULL volume)");
            return generate_once(t, task, r, "generate(NULL volume)");
        });
        run("tf-generator with a depiction", [&] {
            DepictionRecord depiction(3);
            arbor_depiction &d = depiction.record();
            const arbor_branch_role roles[] = {ARBOR_ROLE_PARENT, ARBOR_ROLE_SELECTED, ARBOR_ROLE_SIBLING};
            for (uint32_t b = 0; b < 3; ++b) {
                d.role[b] = roles[b];
                d.opacity_at_saddle[b] = 0.25f * static_cast<float>(b);
                d.opacity_at_extremum[b] = 1.0f - 0.25f * static_cast<float>(b);
                d.hue[b] = 120.0f * static_cast<float>(b);
                d.saturation[b] = 0.5f;
            }
            arbor_tf_request r = request;
            r.depiction = &d;
            return generate_once(t, task, r, "generate(with a depiction)");
        });
        run("tf-generator on every voxel type", [&] {
            for (arbor_voxel_type vt = ARBOR_VOXEL_U8; vt <= ARBOR_VOXEL_F64; ++vt)
                for (const int64_t n : {8, 1}) {
                    FixtureVolume v(vt, n);
                    const auto [lo, hi] = v.value_range();
                    arbor_tf_request r = request;
                    r.volume = &v.record();
                    r.value_range[0] = std::min(lo, 0.0);
                    r.value_range[1] = std::max(hi, 100.0);
                    const std::string call = "generate(" + std::to_string(n) + "^3 " + arbor_voxel_type_name(vt) + ")";
                    if (auto e = generate_once(t, task, r, call); !e.empty())
                        return e;
                }
            return std::string();
        });
        run("tf-generator cancelled mid-call", [&] {
            const FixtureTree big(20000);
            FixtureVolume v(ARBOR_VOXEL_U8, 36); // a voxel for every vertex of the tree
            arbor_tf_request r = request;
            r.tree = &big.record();
            r.volume = &v.record();
            r.value_range[1] = 1000;
            FixtureTfSet out(20000, 256);
            return cancellation("generate(20000 branches)",
                                [&](arbor_task *task) { return t.generate(p_, &r, &out.record(), task); });
        });
    }

    // One generate on `request` (lookup tables of 16): "" when it worked and
    // its output is sane.
    std::string generate_once(const arbor_tf_generator_v1 &t, Task &task, const arbor_tf_request &request,
                              const std::string &call)
    {
        const uint32_t n = request.tree->branch_count, size = 16;
        FixtureTfSet out(n, size);
        if (auto e = expect(t.generate(p_, &request, &out.record(), task.get()), ARBOR_OK, call); !e.empty())
            return e;
        const arbor_tf_set &s = out.record();
        for (uint32_t i = 0; i < n * size * 4; ++i)
            if (!(s.lut[i] >= 0.0f && s.lut[i] <= 1.0f))
                return call + ": lookup table value outside [0, 1] (branch " + std::to_string(i / (size * 4)) + ")";
        for (uint32_t b = 0; b < n; ++b) {
            if (!std::isfinite(s.domain[2 * b]) || !std::isfinite(s.domain[2 * b + 1]))
                return call + ": the domain of branch " + std::to_string(b) + " is not finite";
            if (s.point_offsets[b + 1] < s.point_offsets[b])
                return call + ": point_offsets decrease";
        }
        if (s.point_offsets[n] > 0 && !s.points)
            return call + ": point_offsets count points but points is NULL";
        return "";
    }

    // ---- renderer -----------------------------------------------------------

    void renderer_checks()
    {
        const auto &t = *static_cast<const arbor_renderer_v1 *>(p_->get_interface(p_, ARBOR_INTERFACE_RENDERER));
        FixtureVolume volume(ARBOR_VOXEL_U8, 8);
        FixtureTfSet tfs(1, 16);
        tfs.fill_ramp(0, 99);
        const arbor_camera camera = fixture_camera(8);
        Task task;
        arbor_render_request request{};
        request.struct_size = sizeof(request);
        request.volume = &volume.record();
        request.labels = nullptr;
        request.transfer_functions = &tfs.record();
        request.camera = &camera;
        request.background[3] = 1.0f;
        request.volume_revision = 1;
        run("renderer invalid arguments", [&] {
            FixtureImage image(16, 16);
            if (auto e = expect(t.render(p_, nullptr, &image.record(), task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "render(NULL request)"); !e.empty())
                return e;
            if (auto e = expect(t.render(p_, &request, nullptr, task.get()), ARBOR_ERROR_INVALID_ARGUMENT,
                                "render(NULL image)"); !e.empty())
                return e;
            arbor_render_request no_volume = request;
            no_volume.volume = nullptr;
            return expect(t.render(p_, &no_volume, &image.record(), task.get()),
                          ARBOR_ERROR_INVALID_ARGUMENT, "render without a volume");
        });
        run("renderer on a small volume", [&] {
            FixtureImage image(16, 16);
            if (auto e = expect(t.render(p_, &request, &image.record(), task.get()), ARBOR_OK, "render");
                !e.empty())
                return e;
            return image.all_in_unit_range() ? std::string() : std::string("pixels outside [0, 1]");
        });
        // Other volumes than the one above: each with its own revision, as
        // the host gives them (renderers may keep a volume by revision).
        uint64_t revision = 1;
        const auto render_once = [&](arbor_voxel_type vt, int64_t n, const std::string &call) {
            FixtureVolume v(vt, n);
            const auto [lo, hi] = v.value_range();
            FixtureTfSet functions(1, 16);
            functions.fill_ramp(lo, hi > lo ? hi : lo + 1);
            const arbor_camera c = fixture_camera(n);
            arbor_render_request r = request;
            r.volume = &v.record();
            r.transfer_functions = &functions.record();
            r.camera = &c;
            r.volume_revision = ++revision;
            FixtureImage image(16, 16);
            const arbor_status s = t.render(p_, &r, &image.record(), task.get());
            if (auto e = unexplained(s, call); !e.empty())
                return e;
            if (s == ARBOR_ERROR_UNSUPPORTED || (s != ARBOR_OK && n < 2))
                return std::string(); // refused, and said why
            if (s != ARBOR_OK)
                return call + " returned " + status_text(s) + ": " + message();
            return image.all_in_unit_range() ? std::string() : call + ": pixels outside [0, 1]";
        };
        run("renderer on tiny volumes", [&] {
            for (const int64_t n : {1, 2})
                if (auto e = render_once(ARBOR_VOXEL_U8, n, "render(" + std::to_string(n) + "^3 u8)"); !e.empty())
                    return e;
            return std::string();
        });
        run("renderer on every voxel type", [&] {
            for (arbor_voxel_type vt = ARBOR_VOXEL_U8; vt <= ARBOR_VOXEL_F64; ++vt)
                if (auto e = render_once(vt, 8, std::string("render(8^3 ") + arbor_voxel_type_name(vt) + ")");
                    !e.empty())
                    return e;
            return std::string();
        });
        run("renderer cancelled mid-call", [&] {
            FixtureVolume v(ARBOR_VOXEL_U8, 96);
            const arbor_camera c = fixture_camera(96);
            arbor_render_request r = request;
            r.volume = &v.record();
            r.camera = &c;
            r.volume_revision = ++revision;
            FixtureImage image(256, 256);
            return cancellation("render(96^3 u8 into 256x256)",
                                [&](arbor_task *task) { return t.render(p_, &r, &image.record(), task); });
        });
        const auto *t2 = static_cast<const arbor_renderer_v2 *>(p_->get_interface(p_, ARBOR_INTERFACE_RENDERER_2));
        if (!t2)
            return;
        arbor_render_request_v2 r2{};
        r2.struct_size = sizeof r2;
        r2.volume = request.volume;
        r2.transfer_functions = request.transfer_functions;
        r2.camera = request.camera;
        r2.background[3] = 1.0f;
        r2.volume_revision = r2.labels_revision = r2.transfer_functions_revision = 1;
        r2.frame_width = r2.frame_height = 16;
        r2.region_width = r2.region_height = 16;
        run("renderer/2 interface", [&] {
            return t2->struct_size >= ARBOR_MIN_SIZE(arbor_renderer_v2) && t2->render ? std::string()
                                                                             : std::string("table incomplete");
        });
        run("renderer/2 invalid regions and passes", [&] {
            FixtureImage image(16, 16);
            arbor_render_request_v2 outside = r2;
            outside.region_x = 8; // 8 + 16 > 16
            if (auto e = expect(t2->render(p_, &outside, &image.record(), task.get()), ARBOR_ERROR_INVALID_ARGUMENT,
                                "render(a region beyond the frame)");
                !e.empty())
                return e;
            arbor_render_request_v2 mismatched = r2;
            mismatched.frame_width = mismatched.frame_height = 32;
            mismatched.region_width = 8; // the image is 16 wide
            if (auto e = expect(t2->render(p_, &mismatched, &image.record(), task.get()),
                                ARBOR_ERROR_INVALID_ARGUMENT, "render(a region unlike the image)");
                !e.empty())
                return e;
            arbor_render_request_v2 unknown = r2;
            unknown.pass = 77;
            return expect(t2->render(p_, &unknown, &image.record(), task.get()), ARBOR_ERROR_INVALID_ARGUMENT,
                          "render(pass 77)");
        });
        run("renderer/2 tiles join into the frame", [&] {
            FixtureImage whole(16, 16);
            // FULL only: a coarse pass may choose its rays anew at each
            // frame (renderer.h), and the whole frame here is one frame,
            // its tiles another.
            for (const arbor_render_pass pass : {ARBOR_RENDER_PASS_FULL}) {
                arbor_render_request_v2 r = r2;
                r.pass = pass;
                if (auto e = expect(t2->render(p_, &r, &whole.record(), task.get()), ARBOR_OK, "render(whole frame)");
                    !e.empty())
                    return e;
                if (!whole.all_in_unit_range())
                    return std::string("pixels outside [0, 1]");
                for (uint32_t half = 0; half < 2; ++half) {
                    FixtureImage tile(16, 8);
                    r.region_y = 8 * half;
                    r.region_height = 8;
                    if (auto e = expect(t2->render(p_, &r, &tile.record(), task.get()), ARBOR_OK, "render(a tile)");
                        !e.empty())
                        return e;
                    for (std::size_t i = 0; i < 16 * 8 * 4; ++i)
                        if (std::fabs(tile.rgba()[i] - whole.rgba()[16 * 8 * 4 * half + i]) > 1e-5f)
                            return std::string("a tile's pixels differ from the whole frame's there (pass ") +
                                   std::to_string(pass) + ")";
                }
            }
            return std::string();
        });
    }

    const arbor_plugin_entry &entry_;
    const arbor_host *host_;
    const arbor_plugin_descriptor &d_;
    std::string id_;
    fs::path scratch_;
    CheckSink &sink_;
    arbor_plugin *p_ = nullptr;
    const arbor_params_v1 *params_ = nullptr;
};

} // namespace

void check_entry(const arbor_plugin_entry &entry, const arbor_host *host, CheckSink &sink)
{
    sink.begin("", "entry");
    std::string problem;
    if (entry.plugin_descriptor(entry.plugin_count()) != nullptr)
        problem = "plugin_descriptor(count) must return NULL";
    arbor_plugin *p = nullptr;
    if (problem.empty() && entry.create_plugin(host, nullptr, &p) == ARBOR_OK)
        problem = "create_plugin accepted a NULL id";
    sink.result("", "entry", problem.empty(), problem);
}

void check_plugin(const arbor_plugin_entry &entry, const arbor_host *host,
                  const arbor_plugin_descriptor &descriptor, const fs::path &scratch, CheckSink &sink)
{
    PluginChecks(entry, host, descriptor, scratch, sink).run_all();
}

} // namespace arbor
