// `arbor pacs`: query and retrieve from archives.
//   nodes [add|remove]   the configured nodes (pacs-nodes.json)
//   echo NODE            verify the connection (C-ECHO, or a QIDO-RS search)
//   find NODE            studies or series, filtered, as a table or JSON
//   get NODE --series    retrieve a series by C-GET (or WADO-RS)
//   move NODE --series   retrieve a series by C-MOVE to our storage SCP
// NODE: a configured name, AET@host:port, or a DICOMweb URL.
#include "commands.hpp"
#include "table_text.hpp"
#include "usage_error.hpp"

#include "dicom/pacs_input.hpp"
#include "dicom/series_retrieval.hpp"
#include "dicom/value_text.hpp"

#include "core/stopwatch.hpp"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <iostream>
#include <memory>
#include <regex>

namespace arbor::cli {

namespace {

using dicom::PacsNode;

// What every subcommand that talks to a node shares.
struct NodeFlags {
    std::string node, our_aet;
    int our_port = 0, timeout_s = 30;
    CLI::Option *our_aet_option = nullptr, *our_port_option = nullptr;

    void add_to(CLI::App *c)
    {
        c->add_option("node", node, "A configured node (`arbor pacs nodes`), AET@host:port, or a DICOMweb URL")
            ->required();
        our_aet_option = c->add_option("--our-aet", our_aet, "Our AE title (default: the node's, else ARBOR)");
        our_port_option = c->add_option("--our-port", our_port, "Our storage port, where C-MOVE sends images")
                              ->check(CLI::Range(1, 65535));
        c->add_option("--timeout", timeout_s, "Seconds to wait for the archive at each step")
            ->default_val(30)
            ->check(CLI::Range(1, 3600));
    }

    PacsNode resolve() const
    {
        PacsNode n = dicom::find_node(node, dicom::read_nodes(dicom::default_nodes_file()));
        if (our_aet_option->count())
            n.our_aet = our_aet;
        if (our_port_option->count())
            n.our_port = static_cast<uint16_t>(our_port);
        return n;
    }

    dicom::PacsOptions options(Context &context) const { return {timeout_s, context.stop.get_token()}; }
};

std::string count_text(int n)
{
    return n < 0 ? "-" : std::to_string(n);
}

nlohmann::json count_json(int n)
{
    return n < 0 ? nlohmann::json(nullptr) : nlohmann::json(n);
}

void add_nodes_commands(CLI::App *pacs, Context &context)
{
    CLI::App *nodes = pacs->add_subcommand("nodes", "List the configured nodes (or add and remove them)");
    auto json = std::make_shared<bool>(false);
    nodes->add_flag("--json", *json, "Print JSON instead of a table");
    context.add_command(nodes, [json]() {
        const auto file = dicom::default_nodes_file();
        const auto list = dicom::read_nodes(file);
        if (*json) {
            nlohmann::json j = {{"file", file.string()}, {"nodes", nlohmann::json::array()}};
            for (const PacsNode &n : list) {
                nlohmann::json e = {{"name", n.name},
                                    {"kind", n.kind == PacsNode::Kind::Dimse ? "dimse" : "dicomweb"},
                                    {"address", n.describe()},
                                    {"authentication", n.authentication()}};
                if (n.kind == PacsNode::Kind::Dimse) {
                    e["our_aet"] = n.our_aet;
                    e["our_port"] = n.our_port ? nlohmann::json(n.our_port) : nlohmann::json(nullptr);
                }
                j["nodes"].push_back(e);
            }
            std::cout << j.dump(2) << "\n";
            return 0;
        }
        std::printf("nodes from %s\n", file.c_str());
        if (list.empty()) {
            std::printf("(none: add one with `arbor pacs nodes add NAME AET@host:port` or a DICOMweb URL)\n");
            return 0;
        }
        std::printf("%-16s %-9s %-40s %-18s %s\n", "NAME", "KIND", "ADDRESS", "OUR AE (PORT)", "AUTHENTICATION");
        for (const PacsNode &n : list) {
            const bool dimse = n.kind == PacsNode::Kind::Dimse;
            const std::string ours = dimse ? n.our_aet + (n.our_port ? " (" + std::to_string(n.our_port) + ")" : "")
                                           : std::string("-");
            std::printf("%-16s %-9s %-40s %-18s %s\n", n.name.c_str(), dimse ? "dimse" : "dicomweb",
                        n.describe().c_str(), ours.c_str(), n.authentication().c_str());
        }
        return 0;
    });

    CLI::App *add = nodes->add_subcommand("add", "Add a node, or replace the one of that name");
    struct AddFlags {
        std::string name, address, our_aet, user, password_env, token_env;
        int our_port = 0;
    };
    auto a = std::make_shared<AddFlags>();
    add->add_option("name", a->name, "The node's name")->required();
    add->add_option("address", a->address, "AET@host:port, or the DICOMweb root URL")->required();
    add->add_option("--our-aet", a->our_aet, "Our AE title for this node (default ARBOR)");
    add->add_option("--our-port", a->our_port, "Our storage port for C-MOVE")->check(CLI::Range(1, 65535));
    add->add_option("--user", a->user, "DICOMweb: user for HTTP basic authentication");
    add->add_option("--password-env", a->password_env,
                    "DICOMweb: the environment variable that holds the password (kept out of the file)");
    add->add_option("--token-env", a->token_env, "DICOMweb: the environment variable that holds a bearer token");
    context.add_command(add, [a]() {
        const auto file = dicom::default_nodes_file();
        auto list = dicom::read_nodes(file);
        if (a->name.empty() || dicom::looks_inline(a->name) || a->name.find('/') != std::string::npos)
            throw UsageError("a node name may not be empty or contain '@', ':' or '/'");
        PacsNode n = dicom::parse_inline_node(a->address);
        n.secret = {};
        n.name = a->name;
        if (!a->our_aet.empty())
            n.our_aet = a->our_aet;
        n.our_port = static_cast<uint16_t>(a->our_port);
        n.secret.user = a->user;
        n.secret.password_env = a->password_env;
        n.secret.token_env = a->token_env;
        std::erase_if(list, [&](const PacsNode &o) { return o.name == n.name; });
        list.push_back(n);
        dicom::write_nodes(file, list);
        std::printf("added %s (%s) to %s\n", n.name.c_str(), n.describe().c_str(), file.c_str());
        return 0;
    });

    CLI::App *remove = nodes->add_subcommand("remove", "Remove a node");
    auto name = std::make_shared<std::string>();
    remove->add_option("name", *name, "The node's name")->required();
    context.add_command(remove, [name]() {
        const auto file = dicom::default_nodes_file();
        auto list = dicom::read_nodes(file);
        if (std::erase_if(list, [&](const PacsNode &o) { return o.name == *name; }) == 0)
            throw std::invalid_argument("no node named '" + *name + "' in " + file.string());
        dicom::write_nodes(file, list);
        std::printf("removed %s from %s\n", name->c_str(), file.c_str());
        return 0;
    });
}

void add_echo_command(CLI::App *pacs, Context &context)
{
    CLI::App *echo = pacs->add_subcommand("echo", "Verify the connection to a node (C-ECHO; DICOMweb: a search)");
    auto flags = std::make_shared<NodeFlags>();
    flags->add_to(echo);
    context.add_command(echo, [&context, flags]() {
        const PacsNode node = flags->resolve();
        const double ms = dicom::connect(node, flags->options(context))->echo();
        std::printf("%s answered %s in %.0f ms\n", node.describe().c_str(),
                    node.kind == PacsNode::Kind::Dimse ? "C-ECHO" : "a QIDO-RS search", ms);
        return 0;
    });
}

void add_find_command(CLI::App *pacs, Context &context)
{
    CLI::App *find = pacs->add_subcommand("find", "Search a node's studies or series");
    struct FindFlags {
        NodeFlags node;
        dicom::PacsQuery query;
        std::string level = "series";
        bool json = false;
    };
    auto f = std::make_shared<FindFlags>();
    f->node.add_to(find);
    find->add_option("--level", f->level, "study or series")->check(CLI::IsMember({"study", "series"}))
        ->default_val("series");
    find->add_option("--patient", f->query.patient, "Patient's name; * and ? are wildcards (e.g. 'DOE*')");
    find->add_option("--study-date", f->query.study_date, "YYYYMMDD, or a range YYYYMMDD-YYYYMMDD (either end open)");
    find->add_option("--modality", f->query.modality, "CT, MR, PT...");
    find->add_option("--accession", f->query.accession, "Accession number");
    find->add_option("--study", f->query.study_uid, "Only this study (Study Instance UID)");
    find->add_flag("--json", f->json, "Print JSON instead of a table");
    context.add_command(find, [&context, f]() {
        static const std::regex date(R"(\d{8}|\d{8}-|-\d{8}|\d{8}-\d{8})");
        if (!f->query.study_date.empty() && !std::regex_match(f->query.study_date, date))
            throw UsageError("--study-date: write YYYYMMDD or a range YYYYMMDD-YYYYMMDD, not '" +
                             f->query.study_date + "'");
        const PacsNode node = f->node.resolve();
        const auto client = dicom::connect(node, f->node.options(context));
        if (f->level == "study") {
            const auto rows = client->find_studies(f->query);
            if (f->json) {
                nlohmann::json j = nlohmann::json::array();
                for (const auto &r : rows)
                    j.push_back({{"patient_name", r.patient_name}, {"patient_id", r.patient_id},
                                 {"study_uid", r.study_uid}, {"study_date", r.study_date},
                                 {"study_description", r.study_description}, {"accession", r.accession},
                                 {"modalities", r.modalities}, {"series", count_json(r.series_count)},
                                 {"images", count_json(r.image_count)}});
                std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
                return 0;
            }
            std::printf("%-24s %-12s %-10s %-28s %-8s %6s %6s\n", "PATIENT", "ID", "DATE", "DESCRIPTION", "MOD",
                        "SERIES", "IMAGES");
            for (const auto &r : rows) {
                std::printf("%-24s %-12s %-10s %-28s %-8s %6s %6s\n", clip(r.patient_name, 24).c_str(),
                            clip(r.patient_id, 12).c_str(), dicom::display_date(r.study_date).c_str(),
                            clip(r.study_description, 28).c_str(), clip(r.modalities, 8).c_str(),
                            count_text(r.series_count).c_str(), count_text(r.image_count).c_str());
                std::printf("    study UID %s\n", r.study_uid.c_str());
            }
            if (rows.empty())
                std::printf("(no studies match)\n");
            return 0;
        }
        const auto rows = client->find_series(f->query);
        if (f->json) {
            nlohmann::json j = nlohmann::json::array();
            for (const auto &r : rows)
                j.push_back({{"patient_name", r.patient_name}, {"patient_id", r.patient_id},
                             {"study_uid", r.study_uid}, {"study_date", r.study_date},
                             {"study_description", r.study_description}, {"series_uid", r.series_uid},
                             {"series_number", r.series_number}, {"modality", r.modality},
                             {"description", r.description}, {"images", count_json(r.image_count)}});
            std::cout << j.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
            return 0;
        }
        std::printf("%-22s %-10s %-22s %-6s %-4s %-24s %6s\n", "PATIENT", "DATE", "STUDY", "SERIES", "MOD",
                    "DESCRIPTION", "IMAGES");
        for (const auto &r : rows) {
            std::printf("%-22s %-10s %-22s %-6s %-4s %-24s %6s\n", clip(r.patient_name, 22).c_str(),
                        dicom::display_date(r.study_date).c_str(), clip(r.study_description, 22).c_str(),
                        clip(r.series_number, 6).c_str(), clip(r.modality, 4).c_str(),
                        clip(r.description, 24).c_str(), count_text(r.image_count).c_str());
            std::printf("    series UID %s\n", r.series_uid.c_str());
        }
        if (rows.empty())
            std::printf("(no series match)\n");
        return 0;
    });
}

void add_retrieve_command(CLI::App *pacs, Context &context, dicom::RetrieveMethod method)
{
    const bool get = method == dicom::RetrieveMethod::Get;
    CLI::App *c = pacs->add_subcommand(
        get ? "get" : "move",
        get ? "Retrieve a series by C-GET (DICOMweb: WADO-RS) into a folder"
            : "Retrieve a series by C-MOVE: the archive sends it to our storage SCP on --our-port");
    struct RetrieveFlags {
        NodeFlags node;
        std::string series, output;
    };
    auto f = std::make_shared<RetrieveFlags>();
    f->node.add_to(c);
    c->add_option("--series", f->series, "The Series Instance UID (from `arbor pacs find`)")->required();
    c->add_option("-o,--output", f->output, "Folder for the images (default: ./SERIES_UID)");
    context.add_command(c, [&context, f, method]() {
        const PacsNode node = f->node.resolve();
        const std::string what = node.kind == PacsNode::Kind::DicomWeb ? "WADO-RS"
                                 : method == dicom::RetrieveMethod::Get ? "C-GET"
                                                                        : "C-MOVE";
        const std::filesystem::path folder = f->output.empty() ? f->series : f->output;
        Stopwatch watch;
        const auto client = dicom::connect(node, f->node.options(context));
        const auto progress = [&context](const dicom::RetrievalProgress &p) {
            const std::string of = p.expected >= 0 ? " of " + std::to_string(p.expected) : "";
            context.progress.report("retrieving image " + std::to_string(p.received) + of,
                                    p.expected > 0 ? double(p.received) / p.expected : 0.0);
            if (p.received > 0)
                log_message(ARBOR_LOG_DEBUG, "", "received image " + std::to_string(p.received) + of);
        };
        dicom::Retrieval r;
        try {
            r = dicom::retrieve_series(*client, node, f->series, method, folder, progress);
        } catch (...) {
            context.progress.finish();
            throw;
        }
        context.progress.finish();
        std::printf("retrieved %d image(s) of series %s from %s by %s in %.1f s into %s\n", r.received,
                    f->series.c_str(), node.describe().c_str(), what.c_str(), watch.lap(), r.folder.c_str());
        return 0;
    });
}

} // namespace

void add_pacs_command(CLI::App &app, Context &context)
{
    CLI::App *pacs = app.add_subcommand(
        "pacs", "Query and retrieve from a PACS (DICOM networking or DICOMweb); any command also reads "
                "pacs://NODE/SERIES_UID");
    pacs->require_subcommand(1);
    add_nodes_commands(pacs, context);
    add_echo_command(pacs, context);
    add_find_command(pacs, context);
    add_retrieve_command(pacs, context, dicom::RetrieveMethod::Get);
    add_retrieve_command(pacs, context, dicom::RetrieveMethod::Move);
}

} // namespace arbor::cli
