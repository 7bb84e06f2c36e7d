// instance_server.hpp - one plugin instance inside `arbor-plugin-host`,
// served on its own channel by a thread of its own: each request becomes
// the C call the host's proxy stands for (host/isolated_plugin.cpp), with
// records rebuilt over the shared window.
#pragma once

#include "channel_services.hpp"

#include "host/isolation_wire.hpp"

#include <arbor/arbor.h>

#include <atomic>
#include <string>
#include <thread>

namespace arbor::plugin_host {

class InstanceServer {
public:
    InstanceServer(arbor_plugin *plugin, isolation::ChannelHeader *header, uint8_t *window);
    ~InstanceServer(); // stops the thread, destroys the instance
    InstanceServer(const InstanceServer &) = delete;
    InstanceServer &operator=(const InstanceServer &) = delete;

    // What the instance offers, for the create reply.
    void describe(isolation::MessageWriter &w) const;

private:
    void serve(uint32_t seen);
    int32_t handle(isolation::Op op, isolation::MessageReader &r, isolation::MessageWriter &w);
    std::string error() const;

    arbor_plugin *plugin_;
    isolation::ChannelHeader *header_;
    uint8_t *window_;
    ChannelTask task_;
    const void *tables_[9] = {};
    std::atomic<bool> stop_{false};
    std::thread thread_;
};

// What is wrong with the instance record create_plugin returned; "" when
// the host may use it.
std::string check_instance_record(const arbor_plugin *plugin);

} // namespace arbor::plugin_host
