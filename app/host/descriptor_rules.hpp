// descriptor_rules.hpp - the rules a plugin's self-description must follow.
//
// Shared by the loader (which refuses plugins that break them) and by
// `arbor plugin-check` (which reports every rule, passed or not).  Each check
// returns "" when the rule holds, otherwise a sentence saying what is wrong.
#pragma once

#include <arbor/arbor.h>

#include <string>
#include <string_view>
#include <vector>

namespace arbor {

// Kinds this host knows, and the interface id each kind must offer.
const std::vector<std::string> &known_plugin_kinds();
const char *kind_interface_id(std::string_view kind); // nullptr for an unknown kind

// The library's entry record: its ABI major, size and functions; "" when
// the host may call init.
std::string check_entry_record(const arbor_plugin_entry *entry);

// Reverse-DNS, lowercase, three or more dot-separated parts.
std::string check_plugin_id(const char *id);
// "MAJOR.MINOR.PATCH" with optional "-suffix".
std::string check_semver(const char *version);
std::string check_descriptor(const arbor_plugin_descriptor *descriptor);
// A parameter id: lowercase letters, digits and '-', starting with a letter.
std::string check_param_id(const char *id);
std::string check_param_desc(const arbor_param_desc *desc);
// Every description of an instance's parameters, plus unique ids.
std::vector<std::string> check_param_set(const arbor_plugin *plugin, const arbor_params_v1 &params);

} // namespace arbor
