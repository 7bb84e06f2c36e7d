#include "dimse_store_scp.hpp"

#include "dicom/dcmtk_setup.hpp"
#include "dicom/dimse_contexts.hpp"

#include <dcmtk/dcmnet/diutil.h>

namespace arbor::dicom {

StoreScp::StoreScp(const std::string &aet, uint16_t port, InstanceSink &sink, int timeout_s)
    : aet_(aet), port_(port), sink_(sink)
{
    ensure_dcmtk_ready();
    DcmSCPConfig &c = getConfig();
    c.setAETitle(aet.c_str());
    c.setPort(port);
    c.setConnectionBlockingMode(DUL_NOBLOCK);
    c.setConnectionTimeout(1); // how often a stop request is seen
    c.setDIMSEBlockingMode(DIMSE_NONBLOCKING);
    c.setDIMSETimeout(static_cast<Uint32>(timeout_s));
    c.setACSETimeout(static_cast<Uint32>(timeout_s));
    c.setHostLookupEnabled(OFFalse);
    setEnableVerification();
    add_storage_contexts(*this);
}

StoreScp::~StoreScp()
{
    stop();
}

void StoreScp::start()
{
    const OFCondition c = openListenPort();
    if (c.bad())
        throw PacsError(PacsError::Kind::Failed, "cannot listen on port " + std::to_string(port_) +
                                                     " for the C-MOVE's images (--our-port): " + c.text());
    thread_ = std::thread([this] { acceptAssociations(); });
}

void StoreScp::stop()
{
    stopping_ = true;
    if (thread_.joinable())
        thread_.join();
}

OFBool StoreScp::checkCalledAETitleAccepted(const OFString &called)
{
    return called == aet_.c_str();
}

OFCondition StoreScp::handleIncomingCommand(T_DIMSE_Message *message, const DcmPresentationContextInfo &info)
{
    if (message->CommandField != DIMSE_C_STORE_RQ)
        return DcmSCP::handleIncomingCommand(message, info);
    T_DIMSE_C_StoreRQ &request = message->msg.CStoreRQ;
    const std::filesystem::path staged = sink_.staging_file();
    OFCondition c = receiveSTORERequest(request, info.presentationContextID, OFString(staged.c_str()));
    Uint16 status = STATUS_STORE_Refused_OutOfResources;
    std::string problem;
    if (c.good() && sink_.commit(staged, problem))
        status = STATUS_Success;
    else
        ++failures_;
    if (c.good())
        c = sendSTOREResponse(info.presentationContextID, request, status);
    return c;
}

} // namespace arbor::dicom
