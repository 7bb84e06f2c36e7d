#include "label_map_output.hpp"

#include "label_colors.hpp"

#include "core/atomic_file.hpp"
#include "nrrd_writer.hpp"

#include <algorithm>

namespace arbor::io {

std::filesystem::path color_table_path(const std::filesystem::path &labels_path)
{
    std::filesystem::path p = labels_path;
    const std::string ext = p.extension().string();
    if (ext == ".nrrd" || ext == ".nhdr")
        p.replace_extension(".ctbl");
    else
        p += ".ctbl";
    return p;
}

void write_label_map(const std::filesystem::path &path, const Geometry &geometry, const std::string &content,
                     std::span<const uint32_t> labels, const std::vector<std::string> &names)
{
    const bool wide = names.size() > 65535;
    Volume v = Volume::allocate(wide ? ARBOR_VOXEL_U32 : ARBOR_VOXEL_U16, geometry, {}, uint64_t{1} << 40);
    for (std::size_t i = 0; i < labels.size(); ++i) {
        if (wide)
            v.as<uint32_t>()[i] = labels[i];
        else
            v.as<uint16_t>()[i] = static_cast<uint16_t>(labels[i]);
    }
    NrrdWriteOptions w;
    w.content = content;
    w.key_values = {{"arbor_labels", std::to_string(names.size())},
                    {"arbor_color_table", color_table_path(path).filename().string()}};
    write_nrrd(v, path, w);

    AtomicFile table(color_table_path(path));
    table.write("# Color table file " + color_table_path(path).filename().string() + "\n");
    table.write("# " + std::to_string(names.size()) + " values\n");
    for (std::size_t k = 0; k < names.size(); ++k) {
        std::string name = names[k];
        std::replace(name.begin(), name.end(), ' ', '_');
        const Rgb8 c = label_color(static_cast<uint32_t>(k));
        table.write(std::to_string(k) + " " + name + " " + std::to_string(c[0]) + " " + std::to_string(c[1]) + " " +
                    std::to_string(c[2]) + " 255\n");
    }
    table.commit();
}

} // namespace arbor::io
