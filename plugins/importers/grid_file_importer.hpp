// grid_file_importer.hpp - the reading flow the three importers of this
// library share.  Each importer only says where a file's voxels are and what
// grid they form (locate); this base checks that the file can hold them before
// the host allocates, hands the header to the host, and later checks the
// host's buffer against the file and reads the voxels into it.
#pragma once

#include "voxel_grid.hpp"
#include "voxel_source.hpp"

#include <arbor/sdk/importer.hpp>

#include <filesystem>
#include <string>

namespace arbor::importers {

// What a header (or the raw importer's parameters) says about a file.
struct LocatedVolume {
    VoxelGrid grid;
    VoxelSource source;
    ValueMapping mapping;
};

// The data file a header names, relative to the header's folder.  Throws
// ARBOR_ERROR_IO naming both files when it is missing or not a regular file.
std::filesystem::path resolve_data_file(const std::filesystem::path &header_path,
                                        const std::string &named, const std::string &header_name);

class GridFileImporter : public sdk::Importer {
public:
    using sdk::Importer::Importer;

    void read_header(const std::string &path, const sdk::Task &, arbor_volume &out) override
    {
        LocatedVolume v = locate(path);
        check_data_fits(v.source, v.grid);
        mapping_ = std::move(v.mapping);
        write_volume_header(v.grid, mapping_, out);
    }

    void read_voxels(const std::string &path, const sdk::Task &task, arbor_volume &volume) override
    {
        // Parse again: headers are small, and the file may have changed.
        const LocatedVolume v = locate(path);
        require_matching_volume(v.grid, volume, std::filesystem::path(path).filename().string());
        read_voxel_data(v.source, v.grid, volume.voxels, task);
    }

protected:
    // Parses the header (or parameters) and works out where the voxels are;
    // reads no voxel data.
    virtual LocatedVolume locate(const std::filesystem::path &path) const = 0;

private:
    ValueMapping mapping_; // owns the unit text handed out by read_header
};

} // namespace arbor::importers
