// The DICOMweb side of PacsClient on libcurl: QIDO-RS searches
// (application/dicom+json), WADO-RS series retrieve (multipart/related of
// application/dicom, transfer-syntax=* so the archive sends what it holds),
// HTTP basic or bearer authentication.
#include "dicom/multipart_stream.hpp"
#include "dicom/pacs_client.hpp"
#include "dicom/value_text.hpp"

#include <curl/curl.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <fstream>
#include <mutex>

namespace arbor::dicom {

namespace {

using Kind = PacsError::Kind;
using nlohmann::json;

void curl_ready()
{
    static std::once_flag once;
    std::call_once(once, [] { curl_global_init(CURL_GLOBAL_DEFAULT); });
}

// One value of a DICOM JSON attribute, as text ("" when absent).
std::string value_of(const json &object, const char *tag)
{
    if (!object.is_object() || !object.contains(tag))
        return {};
    const json &a = object.at(tag);
    if (!a.is_object() || !a.contains("Value") || !a.at("Value").is_array())
        return {};
    std::string out;
    for (const json &v : a.at("Value")) {
        std::string one;
        if (v.is_string())
            one = v.get<std::string>();
        else if (v.is_number_integer())
            one = std::to_string(v.get<int64_t>());
        else if (v.is_number())
            one = std::to_string(v.get<double>());
        else if (v.is_object() && v.contains("Alphabetic") && v.at("Alphabetic").is_string())
            one = v.at("Alphabetic").get<std::string>();
        out += (out.empty() ? "" : "\\") + one;
    }
    return out;
}

int count_of(const json &object, const char *tag)
{
    return count_value(value_of(object, tag));
}

struct Transfer {
    std::string body;             // searches
    MultipartStream *parts = nullptr; // retrieves
    std::string content_type;
    const std::stop_token *stop = nullptr;
};

size_t on_body(char *data, size_t size, size_t count, void *user)
{
    auto *t = static_cast<Transfer *>(user);
    const std::size_t n = size * count;
    if (t->parts)
        t->parts->feed(data, n);
    else if (t->body.size() + n > (std::size_t{256} << 20))
        return 0; // a search answer this big is not one
    else
        t->body.append(data, n);
    return n;
}

size_t on_header(char *data, size_t size, size_t count, void *user)
{
    auto *t = static_cast<Transfer *>(user);
    const std::string line(data, size * count);
    if (line.size() > 13 && (line.compare(0, 13, "Content-Type:") == 0 || line.compare(0, 13, "content-type:") == 0))
        t->content_type = line.substr(13);
    return size * count;
}

int on_progress(void *user, curl_off_t, curl_off_t, curl_off_t, curl_off_t)
{
    const auto *t = static_cast<Transfer *>(user);
    return t->stop && t->stop->stop_requested() ? 1 : 0;
}

class DicomWebClient final : public PacsClient {
public:
    DicomWebClient(const PacsNode &node, const PacsOptions &options) : node_(node), options_(options)
    {
        curl_ready();
    }

    double echo() override
    {
        const auto start = std::chrono::steady_clock::now();
        search("/studies?limit=1");
        return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    }

    std::vector<StudyRow> find_studies(const PacsQuery &q) override
    {
        std::string query = "/studies?includefield=StudyDescription&includefield=NumberOfStudyRelatedSeries"
                            "&includefield=NumberOfStudyRelatedInstances&includefield=ModalitiesInStudy";
        add(query, "PatientName", q.patient);
        add(query, "StudyDate", q.study_date);
        add(query, "ModalitiesInStudy", q.modality);
        add(query, "AccessionNumber", q.accession);
        add(query, "StudyInstanceUID", q.study_uid);
        std::vector<StudyRow> rows;
        for (const json &o : search(query)) {
            StudyRow r;
            r.patient_name = display_person_name(value_of(o, "00100010"));
            r.patient_id = value_of(o, "00100020");
            r.study_uid = value_of(o, "0020000D");
            r.study_date = value_of(o, "00080020");
            r.study_description = value_of(o, "00081030");
            r.accession = value_of(o, "00080050");
            r.modalities = value_of(o, "00080061");
            r.series_count = count_of(o, "00201206");
            r.image_count = count_of(o, "00201208");
            rows.push_back(r);
        }
        return rows;
    }

    std::vector<SeriesRow> find_series(const PacsQuery &q) override
    {
        std::vector<SeriesRow> rows;
        for (const StudyRow &study : studies_to_search(q, [&] { return find_studies(q); })) {
            std::string query = "/studies/" + escape(study.study_uid) +
                                "/series?includefield=SeriesDescription&includefield=NumberOfSeriesRelatedInstances";
            add(query, "Modality", q.modality);
            for (const json &o : search(query)) {
                SeriesRow r;
                r.patient_name = study.patient_name;
                r.patient_id = study.patient_id;
                r.study_uid = study.study_uid;
                r.study_date = study.study_date;
                r.study_description = study.study_description;
                r.series_uid = value_of(o, "0020000E");
                r.series_number = value_of(o, "00200011");
                r.modality = value_of(o, "00080060");
                r.description = value_of(o, "0008103E");
                r.image_count = count_of(o, "00201209");
                rows.push_back(r);
            }
        }
        return rows;
    }

    void retrieve(const std::string &series_uid, RetrieveMethod, InstanceSink &sink) override
    {
        const json found = search("/series?SeriesInstanceUID=" + escape(series_uid) +
                                  "&includefield=NumberOfSeriesRelatedInstances");
        if (found.empty())
            throw PacsError(Kind::Failed, node_.describe() + " has no series " + series_uid);
        const std::string study_uid = value_of(found.front(), "0020000D");
        if (const int n = count_of(found.front(), "00201209"); n >= 0)
            sink.expect(n);
        std::string problem;
        int kept = 0;
        Transfer t;
        std::unique_ptr<MultipartStream> stream; // started once the headers named the boundary
        const auto on_part = [&](const std::string &, std::string &body) {
            const std::filesystem::path staged = sink.staging_file();
            std::ofstream out(staged, std::ios::binary);
            out.write(body.data(), static_cast<std::streamsize>(body.size()));
            out.close();
            std::string why;
            if (out && sink.commit(staged, why))
                ++kept;
            else if (problem.empty())
                problem = why.empty() ? "cannot write " + staged.string() : why;
        };
        const std::string url = node_.url + "/studies/" + escape(study_uid) + "/series/" + escape(series_uid);
        request(url, "multipart/related; type=\"application/dicom\"; transfer-syntax=*", t,
                [&](const char *data, std::size_t n) {
                    if (!stream) {
                        const std::string boundary = multipart_boundary(t.content_type);
                        if (boundary.empty())
                            return false;
                        stream = std::make_unique<MultipartStream>(boundary, on_part);
                    }
                    stream->feed(data, n);
                    return true;
                });
        if (!stream || !stream->finished())
            throw PacsError(Kind::Failed, node_.describe() + ": the WADO-RS answer ended before its last part (" +
                                              std::to_string(kept) + " image(s) arrived)");
        if (!problem.empty())
            throw PacsError(Kind::Failed, problem);
    }

private:
    std::string escape(const std::string &s) const
    {
        char *e = curl_easy_escape(nullptr, s.c_str(), static_cast<int>(s.size()));
        std::string out = e ? e : "";
        curl_free(e);
        return out;
    }

    void add(std::string &query, const char *key, const std::string &value) const
    {
        if (!value.empty())
            query += std::string("&") + key + "=" + escape(value);
    }

    json search(const std::string &path_and_query)
    {
        Transfer t;
        request(node_.url + path_and_query, "application/dicom+json", t, nullptr);
        if (t.body.empty())
            return json::array(); // 204 No Content: no matches
        try {
            json j = json::parse(t.body);
            if (!j.is_array())
                throw PacsError(Kind::Failed, node_.describe() + ": the QIDO-RS answer is not a list");
            return j;
        } catch (const json::exception &) {
            throw PacsError(Kind::Failed, node_.describe() + ": the QIDO-RS answer is not DICOM JSON");
        }
    }

    using Chunk = std::function<bool(const char *, std::size_t)>;

    struct Stream {
        Transfer *t;
        Chunk *chunk;
        bool failed = false;
    };

    static size_t on_stream(char *data, size_t size, size_t count, void *user)
    {
        auto *s = static_cast<Stream *>(user);
        if (!(*s->chunk)(data, size * count)) {
            s->failed = true;
            return 0;
        }
        return size * count;
    }

    void request(const std::string &url, const char *accept, Transfer &t, Chunk chunk)
    {
        CURL *curl = curl_easy_init();
        if (!curl)
            throw PacsError(Kind::Failed, "cannot start an HTTP request");
        std::unique_ptr<CURL, void (*)(CURL *)> owner(curl, curl_easy_cleanup);
        curl_slist *headers = curl_slist_append(nullptr, (std::string("Accept: ") + accept).c_str());
        std::unique_ptr<curl_slist, void (*)(curl_slist *)> header_owner(headers, curl_slist_free_all);
        t.stop = &options_.stop;
        Stream stream{&t, &chunk};
        curl_easy_setopt(curl, CURLOPT_URL, url.c_str());
        curl_easy_setopt(curl, CURLOPT_HTTPHEADER, headers);
        curl_easy_setopt(curl, CURLOPT_NOSIGNAL, 1L);
        curl_easy_setopt(curl, CURLOPT_FOLLOWLOCATION, 0L);
        curl_easy_setopt(curl, CURLOPT_CONNECTTIMEOUT, static_cast<long>(options_.timeout_s));
        // No byte for the timeout: the archive stopped sending.
        curl_easy_setopt(curl, CURLOPT_LOW_SPEED_LIMIT, 1L);
        curl_easy_setopt(curl, CURLOPT_LOW_SPEED_TIME, static_cast<long>(options_.timeout_s));
        curl_easy_setopt(curl, CURLOPT_HEADERFUNCTION, on_header);
        curl_easy_setopt(curl, CURLOPT_HEADERDATA, &t);
        if (chunk) {
            curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, on_stream);
            curl_easy_setopt(curl, CURLOPT_WRITEDATA, &stream);
        } else {
            curl_easy_setopt(curl, CURLOPT_WRITEFUNCTION, on_body);
            curl_easy_setopt(curl, CURLOPT_WRITEDATA, &t);
        }
        curl_easy_setopt(curl, CURLOPT_NOPROGRESS, 0L);
        curl_easy_setopt(curl, CURLOPT_XFERINFOFUNCTION, on_progress);
        curl_easy_setopt(curl, CURLOPT_XFERINFODATA, &t);
        curl_easy_setopt(curl, CURLOPT_FAILONERROR, 0L);
        if (!node_.secret.token.empty()) {
            curl_easy_setopt(curl, CURLOPT_HTTPAUTH, CURLAUTH_BEARER);
            curl_easy_setopt(curl, CURLOPT_XOAUTH2_BEARER, node_.secret.token.c_str());
        } else if (!node_.secret.user.empty()) {
            curl_easy_setopt(curl, CURLOPT_HTTPAUTH, CURLAUTH_BASIC);
            curl_easy_setopt(curl, CURLOPT_USERNAME, node_.secret.user.c_str());
            curl_easy_setopt(curl, CURLOPT_PASSWORD, node_.secret.password.c_str());
        }
        const CURLcode c = curl_easy_perform(curl);
        long status = 0;
        curl_easy_getinfo(curl, CURLINFO_RESPONSE_CODE, &status);
        const std::string where = node_.describe();
        if (c == CURLE_ABORTED_BY_CALLBACK)
            throw PacsError(Kind::Cancelled, "cancelled");
        if (c == CURLE_COULDNT_RESOLVE_HOST)
            throw PacsError(Kind::Unreachable, "cannot reach " + where + ": unknown host");
        if (c == CURLE_COULDNT_CONNECT)
            throw PacsError(Kind::Unreachable,
                            "cannot reach " + where + ": connection refused (is the archive running, is the port right?)");
        if (c == CURLE_OPERATION_TIMEDOUT)
            throw PacsError(Kind::Timeout, where + " did not answer within " + std::to_string(options_.timeout_s) +
                                               " s (--timeout)");
        if (c == CURLE_WRITE_ERROR && stream.failed)
            throw PacsError(Kind::Failed, where + ": the WADO-RS answer is not multipart (Content-Type" +
                                              t.content_type + ")");
        if (status == 401 || status == 403)
            throw PacsError(Kind::Rejected,
                            where + " refused " +
                                (node_.secret.user.empty() && node_.secret.token.empty()
                                     ? std::string("us: it needs credentials (user and password or token in the node "
                                                   "file)")
                                     : "our credentials (HTTP " + std::to_string(status) +
                                           "): check the user and password or token of the node"));
        if (c != CURLE_OK)
            throw PacsError(Kind::Failed, where + ": " + curl_easy_strerror(c));
        if (status == 404)
            throw PacsError(Kind::Failed, where + " has no such resource (HTTP 404): is the URL the DICOMweb root?");
        if (status >= 400)
            throw PacsError(Kind::Failed, where + " answered HTTP " + std::to_string(status));
    }

    const PacsNode node_;
    const PacsOptions options_;
};

} // namespace

std::unique_ptr<PacsClient> connect_dicomweb(const PacsNode &node, const PacsOptions &options)
{
    return std::make_unique<DicomWebClient>(node, options);
}

std::unique_ptr<PacsClient> connect(const PacsNode &node, const PacsOptions &options)
{
    if (node.kind == PacsNode::Kind::DicomWeb)
        return connect_dicomweb(node, options);
    return connect_dimse(node, options);
}

} // namespace arbor::dicom
