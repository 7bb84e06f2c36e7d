#include "conformance_checks.hpp"

#include "conformance_fixtures.hpp"
#include "descriptor_rules.hpp"
#include "host_services.hpp"
#include "tf_generation.hpp"

#include <cmath>
#include <cstring>
#include <fstream>
#include <functional>
#include <sstream>

namespace arbor {

namespace fs = std::filesystem;

namespace {

// A check body returns "" when it passed, otherwise the first problem.
using Body = std::function<std::string()>;

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
        sink_.result(id_, name, problem.empty(), problem);
        return problem.empty();
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
            return (c < 0 || c > 100) ? std::string("confidence outside [0, 100]") : std::string();
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
                FixtureVolume in(vt, 8);
                arbor_voxel_type out_type = 0;
                const arbor_status s = t.output_type(p_, &in.record(), &out_type);
                if (s == ARBOR_ERROR_UNSUPPORTED)
                    continue;
                if (s != ARBOR_OK)
                    return std::string("output_type(") + arbor_voxel_type_name(vt) + ") returned " +
                           status_text(s);
                if (arbor_voxel_size(out_type) == 0)
                    return std::string("output_type(") + arbor_voxel_type_name(vt) +
                           ") gave an unknown type";
                FixtureVolume out(out_type, 8);
                const arbor_status a = t.apply(p_, &in.record(), &out.record(), task.get());
                if (a == ARBOR_ERROR_UNSUPPORTED)
                    continue;
                if (a != ARBOR_OK)
                    return std::string("apply on ") + arbor_voxel_type_name(vt) + " returned " +
                           status_text(a) + ": " + message();
                ++accepted;
            }
            return accepted ? std::string() : std::string("accepted no voxel type at all");
        });
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
            return std::string();
        });
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
            const arbor_depiction &d = out.record();
            for (uint32_t b = 0; b < 3; ++b) {
                const float values[] = {d.opacity_at_saddle[b], d.opacity_at_extremum[b], d.saturation[b]};
                for (float v : values)
                    if (!(v >= 0.0f && v <= 1.0f))
                        return std::string("opacity or saturation outside [0, 1]");
                if (!std::isnan(d.hue[b]) && !(d.hue[b] >= 0.0f && d.hue[b] < 360.0f))
                    return std::string("hue outside [0, 360)");
            }
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
            return std::string();
        });
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
            FixtureTfSet out(3, 16);
            if (auto e = expect(t.generate(p_, &request, &out.record(), task.get()), ARBOR_OK, "generate");
                !e.empty())
                return e;
            const arbor_tf_set &s = out.record();
            for (uint32_t i = 0; i < 3 * 16 * 4; ++i)
                if (!(s.lut[i] >= 0.0f && s.lut[i] <= 1.0f))
                    return std::string("lookup table value outside [0, 1]");
            for (uint32_t b = 0; b < 3; ++b) {
                if (!std::isfinite(s.domain[2 * b]) || !std::isfinite(s.domain[2 * b + 1]))
                    return std::string("domain is not finite");
                if (s.point_offsets[b + 1] < s.point_offsets[b])
                    return std::string("point_offsets decrease");
            }
            if (s.point_offsets[3] > 0 && !s.points)
                return std::string("point_offsets count points but points is NULL");
            return std::string();
        });
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
