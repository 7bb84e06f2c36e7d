// dimse_store_scp.hpp - the storage SCP a C-MOVE sends its images to: it
// listens on our port while the move runs, accepts associations called with
// our AE title only, and hands every C-STORE to the retrieve's sink.
#pragma once

#include "dicom/pacs_client.hpp"

#include <dcmtk/dcmnet/scp.h>

#include <atomic>
#include <string>
#include <thread>

namespace arbor::dicom {

class StoreScp final : public DcmSCP {
public:
    StoreScp(const std::string &aet, uint16_t port, InstanceSink &sink, int timeout_s);
    ~StoreScp() override; // stops
    // Opens the port (PacsError when it cannot) and accepts on a thread.
    void start();
    // Waits for a running association to end, then stops listening.
    void stop();
    int failures() const { return failures_; }

protected:
    OFCondition handleIncomingCommand(T_DIMSE_Message *message, const DcmPresentationContextInfo &info) override;
    OFBool checkCalledAETitleAccepted(const OFString &called) override;
    OFBool stopAfterConnectionTimeout() override { return stopping_.load(); }

private:
    const std::string aet_;
    const uint16_t port_;
    InstanceSink &sink_;
    std::thread thread_;
    std::atomic<bool> stopping_{false};
    std::atomic<int> failures_{0};
};

} // namespace arbor::dicom
