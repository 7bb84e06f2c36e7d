#include "plugin_choice.hpp"

#include <stdexcept>

namespace arbor::cli {

void PluginChoice::add_to(CLI::App &command, Context &context, const std::string &group)
{
    for (const PluginInfo *info : context.registry.plugins_of_kind(kind_)) {
        try {
            plugins_.push_back(context.registry.create(info->descriptor->id));
        } catch (const PluginError &e) {
            log_message(ARBOR_LOG_WARNING, "", e.what());
        }
    }
    std::vector<PluginInstance *> ptrs;
    for (PluginInstance &p : plugins_)
        ptrs.push_back(&p);
    options_.add(command, group, ptrs);
}

PluginInstance &PluginChoice::resolve(const std::string &name)
{
    PluginInstance *found = nullptr;
    for (PluginInstance &p : plugins_)
        if (p.id() == name)
            found = &p;
    if (!found) {
        std::vector<PluginInstance *> by_suffix;
        for (PluginInstance &p : plugins_) {
            const std::string id = p.id();
            if (id.size() > name.size() && id.compare(id.size() - name.size(), name.size(), name) == 0 &&
                id[id.size() - name.size() - 1] == '.')
                by_suffix.push_back(&p);
        }
        if (by_suffix.size() == 1)
            found = by_suffix[0];
    }
    if (!found) {
        std::string known;
        for (const PluginInstance &p : plugins_)
            known += (known.empty() ? "" : ", ") + p.id();
        throw std::invalid_argument("no " + noun_ + " '" + name + "' (there are: " +
                                    (known.empty() ? "none - see `arbor plugins`" : known) + ")");
    }
    options_.apply(*found);
    return *found;
}

std::vector<std::string> split_names(const std::string &list)
{
    std::vector<std::string> out;
    std::size_t start = 0;
    while (start <= list.size()) {
        std::size_t end = list.find(',', start);
        if (end == std::string::npos)
            end = list.size();
        std::string item = list.substr(start, end - start);
        item.erase(0, item.find_first_not_of(" \t"));
        item.erase(item.find_last_not_of(" \t") + 1);
        if (!item.empty())
            out.push_back(item);
        start = end + 1;
    }
    return out;
}

} // namespace arbor::cli
