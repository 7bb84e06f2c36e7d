// The DIMSE side of PacsClient on DCMTK's DcmSCU: one association per call,
// Study Root query/retrieve, C-GET with storage contexts in the SCP role,
// C-MOVE to a storage SCP of our own (dimse_store_scp.hpp) listening for the
// archive's sub-operations.
#include "dicom/dcmtk_setup.hpp"
#include "dicom/dimse_contexts.hpp"
#include "dicom/dimse_store_scp.hpp"
#include "dicom/pacs_client.hpp"
#include "dicom/value_text.hpp"

#include <dcmtk/dcmdata/dcdeftag.h>
#include <dcmtk/dcmdata/dcfilefo.h>
#include <dcmtk/dcmdata/dcuid.h>
#include <dcmtk/dcmnet/diutil.h>
#include <dcmtk/dcmnet/scu.h>

#include <chrono>
#include <cstdlib>
#include <optional>
#include <thread>

namespace arbor::dicom {

namespace {

using Kind = PacsError::Kind;

const char *const kFind = UID_FINDStudyRootQueryRetrieveInformationModel;
const char *const kGet = UID_GETStudyRootQueryRetrieveInformationModel;
const char *const kMove = UID_MOVEStudyRootQueryRetrieveInformationModel;

std::string text_of(DcmItem &item, const DcmTagKey &tag)
{
    OFString v;
    if (item.findAndGetOFStringArray(tag, v).bad())
        return {};
    std::string s = v.c_str();
    s.erase(s.find_last_not_of(' ') + 1);
    return s;
}

int count_of(DcmItem &item, const DcmTagKey &tag)
{
    return count_value(text_of(item, tag));
}

class Association final : public DcmSCU {
public:
    Association(const PacsNode &node, const PacsOptions &options) : node_(node), options_(options)
    {
        ensure_dcmtk_ready();
        // DCMTK sets TCP_NODELAY on its sockets only when this variable is
        // set; without it every sub-operation waits ~40 ms for Nagle.
        ::setenv("TCP_NODELAY", "1", 0);
        setAETitle(node.our_aet.c_str());
        setPeerAETitle(node.aet.c_str());
        setPeerHostName(node.host.c_str());
        setPeerPort(node.port);
        setConnectionTimeout(options.timeout_s);
        setACSETimeout(static_cast<Uint32>(options.timeout_s));
        setDIMSEBlockingMode(DIMSE_NONBLOCKING);
        setDIMSETimeout(static_cast<Uint32>(options.timeout_s));
        setMaxReceivePDULength(ASC_DEFAULTMAXPDU);
    }

    ~Association() override
    {
        if (isConnected())
            abortAssociation();
    }

    void open(const char *what)
    {
        OFCondition c = initNetwork();
        if (c.good())
            c = negotiateAssociation();
        if (c.bad())
            throw association_error(c, what);
    }

    void release()
    {
        if (isConnected())
            releaseAssociation();
    }

    T_ASC_PresentationContextID context(const char *abstract_syntax, const char *what)
    {
        const T_ASC_PresentationContextID id = findAnyPresentationContextID(abstract_syntax, "");
        if (id == 0)
            throw PacsError(Kind::Failed, node_.describe() + " does not offer " + what +
                                              " (it accepted no presentation context for it)");
        return id;
    }

    // A failure after the association was open, in words.
    PacsError lost(const OFCondition &c, const std::string &what) const
    {
        if (c == DIMSE_NODATAAVAILABLE)
            return PacsError(Kind::Timeout, node_.describe() + " did not answer the " + what + " within " +
                                                std::to_string(options_.timeout_s) + " s (--timeout)");
        if (c == DUL_PEERABORTEDASSOCIATION || c == DUL_PEERREQUESTEDRELEASE)
            return PacsError(Kind::Rejected,
                             node_.describe() + " ended the association during the " + what +
                                 ": it may not know our AE title " + node_.our_aet +
                                 " (archives answer only callers listed in their configuration)");
        std::string text = c.text(); // DCMTK's may span lines
        for (char &ch : text)
            if (ch == '\n' || ch == '\r')
                ch = ' ';
        for (const char *cut : {"TCP I/O Error", "Broken pipe", "Connection reset", "Socket closed"})
            if (text.find(cut) != std::string::npos)
                return PacsError(Kind::Failed,
                                 "the connection to " + node_.describe() + " was lost during the " + what + " (" + text + ")");
        return PacsError(Kind::Failed, node_.describe() + ": the " + what + " failed (" + text + ")");
    }

    // Sink and stop token of the current retrieve (C-GET stores arrive here).
    InstanceSink *sink = nullptr;
    int stored_failures = 0;
    bool cancelled = false;
    std::optional<RetrieveCounts> counts;

protected:
    OFCondition handleFINDResponse(const T_ASC_PresentationContextID id, QRResponse *response,
                                   OFBool &wait_for_next) override
    {
        const OFCondition c = DcmSCU::handleFINDResponse(id, response, wait_for_next);
        if (wait_for_next && options_.stop.stop_requested()) {
            cancelled = true;
            sendCANCELRequest(id);
        }
        return c;
    }

    OFCondition handleCGETResponse(const T_ASC_PresentationContextID id, RetrieveResponse *response,
                                   OFBool &continue_session) override
    {
        note_counts(*response);
        return DcmSCU::handleCGETResponse(id, response, continue_session);
    }

    OFCondition handleMOVEResponse(const T_ASC_PresentationContextID id, RetrieveResponse *response,
                                   OFBool &wait_for_next) override
    {
        note_counts(*response);
        const OFCondition c = DcmSCU::handleMOVEResponse(id, response, wait_for_next);
        if (wait_for_next && options_.stop.stop_requested()) {
            cancelled = true;
            sendCANCELRequest(id);
        }
        return c;
    }

    OFCondition handleSTORERequest(const T_ASC_PresentationContextID, DcmDataset *incoming,
                                   OFBool &continue_session, Uint16 &status) override
    {
        status = STATUS_STORE_Refused_OutOfResources;
        if (!incoming || !sink)
            return EC_IllegalParameter;
        const E_TransferSyntax xfer = incoming->getOriginalXfer();
        DcmFileFormat file(incoming, OFFalse); // takes the dataset over
        const std::filesystem::path staged = sink->staging_file();
        std::string problem;
        if (file.saveFile(staged.c_str(), xfer == EXS_Unknown ? EXS_LittleEndianExplicit : xfer).good() &&
            sink->commit(staged, problem))
            status = STATUS_Success;
        else
            ++stored_failures;
        if (options_.stop.stop_requested()) {
            cancelled = true;
            continue_session = OFFalse;
        }
        return EC_Normal;
    }

private:
    void note_counts(const RetrieveResponse &r)
    {
        RetrieveCounts n{r.m_status, r.m_numberOfRemainingSubops, r.m_numberOfCompletedSubops,
                         r.m_numberOfFailedSubops, r.m_numberOfWarningSubops};
        counts = n;
        if (sink && r.m_status == STATUS_Pending)
            sink->expect(n.remaining + n.completed + n.failed + n.warning);
    }

    PacsError association_error(const OFCondition &c, const char *what) const
    {
        const std::string text = c.text();
        const std::string where = node_.describe();
        if (c == DUL_ASSOCIATIONREJECTED)
            return PacsError(Kind::Rejected,
                             where + " rejected the association for " + what + ": check its AE title (we called '" +
                                 node_.aet + "') and that it knows ours ('" + node_.our_aet + "')");
        if (text.find("unknown host") != std::string::npos || text.find("Unknown host") != std::string::npos)
            return PacsError(Kind::Unreachable, "cannot reach " + where + ": unknown host " + node_.host);
        if (text.find("refused") != std::string::npos)
            return PacsError(Kind::Unreachable, "cannot reach " + where + ": connection refused (is the archive "
                                                                          "running, and is the port right?)");
        if (text.find("timed out") != std::string::npos || text.find("Timeout") != std::string::npos ||
            text.find("timeout") != std::string::npos || c == DUL_READTIMEOUT)
            return PacsError(Kind::Timeout, "cannot reach " + where + ": no answer within " +
                                                std::to_string(options_.timeout_s) + " s (--timeout)");
        if (c == NET_EC_NoAcceptablePresentationContexts)
            return PacsError(Kind::Rejected, where + " accepted none of the services we proposed for " + what);
        return PacsError(Kind::Unreachable, "cannot open an association with " + where + " for " + what + ": " + text);
    }

    const PacsNode &node_;
    const PacsOptions &options_;
};

std::vector<QRResponse *> run_find(Association &a, DcmDataset &keys)
{
    OFList<QRResponse *> responses;
    const OFCondition c = a.sendFINDRequest(a.context(kFind, "study-root C-FIND"), &keys, &responses);
    std::vector<QRResponse *> out(responses.begin(), responses.end());
    if (a.cancelled) {
        for (QRResponse *r : out)
            delete r;
        throw PacsError(Kind::Cancelled, "cancelled");
    }
    if (c.bad()) {
        for (QRResponse *r : out)
            delete r;
        throw a.lost(c, "C-FIND");
    }
    return out;
}

// Each matching dataset of a C-FIND; throws on a failure status.
template <class Row, class Read>
std::vector<Row> find_rows(Association &a, DcmDataset &keys, const std::string &where, Read read)
{
    std::vector<QRResponse *> responses = run_find(a, keys);
    std::vector<Row> rows;
    std::string failure;
    for (QRResponse *r : responses) {
        if (r->m_status == STATUS_Pending || r->m_status == STATUS_FIND_Pending_WarningUnsupportedOptionalKeys) {
            if (r->m_dataset) {
                r->m_dataset->convertToUTF8(); // names in the archive's character set
                rows.push_back(read(*r->m_dataset));
            }
        } else if (r->m_status != STATUS_Success && failure.empty()) {
            char code[16];
            std::snprintf(code, sizeof code, "0x%04X", r->m_status);
            failure = where + " answered the C-FIND with status " + code +
                      (r->m_statusDetail ? " (" + text_of(*r->m_statusDetail, DCM_ErrorComment) + ")" : "");
        }
        delete r;
    }
    if (!failure.empty())
        throw PacsError(Kind::Failed, failure);
    return rows;
}

void put(DcmDataset &d, const DcmTagKey &tag, const std::string &value)
{
    d.putAndInsertString(tag, value.c_str());
}

class DimseClient final : public PacsClient {
public:
    DimseClient(const PacsNode &node, const PacsOptions &options) : node_(node), options_(options) {}

    double echo() override
    {
        Association a(node_, options_);
        add_query_contexts(a, false);
        a.open("C-ECHO");
        const auto start = std::chrono::steady_clock::now();
        const OFCondition c = a.sendECHORequest(a.context(UID_VerificationSOPClass, "verification (C-ECHO)"));
        const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
        if (c.bad())
            throw a.lost(c, "C-ECHO");
        a.release();
        return ms;
    }

    std::vector<StudyRow> find_studies(const PacsQuery &q) override
    {
        Association a(node_, options_);
        add_query_contexts(a, false);
        a.open("C-FIND");
        std::vector<StudyRow> rows = studies(a, q);
        a.release();
        return rows;
    }

    std::vector<SeriesRow> find_series(const PacsQuery &q) override
    {
        Association a(node_, options_);
        add_query_contexts(a, false);
        a.open("C-FIND");
        std::vector<SeriesRow> rows;
        for (const StudyRow &study : studies_to_search(q, [&] { return studies(a, q); })) {
            for (SeriesRow &s : series_of(a, study, q.modality, ""))
                rows.push_back(std::move(s));
            if (options_.stop.stop_requested())
                throw PacsError(Kind::Cancelled, "cancelled");
        }
        a.release();
        return rows;
    }

    void retrieve(const std::string &series_uid, RetrieveMethod method, InstanceSink &sink) override
    {
        // Study Root retrieves name the study too: find the series first.
        std::optional<SeriesRow> found;
        {
            Association a(node_, options_);
            add_query_contexts(a, false);
            a.open("C-FIND");
            DcmDataset keys;
            put(keys, DCM_QueryRetrieveLevel, "SERIES");
            put(keys, DCM_SeriesInstanceUID, series_uid);
            put(keys, DCM_StudyInstanceUID, "");
            put(keys, DCM_NumberOfSeriesRelatedInstances, "");
            std::vector<SeriesRow> rows = find_rows<SeriesRow>(a, keys, node_.describe(), [](DcmDataset &d) {
                SeriesRow r;
                r.study_uid = text_of(d, DCM_StudyInstanceUID);
                r.image_count = count_of(d, DCM_NumberOfSeriesRelatedInstances);
                return r;
            });
            a.release();
            if (rows.empty())
                throw PacsError(Kind::Failed, node_.describe() + " has no series " + series_uid);
            found = rows.front();
        }
        if (found->image_count >= 0)
            sink.expect(found->image_count);
        if (method == RetrieveMethod::Get)
            get(*found, series_uid, sink);
        else
            move(*found, series_uid, sink);
    }

private:
    static void add_query_contexts(Association &a, bool retrieve)
    {
        OFList<OFString> syntaxes;
        syntaxes.push_back(UID_LittleEndianExplicitTransferSyntax);
        syntaxes.push_back(UID_LittleEndianImplicitTransferSyntax);
        a.addPresentationContext(UID_VerificationSOPClass, syntaxes);
        a.addPresentationContext(kFind, syntaxes);
        if (retrieve) {
            a.addPresentationContext(kGet, syntaxes);
            a.addPresentationContext(kMove, syntaxes);
        }
    }

    std::vector<StudyRow> studies(Association &a, const PacsQuery &q)
    {
        DcmDataset keys;
        put(keys, DCM_QueryRetrieveLevel, "STUDY");
        put(keys, DCM_SpecificCharacterSet, "ISO_IR 192");
        put(keys, DCM_PatientName, q.patient);
        put(keys, DCM_PatientID, "");
        put(keys, DCM_StudyInstanceUID, q.study_uid);
        put(keys, DCM_StudyDate, q.study_date);
        put(keys, DCM_StudyTime, "");
        put(keys, DCM_StudyDescription, "");
        put(keys, DCM_AccessionNumber, q.accession);
        put(keys, DCM_ModalitiesInStudy, q.modality);
        put(keys, DCM_NumberOfStudyRelatedSeries, "");
        put(keys, DCM_NumberOfStudyRelatedInstances, "");
        return find_rows<StudyRow>(a, keys, node_.describe(), [](DcmDataset &d) {
            StudyRow r;
            r.patient_name = display_person_name(text_of(d, DCM_PatientName));
            r.patient_id = text_of(d, DCM_PatientID);
            r.study_uid = text_of(d, DCM_StudyInstanceUID);
            r.study_date = text_of(d, DCM_StudyDate);
            r.study_description = text_of(d, DCM_StudyDescription);
            r.accession = text_of(d, DCM_AccessionNumber);
            r.modalities = text_of(d, DCM_ModalitiesInStudy);
            r.series_count = count_of(d, DCM_NumberOfStudyRelatedSeries);
            r.image_count = count_of(d, DCM_NumberOfStudyRelatedInstances);
            return r;
        });
    }

    std::vector<SeriesRow> series_of(Association &a, const StudyRow &study, const std::string &modality,
                                     const std::string &series_uid)
    {
        DcmDataset keys;
        put(keys, DCM_QueryRetrieveLevel, "SERIES");
        put(keys, DCM_SpecificCharacterSet, "ISO_IR 192");
        put(keys, DCM_StudyInstanceUID, study.study_uid);
        put(keys, DCM_SeriesInstanceUID, series_uid);
        put(keys, DCM_SeriesNumber, "");
        put(keys, DCM_Modality, modality);
        put(keys, DCM_SeriesDescription, "");
        put(keys, DCM_NumberOfSeriesRelatedInstances, "");
        std::vector<SeriesRow> rows = find_rows<SeriesRow>(a, keys, node_.describe(), [&](DcmDataset &d) {
            SeriesRow r;
            r.patient_name = study.patient_name;
            r.patient_id = study.patient_id;
            r.study_uid = study.study_uid;
            r.study_date = study.study_date;
            r.study_description = study.study_description;
            r.series_uid = text_of(d, DCM_SeriesInstanceUID);
            r.series_number = text_of(d, DCM_SeriesNumber);
            r.modality = text_of(d, DCM_Modality);
            r.description = text_of(d, DCM_SeriesDescription);
            r.image_count = count_of(d, DCM_NumberOfSeriesRelatedInstances);
            return r;
        });
        return rows;
    }

    static DcmDataset retrieve_keys(const SeriesRow &series, const std::string &series_uid)
    {
        DcmDataset keys;
        put(keys, DCM_QueryRetrieveLevel, "SERIES");
        put(keys, DCM_StudyInstanceUID, series.study_uid);
        put(keys, DCM_SeriesInstanceUID, series_uid);
        return keys;
    }

    void finish_retrieve(Association &a, const OFCondition &c, const char *what)
    {
        if (a.cancelled)
            throw PacsError(Kind::Cancelled, "cancelled");
        if (c.bad())
            throw a.lost(c, what);
        if (!a.counts)
            throw PacsError(Kind::Failed, node_.describe() + " sent no final " + what + " response");
        const RetrieveCounts &n = *a.counts;
        if (n.status == STATUS_Success && n.failed == 0 && a.stored_failures == 0)
            return;
        throw PacsError(Kind::Failed, describe_retrieve_status(node_, what, n, a.stored_failures));
    }

    void get(const SeriesRow &series, const std::string &series_uid, InstanceSink &sink)
    {
        Association a(node_, options_);
        add_query_contexts(a, true);
        add_storage_contexts(a, ASC_SC_ROLE_SCP);
        a.open("C-GET");
        a.sink = &sink;
        DcmDataset keys = retrieve_keys(series, series_uid);
        const OFCondition c = a.sendCGETRequest(a.context(kGet, "study-root C-GET"), &keys, nullptr);
        finish_retrieve(a, c, "C-GET");
        a.release();
    }

    void move(const SeriesRow &series, const std::string &series_uid, InstanceSink &sink)
    {
        if (node_.our_port == 0)
            throw PacsError(Kind::Failed, "C-MOVE needs our storage port: give --our-port (and make sure " +
                                              node_.describe() + " knows " + node_.our_aet +
                                              " at this machine's address and that port)");
        StoreScp scp(node_.our_aet, node_.our_port, sink, options_.timeout_s);
        scp.start(); // listening before the archive is asked to connect
        Association a(node_, options_);
        add_query_contexts(a, true);
        a.open("C-MOVE");
        a.sink = &sink;
        DcmDataset keys = retrieve_keys(series, series_uid);
        const OFCondition c =
            a.sendMOVERequest(a.context(kMove, "study-root C-MOVE"), node_.our_aet.c_str(), &keys, nullptr);
        a.release();
        scp.stop(); // after the archive's store association ended
        a.stored_failures = scp.failures();
        finish_retrieve(a, c, "C-MOVE");
    }

    const PacsNode node_;
    const PacsOptions options_;
};

} // namespace

std::unique_ptr<PacsClient> connect_dimse(const PacsNode &node, const PacsOptions &options)
{
    return std::make_unique<DimseClient>(node, options);
}

} // namespace arbor::dicom
