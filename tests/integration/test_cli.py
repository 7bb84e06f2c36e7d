"""End-to-end tests of the `arbor` command on the shared real volumes.

Run by ctest with ARBOR (the executable), ARBOR_SHARED_DIR (../shared),
ARBOR_FIXTURE_PLUGIN_DIR (broken plugins) and ARBOR_SCRATCH (an empty folder).
Expected values come from the data sets' READMEs in ../shared/data.
"""
import gzip
import hashlib
import json
import math
import os
import pathlib
import subprocess
import unittest

ARBOR = os.environ["ARBOR"]
SHARED = pathlib.Path(os.environ["ARBOR_SHARED_DIR"])
DATA = SHARED / "data"
FIXTURES = pathlib.Path(os.environ["ARBOR_FIXTURE_PLUGIN_DIR"])
SCRATCH = pathlib.Path(os.environ["ARBOR_SCRATCH"])
PLUGIN_DIR = pathlib.Path(os.environ["ARBOR_PLUGIN_DIR"])


def arbor(*args, env=None, check=True, memory_limit_mb=None):
    """Runs arbor; returns (exit status, stdout, stderr)."""
    full_env = dict(os.environ)
    full_env.pop("ARBOR_PLUGIN_PATH", None)
    full_env.pop("XDG_DATA_HOME", None)
    full_env["HOME"] = str(SCRATCH / "home")  # no per-user plugins
    full_env.update(env or {})
    cmd = [ARBOR, *map(str, args)]
    if memory_limit_mb:
        cmd = ["bash", "-c", f'ulimit -v {memory_limit_mb * 1024} && exec "$@"', "arbor", *cmd]
    p = subprocess.run(cmd, capture_output=True, text=True, env=full_env, timeout=600)
    if check and p.returncode != 0:
        raise AssertionError(f"arbor {' '.join(map(str, args))} failed ({p.returncode}):\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def info(*args, **kw):
    return json.loads(arbor("info", *args, "--json", **kw)[1])


# name: (path under data/, dims, type, spacing, (min, max), mean, importer)
VOLUMES = {
    "nucleon": ("nucleon/nucleon.nrrd", [41, 41, 41], "u8", [1, 1, 1], (0, 249), 39.4, "nrrd"),
    "neghip": ("neghip/neghip.nhdr", [64, 64, 64], "u8", [1, 1, 1], (0, 255), 18.4, "nrrd"),
    "bucky": ("bucky/bucky.nhdr", [32, 32, 32], "u8", [1, 1, 1], (0, 255), 35.9, "nrrd"),
    "tooth": ("tooth/tooth.nhdr", [103, 94, 161], "u8", [1, 1, 1], (0, 255), 103.2, "nrrd"),
    "tooth16": ("tooth16_bigendian/tooth.nhdr", [103, 94, 161], "u16", [1, 1, 1], (0, 1300), 526.9, "nrrd"),
    "walnut": ("walnut/walnut.nhdr", [128, 96, 114], "u16", [1, 1, 1], (0, 22526), 2050.9, "nrrd"),
    "brain1": ("mr_brain_tumor_pyradiomics/brain1_image.nrrd", [256, 256, 25], "i16",
               [0.78125, 0.78125, 6.5], (0, 3057), 385.7, "nrrd"),
    "lidc2": ("ct_chest_lidc2/LIDC2.mha", [256, 256, 133], "u8", [1.40625, 1.40625, 2.5], (0, 255), 7.1,
              "metaimage"),
    "mrhead": ("mr_head_lowres/HeadMRVolume.mhd", [48, 62, 42], "u8", [4, 4, 4], None, None, "metaimage"),
    "engine": ("engine/engine.vti", [256, 256, 128], "u8", [1, 1, 1], (0, 255), 22.3, "vtk-image"),
    "bonsai": ("bonsai/bonsai.vti", [256, 256, 256], "u8", [1, 1, 1], (0, 255), 13.7, "vtk-image"),
    "aneurism": ("aneurism/aneurism.vti", [256, 256, 256], "u8", [1, 1, 1], (0, 255), 1.07, "vtk-image"),
    "hydrogen": ("hydrogen_orbital/hydrogen.vti", [64, 64, 64], "f32", [1, 1, 1], (0, 1), 0.019, "vtk-image"),
    "ironprot": ("ironprot/ironProt.vtk", [68, 68, 68], "u8", [1, 1, 1], (0, 255), 13.1, "vtk-image"),
    "colin27": ("mr_brain_colin27/ch2.nii.gz", [181, 217, 181], "u8", [1, 1, 1], (0, 254), 44.6, "nifti"),
    "avm": ("ct_angio_avm/CT_AVM.nii.gz", [256, 242, 154], "u8", [0.7199, 0.7209, 1.0], None, None, "nifti"),
}


class InfoOnSharedVolumes(unittest.TestCase):
    def test_every_volume_opens_with_its_documented_geometry_and_values(self):
        for name, (rel, dims, vtype, spacing, value_range, mean, importer) in VOLUMES.items():
            with self.subTest(volume=name):
                j = info(DATA / rel)
                self.assertEqual(j["dims"], dims)
                self.assertEqual(j["voxel_type"], vtype)
                self.assertTrue(j["importer"]["id"].endswith("." + importer), j["importer"])
                for got, want in zip(j["spacing_mm"], spacing):
                    self.assertAlmostEqual(got, want, delta=5e-4)
                if value_range:
                    self.assertAlmostEqual(j["stored"]["min"], value_range[0], places=3)
                    self.assertAlmostEqual(j["stored"]["max"], value_range[1], places=3)
                if mean is not None:
                    self.assertAlmostEqual(j["stored"]["mean"], mean, delta=0.051 * max(1, mean))

    def test_nifti_scale_gives_the_physical_range(self):
        j = info(DATA / "ct_angio_avm/CT_AVM.nii.gz")
        self.assertAlmostEqual(j["value_mapping"]["scale"], 2.2086, places=3)
        self.assertAlmostEqual(j["physical"]["max"], 563.2, delta=0.5)

    def test_no_volume_but_a_ct_in_hu_is_read_as_hounsfield_units(self):
        # The oracle is DICOM's own statement: the CT head's series says HU.
        # The same values written to NRRD without the unit are recognised as
        # HU from the values alone; every other shared volume (MR, 8-bit
        # windowed CT exports, scaled CT angiography, synthetic fields) is not.
        head = info(DATA / "dicom_ct_head_0051")
        self.assertEqual(head["value_mapping"]["unit"], "HU")
        self.assertNotIn("unit_inferred", head["value_mapping"])
        converted = SCRATCH / "ct_head.nrrd"
        arbor("convert", DATA / "dicom_ct_head_0051", "-o", converted)
        raw = converted.read_bytes()
        cut = raw.index(b"\n\n")
        lines = raw[:cut].split(b"\n")
        header = [l for l in lines if not l.startswith(b"arbor_value_unit")]
        self.assertEqual(len(header), len(lines) - 1, "convert writes the unit into the NRRD")
        unnamed = SCRATCH / "ct_head_no_unit.nrrd"
        unnamed.write_bytes(b"\n".join(header) + raw[cut:])
        j = info(unnamed)
        self.assertEqual(j["value_mapping"]["unit"], "HU")
        inferred = j["value_mapping"]["unit_inferred"]
        self.assertAlmostEqual(inferred["air_peak"], -1000, delta=40)
        self.assertTrue(-20 <= inferred["tissue_peak"] <= 60, inferred)
        self.assertGreater(inferred["air_fraction"], 0.3)
        _, out, _ = arbor("info", unnamed)
        self.assertIn("HU read from the values", out)
        for name in ("brain1", "lidc2", "mrhead", "colin27", "avm", "walnut", "tooth16", "hydrogen"):
            with self.subTest(volume=name):
                j = info(DATA / VOLUMES[name][0])
                self.assertEqual(j["value_mapping"]["unit"], "")
                self.assertNotIn("unit_inferred", j["value_mapping"])
        mr = info(DATA / "dicom_mr_brain_vs_tumor")
        self.assertEqual(mr["value_mapping"]["unit"], "")

    def test_text_output_names_the_essentials(self):
        _, out, _ = arbor("info", DATA / "walnut/walnut.nhdr")
        for word in ("Dimensions  128 x 96 x 114", "u16", "Spacing", "Origin", "Histogram", "median"):
            self.assertIn(word, out)

    def test_raw_file_with_explicit_parameters(self):
        j = info(DATA / "tooth16_bigendian/tooth.raw", "--raw.dims", "103,94,161", "--raw.type", "u16",
                 "--raw.endian", "big")
        self.assertEqual(j["dims"], [103, 94, 161])
        self.assertEqual(j["stored"]["max"], 1300)


class Phantom(unittest.TestCase):
    def test_phantom_is_the_builtin_default_data(self):
        j = info("--phantom", "head")
        self.assertEqual(j["dims"], [128, 128, 128])
        self.assertEqual(j["voxel_type"], "u16")
        self.assertEqual(j["source"], "phantom:head")

    def test_phantom_file_is_deterministic_and_reads_back(self):
        a, b = SCRATCH / "a.nrrd", SCRATCH / "b.nrrd"
        for path in (a, b):
            arbor("phantom", "--kind", "head", "-o", path, "--size", 64, "--noise", 5, "--blobs", 6, "--seed", 3)
        self.assertEqual(hashlib.sha256(a.read_bytes()).digest(), hashlib.sha256(b.read_bytes()).digest())
        j = info(a)
        self.assertEqual(j["dims"], [64, 64, 64])
        self.assertAlmostEqual(j["spacing_mm"][0], 200 / 64)
        self.assertAlmostEqual(sum(j["origin_lps_mm"]) / 3, -0.5 * 200 / 64 * 63)
        c = SCRATCH / "c.nrrd"
        arbor("phantom", "-o", c, "--size", 64, "--noise", 5, "--blobs", 6, "--seed", 4)
        self.assertNotEqual(a.read_bytes(), c.read_bytes())

    def test_phantom_nests_structures_with_overlapping_ranges(self):
        # Scalp brightest, skull darkest inside the head, tumour values inside the brain's range.
        j = info("--phantom", "head", "--phantom-size", 64)
        self.assertEqual(j["stored"]["max"], 700)


class BadInput(unittest.TestCase):
    def expect_failure(self, *args, words=(), status=1, **kw):
        code, out, err = arbor(*args, check=False, **kw)
        self.assertEqual(code, status, f"stdout: {out}\nstderr: {err}")
        for w in words:
            self.assertIn(w, err)
        self.assertNotIn("Traceback", err)
        return err

    def write(self, name, data):
        p = SCRATCH / name
        p.write_bytes(data if isinstance(data, bytes) else data.encode())
        return p

    def test_missing_file(self):
        self.expect_failure("info", SCRATCH / "nothing-here.nrrd", words=("no such file",))

    def test_garbage_with_a_known_suffix(self):
        p = self.write("garbage.nrrd", os.urandom(5000))
        self.expect_failure("info", p)

    def test_header_claiming_100000_cubed_voxels(self):
        p = self.write("huge.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 100000 100000 100000\n"
                                    "encoding: raw\n\n" + "x" * 100)
        self.expect_failure("info", p, words=("100000",), memory_limit_mb=2048)

    def test_products_that_overflow(self):
        p = self.write("overflow.nrrd", "NRRD0004\ntype: uint8\ndimension: 3\n"
                                        "sizes: 9223372036854775807 9223372036854775807 2\nencoding: raw\n\n")
        self.expect_failure("info", p, memory_limit_mb=2048)

    def test_zero_and_negative_dims(self):
        for sizes in ("0 64 64", "-5 64 64"):
            with self.subTest(sizes=sizes):
                p = self.write("bad-dims.nrrd", f"NRRD0004\ntype: uint8\ndimension: 3\nsizes: {sizes}\n"
                                                "encoding: raw\n\n")
                self.expect_failure("info", p)

    def test_unknown_type(self):
        p = self.write("type.nrrd", "NRRD0004\ntype: quaternion\ndimension: 3\nsizes: 2 2 2\nencoding: raw\n\n")
        self.expect_failure("info", p, words=("quaternion",))

    def test_truncated_data(self):
        p = self.write("short.nrrd", "NRRD0004\ntype: uint16\ndimension: 3\nsizes: 64 64 64\n"
                                     "endian: little\nencoding: raw\n\n" + "\0" * 1000)
        self.expect_failure("info", p)

    def test_truncated_gzip(self):
        body = gzip.compress(bytes(64 * 64 * 64))
        p = self.write("short-gz.nrrd", b"NRRD0004\ntype: uint8\ndimension: 3\nsizes: 64 64 64\n"
                                        b"encoding: gzip\n\n" + body[: len(body) // 2])
        self.expect_failure("info", p)

    def test_gzip_claiming_far_more_than_it_can_hold(self):
        # 20 bytes of gzip cannot expand to 4 GB: refuse without allocating it.
        p = self.write("bomb.nrrd", b"NRRD0004\ntype: uint32\ndimension: 3\nsizes: 1024 1024 1000\n"
                                    b"encoding: gzip\n\n" + gzip.compress(b"\0" * 10))
        self.expect_failure("info", p, memory_limit_mb=2048)

    def test_raw_without_dimensions_names_the_flag(self):
        self.expect_failure("info", DATA / "walnut/walnut.raw", words=("--raw.dims",), status=2)

    def test_raw_with_an_invalid_flag_value(self):
        self.expect_failure("info", DATA / "walnut/walnut.raw", "--raw.dims", "0,96,114", words=("dims",), status=2)

    def test_raw_larger_than_the_file(self):
        self.expect_failure("info", DATA / "walnut/walnut.raw", "--raw.dims", "512,512,512",
                            "--raw.type", "u16")

    def test_usage_errors_exit_with_2(self):
        self.expect_failure("no-such-command", status=2)
        self.expect_failure("info", "--no-such-flag", status=2)
        self.expect_failure("phantom", status=2)  # -o is required

    def test_every_command_has_help(self):
        for cmd in ("info", "phantom", "convert", "plugins", "plugin-check"):
            with self.subTest(command=cmd):
                code, out, _ = arbor(cmd, "--help", check=False)
                self.assertEqual(code, 0)
                self.assertIn("Usage", out)


class Plugins(unittest.TestCase):
    def test_lists_the_shipped_importers(self):
        j = json.loads(arbor("plugins", "--json")[1])
        ids = {p["id"] for p in j["plugins"]}
        for want in ("org.arbor.importer.nrrd", "org.arbor.importer.metaimage", "org.arbor.importer.raw",
                     "org.arbor.importer.vtk-image", "org.arbor.importer.nifti", "org.arbor.importer.dicom"):
            self.assertIn(want, ids)
        self.assertEqual(j["refused"], [])

    def test_refuses_broken_plugins_by_name_and_carries_on(self):
        code, out, err = arbor("plugins", "--json", env={"ARBOR_PLUGIN_PATH": str(FIXTURES)})
        self.assertEqual(code, 0)
        j = json.loads(out)
        reasons = {pathlib.Path(r["library"]).name + " " + r["plugin"]: r["reason"] for r in j["refused"]}
        self.assertIn("ABI 2.", reasons["fixture-abi2.so "])
        self.assertIn("arbor_entry", reasons["fixture-no-entry.so "])
        self.assertTrue(any("reverse-DNS" in v for v in reasons.values()))
        ids = {p["id"] for p in j["plugins"]}
        self.assertIn("org.arbor.test.good", ids)
        self.assertIn("org.arbor.importer.nrrd", ids)
        self.assertIn("fixture-abi2.so", err)  # also said on the terminal
        # The host still works with broken plugins around.
        j2 = info(DATA / "nucleon/nucleon.nrrd", env={"ARBOR_PLUGIN_PATH": str(FIXTURES)})
        self.assertEqual(j2["dims"], [41, 41, 41])

    def test_plugin_check_passes_on_every_shipped_plugin(self):
        libs = sorted(PLUGIN_DIR.glob("*.so"))
        self.assertTrue(libs)
        code, out, err = arbor("plugin-check", *libs, "--json", check=False)
        self.assertEqual(code, 0, out + err)
        for lib in json.loads(out):
            self.assertTrue(lib["passed"], lib)

    def test_plugin_check_reports_a_crashing_plugin(self):
        code, out, _ = arbor("plugin-check", FIXTURES / "fixture-crash.so", check=False)
        self.assertEqual(code, 1)
        self.assertIn("crashed with signal", out)


class Convert(unittest.TestCase):
    def test_convert_keeps_geometry_and_values(self):
        out = SCRATCH / "lidc2.nrrd"
        arbor("convert", DATA / "ct_chest_lidc2/LIDC2.mha", "-o", out)
        a, b = info(DATA / "ct_chest_lidc2/LIDC2.mha"), info(out)
        for key in ("dims", "voxel_type", "stored", "histogram"):
            self.assertEqual(a[key], b[key], key)
        for key in ("spacing_mm", "origin_lps_mm", "direction"):
            for x, y in zip(a[key], b[key]):
                self.assertAlmostEqual(x, y, places=9)

    def test_failed_conversion_keeps_an_existing_file(self):
        out = SCRATCH / "keep.nrrd"
        out.write_text("precious")
        arbor("convert", SCRATCH / "does-not-exist.nrrd", "-o", out, check=False)
        self.assertEqual(out.read_text(), "precious")


class Topology(unittest.TestCase):
    def test_pairs_match_ttk_on_a_shared_volume(self):
        out = SCRATCH / "nucleon.pairs"
        arbor("pairs", DATA / "nucleon/nucleon.nrrd", "-o", out)
        ours = {tuple(map(int, l.split()[:3])) for l in out.read_text().splitlines() if l and not l.startswith("#")}
        with gzip.open(SHARED / "reference/ttk/nucleon.pairs.txt.gz", "rt") as f:
            ttk = {tuple(map(int, l.split()[:3])) for l in f if l.strip() and not l.startswith("#")}
        self.assertEqual(ours, ttk)
        header = out.read_text().splitlines()[5]
        self.assertEqual(header.split()[1:], ["type", "birth_vertex", "death_vertex", "birth_value", "death_value",
                                              "persistence", "bx", "by", "bz", "dx", "dy", "dz"])

    def test_tree_json_describes_nodes_arcs_and_branches(self):
        out = SCRATCH / "phantom-tree.json"
        code, _, err = arbor("tree", "--phantom", "head", "--phantom-size", 48, "--json", out, "--timings", "--no-cache")
        j = json.loads(out.read_text())
        self.assertEqual(j["format"], "arbor-contour-tree/2")
        nodes, arcs, br = j["nodes"], j["arcs"], j["branches"]
        # Tables of columns: every column has an entry per node, arc or branch.
        n = len(nodes["vertex"])
        for key in ("kind", "value", "branch"):
            self.assertEqual(len(nodes[key]), n, key)
        self.assertEqual(len(arcs["lower"]), n - 1)
        for key in ("upper", "interior_voxels", "branch"):
            self.assertEqual(len(arcs[key]), n - 1, key)
        kinds = {nodes["kind_names"][k] for k in nodes["kind"]}
        self.assertTrue({"minimum", "maximum"} <= kinds)
        # Every voxel is a node or lies inside exactly one arc.
        self.assertEqual(sum(arcs["interior_voxels"]) + n, 48 ** 3)
        measures = br["measures"]
        count = len(br["kind"])
        for column in [br[k] for k in ("parent", "depth", "extremum_node", "saddle_node", "importance")] + \
                [measures[k] for k in measures]:
            self.assertEqual(len(column), count)
        kind = lambda b: br["kind_names"][br["kind"][b]]
        # Derived as README.md says: relative = measure / the root's (0 when
        # that is 0), children from the parents, positions from the geometry.
        relative = lambda key, b: measures[key][b] / measures[key][0] if measures[key][0] > 0 else 0
        children = {b: [] for b in range(count)}
        for b in range(1, count):
            children[br["parent"][b]].append(b)
        vol = j["volume"]
        dims, spacing, origin, d = vol["dims"], vol["spacing_mm"], vol["origin_mm"], vol["direction"]

        def position(vertex):
            ijk = (vertex % dims[0], vertex // dims[0] % dims[1], vertex // (dims[0] * dims[1]))
            g = [s * c for s, c in zip(spacing, ijk)]
            return [origin[r] + sum(d[3 * r + c] * g[c] for c in range(3)) for r in range(3)]

        corners = [position(i + dims[0] * (j_ + dims[1] * k)) for i in (0, dims[0] - 1) for j_ in (0, dims[1] - 1)
                   for k in (0, dims[2] - 1)]
        self.assertEqual(kind(0), "root")
        self.assertEqual(measures["volume"][0], 48 ** 3)
        self.assertEqual(relative("persistence", 0), 1)
        for b in range(1, count):
            parent = br["parent"][b]
            self.assertLess(parent, b)  # parents come first
            self.assertEqual(br["depth"][b], br["depth"][parent] + 1)
            self.assertIn(b, children[parent])
            self.assertLessEqual(measures["volume"][b], measures["volume"][parent])
            for key in ("persistence", "volume", "volume-mm3", "hypervolume", "relative-hypervolume"):
                self.assertGreaterEqual(measures[key][b], 0)
                self.assertLessEqual(relative(key, b), 1.0 + 1e-9)
            p = position(nodes["vertex"][br["extremum_node"][b]])
            self.assertEqual(len(p), 3)
            for axis in range(3):
                self.assertGreaterEqual(p[axis], min(c[axis] for c in corners) - 1e-9)
                self.assertLessEqual(p[axis], max(c[axis] for c in corners) + 1e-9)
        # The children of a branch are consecutive (breadth first).
        for kids in children.values():
            self.assertEqual(kids, list(range(kids[0], kids[0] + len(kids))) if kids else [])
        self.assertAlmostEqual(measures["volume-mm3"][1], measures["volume"][1] * (200 / 48) ** 3, places=3)
        for stage in ("sort", "join+split trees", "merge", "total", "peak memory"):
            self.assertIn(stage, err)

    def test_tree_cut_writes_a_label_map(self):
        out, labels = SCRATCH / "cut.json", SCRATCH / "labels.nrrd"
        arbor("tree", "--phantom", "head", "--phantom-size", 48, "--phantom-noise", 4, "--json", out,
              "--keep", 6, "--labels", labels)
        j = json.loads(out.read_text())
        kept = j["simplified"]["kept_branches"]
        self.assertEqual(len(kept["branch"]), 6)
        self.assertEqual(len(kept["parent_label"]), 6)
        # Six distinct branches of the tree, the root first.
        self.assertEqual(len(set(kept["branch"])), 6)
        self.assertTrue(all(0 <= b < len(j["branches"]["kind"]) for b in kept["branch"]))
        self.assertEqual(kept["branch"][0], 0)
        info_labels = info(labels)
        self.assertEqual(info_labels["dims"], [48, 48, 48])
        self.assertEqual(info_labels["stored"]["min"], 0)
        self.assertLessEqual(info_labels["stored"]["max"], 5)

    def test_non_finite_values_are_refused_with_where_they_are(self):
        import struct
        values = [0.5] * 27
        values[13] = float("nan")
        p = SCRATCH / "nan.nrrd"
        p.write_bytes(b"NRRD0004\ntype: float\ndimension: 3\nsizes: 3 3 3\nendian: little\nencoding: raw\n\n"
                      + struct.pack("<27f", *values))
        code, _, err = arbor("pairs", p, "-o", SCRATCH / "nan.pairs", check=False)
        self.assertEqual(code, 1)
        self.assertIn("1 NaN", err)
        self.assertIn("1, 1, 1", err)

    def test_file_names_that_are_not_utf8_come_out_as_valid_json(self):
        # A Latin-1 file name: its bytes are not UTF-8, yet every JSON output
        # must be, with the stray byte replaced by U+FFFD.
        # (The messages on stdout name the file as it is, so they are read
        # as bytes here.)
        src = SCRATCH / os.fsdecode(b"M\xfcller.nrrd")
        expected = str(src).replace(os.fsdecode(b"\xfc"), "\ufffd")

        def run(*args):
            env = {k: v for k, v in os.environ.items() if k not in ("ARBOR_PLUGIN_PATH", "XDG_DATA_HOME")}
            p = subprocess.run([ARBOR, *map(str, args)], capture_output=True, timeout=600,
                               env={**env, "HOME": str(SCRATCH / "home")})
            self.assertEqual(p.returncode, 0, p.stderr.decode("utf-8", "replace"))
            return p.stdout

        read = lambda p: json.loads(p.read_bytes().decode("utf-8"))
        run("convert", DATA / "nucleon/nucleon.nrrd", "-o", src)
        run("tree", src, "--json", SCRATCH / "latin1-tree.json")
        self.assertEqual(read(SCRATCH / "latin1-tree.json")["volume"]["source"], expected)
        run("simplify", src, "--keep", 3, "--json", SCRATCH / "latin1-kept.json")
        self.assertEqual(read(SCRATCH / "latin1-kept.json")["volume"]["source"], expected)
        run("run", src, "--keep", 3, "--width", 32, "--height", 32, "-o", SCRATCH / "latin1.png")
        self.assertEqual(read(SCRATCH / "latin1.report.json")["input"]["source"], expected)
        self.assertEqual(json.loads(run("info", src, "--json").decode("utf-8"))["source"], expected)

    def test_constant_and_single_voxel_volumes(self):
        for sizes in ("4 3 2", "1 1 1"):
            with self.subTest(sizes=sizes):
                n = 1
                for d in sizes.split():
                    n *= int(d)
                p = SCRATCH / "flat.nrrd"
                p.write_bytes(f"NRRD0004\ntype: uint8\ndimension: 3\nsizes: {sizes}\nencoding: raw\n\n".encode()
                              + bytes([7] * n))
                out = SCRATCH / "flat.json"
                arbor("tree", p, "--json", out)
                j = json.loads(out.read_text())
                self.assertEqual(len(j["branches"]["kind"]), 1)
                self.assertEqual(j["branches"]["measures"]["volume"][0], n)


if __name__ == "__main__":
    unittest.main()


def png_size(path):
    """(width, height) of a PNG file, checking its signature."""
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n", f"{path} is not a PNG"
    return int.from_bytes(data[16:20], "big"), int.from_bytes(data[20:24], "big")


class Simplify(unittest.TestCase):
    NOISY = ("--phantom", "head", "--phantom-noise", 8, "--phantom-blobs", 20)

    def test_simplify_writes_kept_branches_and_a_slicer_label_map(self):
        out, labels = SCRATCH / "itri.json", SCRATCH / "itri-labels.nrrd"
        arbor("simplify", *self.NOISY, "--simplifier", "itri", "--keep", 16, "--json", out, "--labels", labels)
        j = json.loads(out.read_text())
        self.assertEqual(j["format"], "arbor-simplified-tree/1")
        self.assertEqual(j["simplifier"]["id"], "org.arbor.simplifier.itri")
        kept = j["kept_branches"]
        self.assertEqual(len(kept), 16)
        self.assertEqual(kept[0]["kind"], "root")
        for b in kept[1:]:
            self.assertGreater(b["importance"], 0)
            self.assertLess(b["parent_label"], b["label"])
            self.assertEqual(b["depth"], kept[b["parent_label"]]["depth"] + 1)
            self.assertEqual(set(b["relative_measures"]), {"persistence", "volume", "volume-mm3", "hypervolume",
                                                            "relative-hypervolume"})
        # The tumour (centre (-27, 47, 10) mm, radius 8 mm) is one of ITri's branches.
        self.assertTrue(any(sum((a - c) ** 2 for a, c in zip(b["extremum"]["position_mm"], (-27, 47, 10))) < 64
                            for b in kept))
        lab = info(labels)
        self.assertEqual(lab["dims"], [128, 128, 128])
        self.assertEqual((lab["stored"]["min"], lab["stored"]["max"]), (0, 15))
        table = (SCRATCH / "itri-labels.ctbl").read_text().splitlines()
        entries = [l.split() for l in table if not l.startswith("#")]
        self.assertEqual([int(e[0]) for e in entries], list(range(16)))
        self.assertTrue(all(len(e) == 6 and all(0 <= int(x) <= 255 for x in e[2:]) for e in entries))

    def test_threshold_on_a_real_volume(self):
        out = SCRATCH / "tooth-persistence.json"
        arbor("simplify", DATA / "tooth/tooth.nhdr", "--simplifier", "org.arbor.simplifier.persistence",
              "--threshold", 0.2, "--json", out)
        kept = json.loads(out.read_text())["kept_branches"]
        self.assertGreater(len(kept), 1)
        for b in kept[1:]:
            self.assertGreater(b["importance"], 0.2)
            self.assertAlmostEqual(b["importance"], b["relative_measures"]["persistence"])

    def test_compare_on_the_noisy_phantom_with_ground_truth(self):
        phantom, truth, out = SCRATCH / "noisy.nrrd", SCRATCH / "truth.nrrd", SCRATCH / "compare-phantom"
        arbor("phantom", "--noise", 8, "--blobs", 20, "-o", phantom, "--labels", truth)
        code, stdout, _ = arbor("compare", phantom, "--keep", 16, "--truth", truth, "--out", out)
        self.assertIn("report.md", stdout)
        r = json.loads((out / "report.json").read_text())
        ids = [s["id"] for s in r["study"]["simplifiers"]]
        self.assertEqual(ids, ["org.arbor.simplifier." + n for n in ("itri", "persistence", "volume", "hypervolume")])
        result = r["results"][0]
        for s in result["simplifiers"]:
            self.assertEqual(s["cuts"][0]["kept_count"], 16)
            self.assertEqual(len(s["cuts"][0]["kept"]), 16)
        timings = json.loads((out / "timings.json").read_text())
        for s in timings["filters"][0]["simplifiers"]:
            self.assertGreater(s["decomposition_seconds"], 0)
        self.assertEqual(len(result["overlaps"]), 6)
        for o in result["overlaps"]:
            self.assertEqual(o["shared"] + o["only_a"], 15)
            self.assertAlmostEqual(o["jaccard"], o["shared"] / (o["shared"] + o["only_a"] + o["only_b"]))
        # The structures are named from the colour table beside the truth.
        dice = {s["label"]: {t["name"]: t for t in s["cuts"][0]["truth"]} for s in result["simplifiers"]}
        self.assertGreater(dice["itri"]["tumour"]["one_to_one"]["dice"], 0.5)
        self.assertLess(dice["persistence"]["tumour"]["one_to_one"]["dice"], 0.1)
        for s in dice:
            self.assertGreater(dice[s]["skull"]["best_match"]["dice"], 0.8)
        rows = (out / "report.csv").read_text().splitlines()
        self.assertEqual(len(rows), 1 + 4 * 16)
        self.assertTrue(rows[0].startswith("filter,cut,simplifier,label,branch,parent_label,kind"))
        md = (out / "report.md").read_text()
        self.assertIn("### Dice with the ground truth", md)
        self.assertIn("![priority-lines.png](priority-lines.png)", md)
        w, h = png_size(out / "priority-lines.png")
        self.assertGreater(w, 600)
        self.assertGreater(h, 4 * 100)
        w, h = png_size(out / "labels-axial.png")
        self.assertGreater(w, 600)

    def test_compare_on_a_real_volume(self):
        out = SCRATCH / "compare-engine"
        arbor("compare", DATA / "engine/engine.vti", "--keep", 10, "--simplifiers", "itri,volume", "--out", out)
        r = json.loads((out / "report.json").read_text())
        self.assertEqual([s["cuts"][0]["kept_count"] for s in r["results"][0]["simplifiers"]], [10, 10])
        self.assertEqual(r["volume"]["dims"], [256, 256, 128])
        png_size(out / "labels-axial.png")

    def test_a_third_party_simplifier_is_picked_up_by_id(self):
        out = SCRATCH / "compare-third-party"
        env = {"ARBOR_PLUGIN_PATH": str(FIXTURES / "fixture-simplifier")}
        arbor("compare", "--phantom", "head", "--phantom-size", 48, "--keep", 5, "--simplifiers",
              "volume-squared,org.arbor.simplifier.volume", "--out", out, env=env)
        r = json.loads((out / "report.json").read_text())
        self.assertEqual(r["study"]["simplifiers"][0]["id"], "org.arbor.test.simplifier.volume-squared")
        # Squaring the volume ranks branches as the volume does.
        self.assertEqual(r["results"][0]["overlaps"][0]["jaccard"], 1.0)

    def test_a_plugin_built_against_the_abi_1_0_headers_runs_in_this_host(self):
        out = SCRATCH / "compare-abi-1-0"
        env = {"ARBOR_PLUGIN_PATH": str(FIXTURES / "fixture-simplifier-abi-1-0")}
        _, listed, _ = arbor("plugins", env=env)
        self.assertIn("org.arbor.test.simplifier.abi-1-0", listed)
        arbor("compare", "--phantom", "head", "--phantom-size", 48, "--keep", 5, "--simplifiers",
              "org.arbor.test.simplifier.abi-1-0,org.arbor.simplifier.volume", "--out", out, env=env)
        r = json.loads((out / "report.json").read_text())
        self.assertEqual(r["results"][0]["overlaps"][0]["jaccard"], 1.0)

    def test_bad_simplifiers_and_arguments_are_refused_clearly(self):
        (SCRATCH / "bad.json").unlink(missing_ok=True)
        for library, id_ in (("fixture-simplifier-nan", "org.arbor.test.simplifier.nan"),
                             ("fixture-simplifier-negative", "org.arbor.test.simplifier.negative")):
            code, _, err = arbor("simplify", "--phantom", "head", "--phantom-size", 32, "--simplifier", id_,
                                 "--keep", 3, "--json", SCRATCH / "bad.json", check=False,
                                 env={"ARBOR_PLUGIN_PATH": str(FIXTURES / library)})
            self.assertNotEqual(code, 0)
            self.assertIn(id_, err)
            self.assertIn("finite number >= 0", err)
            self.assertFalse((SCRATCH / "bad.json").exists())
        code, _, err = arbor("simplify", "--phantom", "head", "--simplifier", "entropy", "--keep", 3,
                             "--json", SCRATCH / "x.json", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("no simplifier 'entropy'", err)
        self.assertIn("org.arbor.simplifier.itri", err)
        code, _, err = arbor("simplify", "--phantom", "head", "--json", SCRATCH / "x.json", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("--keep N or --threshold T", err)
        code, _, err = arbor("compare", "--phantom", "head", "--phantom-size", 32, "--keep", 3, "--truth",
                             DATA / "neghip/neghip.nhdr", "--out", SCRATCH / "x", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("dims differ", err)
        code, _, err = arbor("simplify", "--phantom", "head", "--simplifier", "n-measure", "--n-measure.measures",
                             "volume", "--keep", 3, "--json", SCRATCH / "x.json", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("at least two measures", err)


def srgb_to_lab(c):
    def lin(u):
        return u / 12.92 if u <= 0.04045 else ((u + 0.055) / 1.055) ** 2.4
    r, g, b = map(lin, c[:3])
    x, y, z = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047, 0.2126 * r + 0.7152 * g + 0.0722 * b, \
        (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883
    f = lambda t: t ** (1 / 3) if t > (6 / 29) ** 3 else t / (3 * (6 / 29) ** 2) + 4 / 29
    return 116 * f(y) - 16, 500 * (f(x) - f(y)), 200 * (f(y) - f(z))


class TransferFunctionsCli(unittest.TestCase):
    # The generator's behaviour on the noise itself (no automatic denoising).
    NOISY = ("--phantom", "head", "--phantom-noise", 8, "--filter", "none")

    def tf(self, *args, name="tf.json"):
        out = SCRATCH / name
        arbor("tf", *args, "-o", out)
        return json.loads(out.read_text())

    def test_phantom_transfer_functions_file(self):
        j = self.tf(*self.NOISY, "--keep", 12, "--lut-size", 32)
        self.assertEqual(j["format"], "arbor-transfer-functions/1")
        self.assertEqual(j["generator"]["id"], "org.arbor.tf.residue-flow")
        self.assertEqual(j["depictor"]["id"], "org.arbor.depictor.inclusion")
        self.assertEqual(j["simplifier"], {"id": "org.arbor.simplifier.itri", "cut": "keep 12"})
        self.assertEqual(len(j["branches"]), 12)
        for b in j["branches"]:
            self.assertEqual(len(b["lut"]), 32)
            self.assertLessEqual(b["domain"][0], b["domain"][1])
            self.assertGreaterEqual(len(b["points"]), 2)
            self.assertTrue(all(0 <= x <= 1 for entry in b["lut"] for x in entry))
            values = [p["value"] for p in b["points"]]
            self.assertEqual(values, sorted(values))
        # Inner branches are more opaque than the branches that include them.
        by_label = {b["label"]: b for b in j["branches"]}
        for b in j["branches"][1:]:
            self.assertGreater(b["opacity_range"][1], by_label[b["parent"]]["opacity_range"][1])
        # The tumour (the deepest branch) is the most opaque, the skin (root) the least.
        tumour = max(j["branches"], key=lambda b: b["depth"])
        v, h = tumour["extremum_vertex"], 200 / 128
        position = [(-63.5 + i) * h for i in (v % 128, v // 128 % 128, v // 128 ** 2)]
        self.assertLess(sum((a - c) ** 2 for a, c in zip(position, (-27, 47, 10))), 8 ** 2)
        self.assertEqual(max(j["branches"], key=lambda b: b["opacity_range"][1])["label"], tumour["label"])
        self.assertEqual(min(j["branches"], key=lambda b: b["opacity_range"][1])["label"], 0)

    def test_flow_rate_moves_opacity_inwards_without_changing_colours(self):
        low = self.tf(*self.NOISY, "--keep", 12, "--flow-rate", 10, "--relation", "none", name="q10.json")
        high = self.tf(*self.NOISY, "--keep", 12, "--flow-rate", 250, "--relation", "none", name="q250.json")
        band = lambda b: b["opacity_range"][1] - b["opacity_range"][0]
        self.assertLess(band(high["branches"][0]), band(low["branches"][0]))
        deepest = max(range(12), key=lambda i: low["branches"][i]["depth"])
        self.assertGreater(band(high["branches"][deepest]), band(low["branches"][deepest]))
        for a, b in zip(low["branches"], high["branches"]):
            self.assertEqual(a["rgba_at_extremum"][:3], b["rgba_at_extremum"][:3])

    def test_neighbour_relation_with_legend_and_harmonic_hues(self):
        legend = SCRATCH / "wheel.png"
        arbor("tf", *self.NOISY, "--keep", 12, "--relation", "neighbour", "--select", 4, "--hues", "X:30",
              "--shape", "peak", "--legend", legend, "-o", SCRATCH / "neighbour.json")
        j = json.loads((SCRATCH / "neighbour.json").read_text())
        self.assertEqual(j["depictor"]["id"], "org.arbor.depictor.neighbour")
        self.assertEqual(j["depictor"]["parameters"]["rotation"], "0")
        self.assertEqual(j["generator"]["parameters"]["hues"], "X:30")
        roles = {b["label"]: b["role"] for b in j["branches"]}
        self.assertEqual(roles[4], "selected")
        self.assertEqual(roles[j["branches"][4]["parent"]], "parent")
        for b in j["branches"]:
            if b["parent"] == 4:
                self.assertEqual(b["role"], "child")
        self.assertEqual(png_size(legend), (512, 512))

    def test_baseline_and_real_volume(self):
        j = self.tf(DATA / "tooth/tooth.nhdr", "--generator", "histogram-ramp", "--keep", 8, name="tooth-tf.json")
        self.assertEqual(j["generator"]["id"], "org.arbor.tf.histogram-ramp")
        self.assertEqual(len(j["branches"]), 8)
        j = self.tf(DATA / "engine/engine.vti", "--keep", 20, name="engine-tf.json")
        self.assertEqual(len(j["branches"]), 20)

    def test_bad_arguments_are_refused_clearly(self):
        cases = [
            (("--relation", "neighbour"), "needs --select"),
            (("--select", 99), "has 12 branches"),
            (("--hues", "Q"), "unknown hue template"),
            (("--legend", SCRATCH / "w.png"), "draws no legend"),
            (("--shape", "spiral"), "shape"),
            (("--generator", "magic"), "no transfer-function generator 'magic'"),
        ]
        (SCRATCH / "bad-tf.json").unlink(missing_ok=True)
        for args, message in cases:
            with self.subTest(args=args):
                code, _, err = arbor("tf", "--phantom", "head", "--phantom-size", 32, *args, "-o",
                                     SCRATCH / "bad-tf.json", check=False)
                self.assertNotEqual(code, 0)
                self.assertIn(message, err)
                self.assertFalse((SCRATCH / "bad-tf.json").exists())


def png_pixels(path):
    """(width, height, bytes per pixel, rows of bytes) of an 8-bit PNG, decoded with zlib."""
    import struct
    import zlib
    data = pathlib.Path(path).read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat, width = 8, b"", 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour = struct.unpack(">IIBB", body[:10])
            bpp = {2: 3, 6: 4, 0: 1}[colour]
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw, rows, prev = zlib.decompress(idat), [], bytearray(width * bpp)
    stride = width * bpp + 1
    for y in range(height):
        f, line = raw[y * stride], bytearray(raw[y * stride + 1:(y + 1) * stride])
        for i in range(len(line)):
            a = line[i - bpp] if i >= bpp else 0
            b, c = prev[i], prev[i - bpp] if i >= bpp else 0
            if f == 1:
                line[i] = (line[i] + a) & 255
            elif f == 2:
                line[i] = (line[i] + b) & 255
            elif f == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif f == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        prev = line
    return width, height, bpp, rows


class Run(unittest.TestCase):
    def test_the_image_is_the_same_with_1_2_and_8_threads(self):
        """Tiles are split over threads; no thread count changes a pixel."""
        images = []
        for threads in (1, 2, 8):
            out = SCRATCH / f"threads-{threads}.png"
            arbor("run", DATA / "tooth/tooth.nhdr", "--no-cache", "--renderer", "cpu-raycast",
                  "--cpu-raycast.threads", threads, "--width", 200, "--height", 200, "-o", out)
            images.append(out.read_bytes())
        self.assertEqual(images[0], images[1], "1 and 2 threads")
        self.assertEqual(images[0], images[2], "1 and 8 threads")

    def check_report(self, report, image):
        r = json.loads(report.read_text())
        self.assertEqual(r["format"], "arbor-run-report/1")
        for key in ("input", "plugins", "simplification", "camera", "seconds", "branches", "output"):
            self.assertIn(key, r)
        for stage in ("import", "contour tree", "simplification", "transfer functions", "render", "total"):
            self.assertGreaterEqual(r["seconds"][stage], 0)
        for role in ("simplifier", "generator", "renderer", "depictor"):
            self.assertRegex(r["plugins"][role]["version"], r"^\d+\.\d+\.\d+$")
        s = r["simplification"]
        self.assertGreater(s["branches_before"], s["branches_after"] - 1)
        self.assertEqual(len(r["branches"]), s["branches_after"])
        for b in r["branches"]:
            self.assertRegex(b["colour"], r"^#[0-9a-f]{6}$")
            self.assertLessEqual(b["opacity_range"][0], b["opacity_range"][1])
            self.assertGreaterEqual(b["visibility"], 0)
        self.assertAlmostEqual(sum(b["visibility"] for b in r["branches"]), 1.0, places=6)
        self.assertGreater(r["output"]["covered_fraction"], 0.02)
        self.assertEqual(r["output"]["image"], str(image))
        self.assertTrue(report.with_suffix(".md").exists())
        return r

    def test_main_job_on_the_phantom(self):
        out = SCRATCH / "head" / "head.png"
        code, stdout, _ = arbor("run", "--phantom", "head", "-o", out)
        self.assertIn("image:  " + str(out), stdout)
        width, height, bpp, rows = png_pixels(out)
        self.assertEqual((width, height, bpp), (512, 512, 4))
        self.assertGreater(len({r[i:i + 3] for r in rows[::16] for i in range(0, len(r), 64)}), 20, "blank image")
        r = self.check_report(SCRATCH / "head" / "head.report.json", out)
        self.assertTrue(r["simplification"]["automatic"])
        self.assertEqual(png_size(SCRATCH / "head" / "head-legend.png"), (512, 512))
        self.assertIn("visibility", stdout)
        self.assertEqual(len([l for l in stdout.splitlines() if "%  " in l]), len(r["branches"]))

    def test_the_flow_rate_peels_a_real_mr_from_its_surface_to_its_inside(self):
        """The balance is taken at the default flow rate and kept: Q 10 .. 1000
        takes the root (the head's surface) from over half the picture to
        under a tenth, monotonically, and brings the leaves forward."""
        out = SCRATCH / "peel" / "brain1.png"
        rates = (10, 30, 60, 150, 300, 1000)
        arbor("run", DATA / "mr_brain_tumor_pyradiomics/brain1_image.nrrd", "--flow-rate",
              ",".join(map(str, rates)), "--width", 256, "--height", 256, "-o", out)
        runs = json.loads((SCRATCH / "peel" / "brain1.report.json").read_text())["runs"]
        self.assertEqual(len(runs), len(rates))
        roots = [r["branches"][0]["visibility"] for r in runs]
        self.assertGreaterEqual(roots[0], 0.5, roots)
        self.assertLessEqual(roots[-1], 0.1, roots)
        for a, b in zip(roots, roots[1:]):
            self.assertLess(b, a, roots)
        parents = {b["parent"] for b in runs[0]["branches"]}
        leaves = lambda r: sum(b["visibility"] for b in r["branches"] if b["label"] not in parents)
        self.assertGreater(leaves(runs[-1]), leaves(runs[0]) + 0.2)
        at_default = runs[rates.index(60)]["branches"]
        for r in runs:
            for b, d in zip(r["branches"], at_default):
                self.assertEqual(b["balance_scale"], d["balance_scale"], "one balance, taken at the default")
                self.assertAlmostEqual(b["optical_depth_scale"], b["balance_scale"] * b["flow_peel"])
        self.assertEqual([b["flow_peel"] for b in at_default], [1.0] * len(at_default))

    def test_ct_branches_name_their_hounsfield_range_and_tissues(self):
        out = SCRATCH / "ct-head.png"
        arbor("run", DATA / "dicom_ct_head_0051", "--keep", 8, "--width", 64, "--height", 64, "-o", out)
        r = json.loads((SCRATCH / "ct-head.report.json").read_text())
        known = {"air", "lung", "fat", "soft tissue", "contrast", "bone"}
        for b in r["branches"]:
            lo, hi = b["hu_range"]
            self.assertLessEqual(lo, hi)
            self.assertTrue(b["tissues"] and set(b["tissues"]) <= known, b)
        root = r["branches"][0]
        self.assertAlmostEqual(root["hu_range"][0], -1024, delta=1)  # stored 0, intercept -1024
        self.assertEqual(root["tissues"][0], "air")
        self.assertEqual(root["tissues"][-1], "bone")
        # Colour by tissue: every branch wholly in bone is coloured as bone,
        # the root as the skin.
        self.assertIn("colour: soft tissue", root["generator_note"])
        bones = [b for b in r["branches"] if b["hu_range"][0] >= 350]
        self.assertGreaterEqual(len(bones), 2)
        for b in bones:
            self.assertIn("colour: bone", b["generator_note"], b)
        # The headrest (its two halves, behind the head) is outside the body:
        # faint context; nothing of the skull is.
        context = [b for b in r["branches"] if b.get("context") == "outside the body"]
        self.assertEqual(len(context), 2, [b.get("context") for b in r["branches"]])
        for b in context:
            self.assertGreater(b["extremum_position_mm"][1], 60)  # LPS: posterior
            self.assertEqual(b["outside_body"], 1.0)
            self.assertLessEqual(b["visibility"], 0.03)
        for b in bones:
            self.assertNotIn("context", b)

    def test_automatic_count_keeps_the_tumour_of_the_noisy_phantom(self):
        out = SCRATCH / "noisy-head.png"
        arbor("run", "--phantom", "head", "--phantom-noise", 8, "--phantom-blobs", 20, "-o", out,
              "--width", 128, "--height", 128)
        r = json.loads((SCRATCH / "noisy-head.report.json").read_text())
        self.assertTrue(r["simplification"]["automatic"])
        self.assertTrue(any(sum((a - c) ** 2 for a, c in zip(b["extremum_position_mm"], (-27, 47, 10))) < 64
                            for b in r["branches"]), "the tumour branch was not kept")

    def test_exr_output_with_depth(self):
        out = SCRATCH / "head.exr"
        arbor("run", "--phantom", "head", "--phantom-size", 48, "--keep", 6, "--width", 96, "--height", 64,
              "--azimuth", 40, "--elevation", 20, "--orthographic", "-o", out)
        data = out.read_bytes()
        self.assertEqual(data[:4], b"\x76\x2f\x31\x01")  # OpenEXR magic
        for channel in (b"R\0", b"G\0", b"B\0", b"A\0", b"Z\0"):
            self.assertIn(channel, data[:400])
        r = json.loads((SCRATCH / "head.report.json").read_text())
        self.assertEqual((r["camera"]["width"], r["camera"]["height"]), (96, 64))
        self.assertFalse(r["camera"]["perspective"])

    def test_main_job_on_every_shared_volume(self):
        for name, (path, *_rest) in VOLUMES.items():
            with self.subTest(volume=name):
                out = SCRATCH / "shared" / (name + ".png")
                arbor("run", DATA / path, "-o", out, "--width", 256, "--height", 256)
                self.assertEqual(png_size(out), (256, 256))
                self.check_report(SCRATCH / "shared" / (name + ".report.json"), out)

    def test_render_with_a_transfer_function_file(self):
        tf, out = SCRATCH / "render-tf.json", SCRATCH / "render.png"
        arbor("tf", "--phantom", "head", "--phantom-size", 64, "--keep", 8, "--shape", "box", "-o", tf)
        code, stdout, _ = arbor("render", "--phantom", "head", "--phantom-size", 64, "--tf", tf, "-o", out,
                                "--width", 128, "--height", 128)
        self.assertEqual(png_size(out), (128, 128))
        # Functions made for another volume are refused, not misapplied.
        code, _, err = arbor("render", "--phantom", "head", "--phantom-size", 64, "--phantom-noise", 5, "--tf", tf,
                             "-o", SCRATCH / "other.png", check=False)
        self.assertNotEqual(code, 0)
        self.assertIn("regenerate them with `arbor tf`", err)

    def test_a_volume_too_large_for_the_memory_is_refused_with_what_it_needs(self):
        """The figures follow from the dimensions: bonsai is 256^3 u8; a run
        keeps the voxels, a filtered copy and 8 B/voxel, and the tree works
        in 20 B/voxel at the least (its order streamed)."""
        voxels = 256 ** 3
        volume = DATA / "bonsai/bonsai.vti"
        out = SCRATCH / "too-large.png"
        out.unlink(missing_ok=True)
        # At the header, before the voxels are read.
        code, _, err = arbor("run", volume, "--no-cache", "-o", out,
                             env={"ARBOR_MEMORY_AVAILABLE": "100000000"}, check=False)
        self.assertEqual(code, 1, err)
        self.assertIn(f"needs about {voxels * 10 / 1e6:.1f} MB", err)
        self.assertIn("and 100.0 MB of memory is available", err)
        self.assertIn(f"contour tree, which needs {voxels * 20 / 1e6:.1f} MB more", err)
        # Unfiltered, the voxels fit; the tree's work space does not.
        code, _, err = arbor("run", volume, "--no-cache", "--filter", "none", "-o", out,
                             env={"ARBOR_MEMORY_AVAILABLE": "250000000"}, check=False)
        self.assertEqual(code, 1, err)
        self.assertIn(f"the contour tree of 256 x 256 x 256 voxels needs about {voxels * 20 / 1e6:.1f} MB", err)
        self.assertFalse(out.exists())
        # With room, the same run goes through.  The tree takes the fastest
        # plan whose work space is at most half of what is available: with
        # 60 B/voxel both sweeps run at once (27), with 50 one after the
        # other (23), with 25 the order is streamed (20).  The tree, and so
        # the image, is the same.
        images = []
        for per_voxel, plan in ((60, "parallel"), (50, "sequential"), (25, "streamed")):
            image = SCRATCH / f"fits-{per_voxel}.png"
            arbor("run", volume, "--no-cache", "--filter", "none", "--width", 64, "--height", 64, "-o", image,
                  env={"ARBOR_MEMORY_AVAILABLE": str(voxels * per_voxel)})
            report = json.loads(image.with_suffix(".report.json").read_text())
            self.assertEqual(report["contour_tree"]["memory_plan"], plan)
            images.append(image.read_bytes())
        self.assertEqual(images[0], images[1], "sweeps at once and one after the other")
        self.assertEqual(images[0], images[2], "the order whole and streamed")

    def test_bad_inputs_are_refused_clearly(self):
        cases = [
            (("--phantom", "head", "-o", SCRATCH / "x.jpg"), "written as .png or .exr"),
            (("--phantom", "head", "--renderer", "opengl", "-o", SCRATCH / "x.png"), "no renderer 'opengl'"),
            ((DATA / "dicom_malformed", "-o", SCRATCH / "x.png"), "choose one with --series"),
            ((SCRATCH / "missing.nrrd", "-o", SCRATCH / "x.png"), "missing.nrrd"),
        ]
        for args, message in cases:
            with self.subTest(args=args):
                code, _, err = arbor("run", *args, "--phantom-size", 32, check=False)
                self.assertNotEqual(code, 0)
                self.assertIn(message, err)
                self.assertRegex(err, r"(?m)^arbor: error:")  # after warnings, if any


class Denoise(unittest.TestCase):
    NOISY = ("--phantom", "head", "--phantom-size", 64, "--phantom-noise", 8)

    def test_filter_before_the_tree(self):
        raw, smooth = SCRATCH / "raw.json", SCRATCH / "smooth.json"
        arbor("simplify", *self.NOISY, "--keep", 5, "--json", raw)
        arbor("simplify", *self.NOISY, "--filter", "gaussian:sigma=4", "--keep", 5, "--json", smooth)
        a, b = json.loads(raw.read_text()), json.loads(smooth.read_text())
        self.assertGreater(a["contour_tree"]["branches"], 5 * b["contour_tree"]["branches"])
        self.assertIn("gaussian:sigma=4", b["volume"]["source"])
        # The same through the generated flag, and on the other commands.
        arbor("tree", *self.NOISY, "--filter", "gaussian", "--gaussian.sigma", 4, "--json", SCRATCH / "t.json")
        t = json.loads((SCRATCH / "t.json").read_text())
        self.assertEqual(len(t["branches"]["kind"]), b["contour_tree"]["branches"])
        arbor("convert", *self.NOISY, "--filter", "median:size=3", "-o", SCRATCH / "median.nrrd")
        self.assertEqual(info(SCRATCH / "median.nrrd")["dims"], [64, 64, 64])

    def test_denoise_study_writes_csv_and_plot(self):
        out = SCRATCH / "study"
        code, stdout, _ = arbor("denoise-study", *self.NOISY, "--to", 16, "--steps", 9, "--out", out)
        rows = (out / "study.csv").read_text().splitlines()
        self.assertEqual(rows[0], "sigma,branches,minima,maxima,seconds,plateau")
        values = [r.split(",") for r in rows[1:]]
        self.assertEqual(len(values), 9)
        counts = [int(v[1]) for v in values]
        self.assertGreater(counts[0], 5 * counts[-1])
        self.assertEqual(sum(int(v[5]) for v in values), 1)
        for v in values:
            self.assertEqual(int(v[1]), int(v[2]) + int(v[3]) - 1)
        # The plateau: after the steepest step, the first whose next step
        # removes under a fifth of it (in log terms), recomputed here.
        drops = [math.log(a) - math.log(b) for a, b in zip(counts, counts[1:])]
        steepest = max(drops)
        plateau = next(i for i in range(1, len(drops)) if i > drops.index(steepest) and drops[i] < 0.2 * steepest)
        self.assertEqual([int(v[5]) for v in values].index(1), plateau)
        self.assertIn("suggested sigma = %s" % values[plateau][0], stdout)
        w, h = png_size(out / "study.png")
        self.assertGreater(w, 600)
        self.assertTrue((out / "study.svg").read_text().startswith("<?xml"))

    def test_denoise_study_says_when_no_plateau_lies_in_the_range(self):
        out = SCRATCH / "study-short"
        _, stdout, _ = arbor("denoise-study", *self.NOISY, "--to", 4, "--steps", 5, "--out", out)
        rows = [r.split(",") for r in (out / "study.csv").read_text().splitlines()[1:]]
        self.assertEqual([r[5] for r in rows], ["0"] * 5)
        self.assertIn("no plateau between sigma = 0 and 4", stdout)
        self.assertIn("try a larger --to", stdout)
        self.assertNotIn("suggested", stdout)

    def test_bad_filter_specs_are_refused_clearly(self):
        for spec, message in (("blur", "no filter 'blur'"), ("gaussian:radius=2", "has no parameter 'radius'"),
                              ("gaussian:sigma", "is not key=value"), ("gaussian:sigma=-1", "sigma")):
            with self.subTest(spec=spec):
                code, _, err = arbor("tree", "--phantom", "head", "--phantom-size", 32, "--filter", spec,
                                     "--json", SCRATCH / "bad.json", check=False)
                self.assertNotEqual(code, 0)
                self.assertIn(message, err)
