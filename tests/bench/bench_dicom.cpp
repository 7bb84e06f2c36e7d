// bench_dicom.cpp - how fast DICOM series import through the ABI: the scan
// and plan (headers only) and the whole import (decoding included), on the
// shared DICOM series and WG04 files in several transfer syntaxes, against
// pydicom reading and stacking the same files (the anchor; its numpy
// stacking is the fast part).  Prints a table; not a pass/fail test.
#include "fastest_run.hpp"
#include "test_paths.hpp"

#include "host/host_services.hpp"
#include "host/plugin_registry.hpp"
#include "host/volume_import.hpp"

#include <array>
#include <cstdio>
#include <memory>
#include <string>

using namespace arbor;

namespace {

// pydicom: read every file, sort by position along the normal, stack the
// pixel arrays; fastest of `repeat`.  Returns a negative number when pydicom
// cannot decode the input (no JPEG or JPEG-LS handler in Debian's pydicom).
double pydicom_seconds(const std::string &path, int repeat)
{
    const std::string script =
        "import glob, os, sys, time, numpy as np, pydicom\n"
        "p = sys.argv[1]\n"
        "files = sorted(glob.glob(os.path.join(p, '*.dcm'))) if os.path.isdir(p) else [p]\n"
        "best = 1e30\n"
        "for _ in range(" + std::to_string(repeat) + "):\n"
        "    t0 = time.perf_counter()\n"
        "    ds = [pydicom.dcmread(f) for f in files]\n"
        "    n = np.cross(*np.reshape(np.array(ds[0].ImageOrientationPatient, float), (2, 3)))\n"
        "    ds.sort(key=lambda d: float(np.dot(np.array(d.ImagePositionPatient, float), n)))\n"
        "    v = np.stack([d.pixel_array for d in ds])\n"
        "    best = min(best, time.perf_counter() - t0)\n"
        "print(best)\n";
    const std::string command = std::string(ARBOR_BENCH_PYTHON) + " -c \"$ARBOR_BENCH_SCRIPT\" '" + path + "' 2>/dev/null";
    setenv("ARBOR_BENCH_SCRIPT", script.c_str(), 1);
    std::unique_ptr<FILE, int (*)(FILE *)> pipe(popen(command.c_str(), "r"), &pclose);
    double seconds = -1;
    if (!pipe || std::fscanf(pipe.get(), "%lf", &seconds) != 1)
        return -1;
    return seconds;
}

} // namespace

int main()
{
    PluginRegistry registry;
    registry.load_directories({test::plugin_dir()});
    set_log_level(ARBOR_LOG_ERROR); // the irregular CT warns on every import
    const int repeat = 3;
    const std::array<const char *, 8> inputs = {
        "dicom_ct_head_0051",          "dicom_mr_brain_vs_tumor",
        "dicom_compressed_wg04/CT1_UNC.dcm",  "dicom_compressed_wg04/CT1_JPLL.dcm",
        "dicom_compressed_wg04/CT1_JLSL.dcm", "dicom_compressed_wg04/CT1_RLE.dcm",
        "dicom_compressed_wg04/CT1_J2KR.dcm", "dicom_compressed_wg04/CT1_J2KI.dcm"};
    std::printf("arbor_bench_dicom: org.arbor.importer.dicom through the ABI, fastest of %d runs;\n"
                "anchor: pydicom reading and stacking the same files (ratio = pydicom / Arbor)\n\n",
                repeat);
    std::printf("%-36s %10s %9s %10s %10s %9s %11s %7s\n", "input", "voxels", "MB", "header s", "import s",
                "MB/s", "pydicom s", "ratio");
    for (const char *name : inputs) {
        const auto path = test::shared_data(name);
        PluginInstance importer = registry.create("org.arbor.importer.dicom");
        const auto &table = importer.interface<arbor_importer_v1>(ARBOR_INTERFACE_IMPORTER);
        Volume volume;
        const double header = bench::fastest_seconds(
            [&] {
                arbor_volume h{};
                h.struct_size = sizeof h;
                Task task;
                importer.check(table.read_header(importer.get(), path.c_str(), task.get(), &h), "header");
            },
            repeat);
        const double total =
            bench::fastest_seconds([&] { volume = import_volume(importer, path, nullptr, uint64_t{1} << 33); }, repeat);
        const auto &d = volume.geometry().dims;
        const int64_t voxels = d[0] * d[1] * d[2];
        const double mb = static_cast<double>(voxels * arbor_voxel_size(volume.type())) / 1e6;
        const double anchor = pydicom_seconds(path.string(), repeat);
        char anchor_text[32] = "n/a", ratio_text[32] = "n/a";
        if (anchor > 0) {
            std::snprintf(anchor_text, sizeof anchor_text, "%.4f", anchor);
            std::snprintf(ratio_text, sizeof ratio_text, "%.1fx", anchor / total);
        }
        std::printf("%-36s %10lld %9.2f %10.4f %10.4f %9.1f %11s %7s\n", name, static_cast<long long>(voxels),
                    mb, header, total, mb / total, anchor_text, ratio_text);
        std::fflush(stdout);
    }
    std::printf("\nheader s: scan and plan only; import s: header, decoding and the host's checks.\n"
                "n/a: pydicom in Debian 12 has no JPEG or JPEG-LS decoder.\n");
    return 0;
}
