"""DICOM import end to end: `arbor convert/info/run/dicom ls` on the shared DICOM
data, checked against an independent reading with pydicom (Debian's
python3-pydicom), plus series problems built at test time from real images.

Expected volumes are computed here from pydicom's pixel arrays with the rules
the importer documents (dicom/README.md): slices sorted along the normal of
Image Orientation (Patient), spacing from the positions, irregular gaps
resampled onto round(extent / typical gap) + 1 slices, pixel padding set to
the lowest real value, MONOCHROME1 inverted with the value mapping negated.
"""
import copy
import gzip
import json
import shutil
import unittest

import numpy as np
import pydicom
from pydicom.dataset import Dataset
from pydicom.sequence import Sequence
from pydicom.uid import generate_uid

from test_cli import DATA, SCRATCH, arbor

CT_HEAD = DATA / "dicom_ct_head_0051"
MR_TUMOR = DATA / "dicom_mr_brain_vs_tumor"
WG04 = DATA / "dicom_compressed_wg04"
VARIANTS = DATA / "dicom_pydicom_variants"
MALFORMED = DATA / "dicom_malformed"


def read_nrrd(path):
    """(header fields, array indexed [k, j, i]) of an NRRD file written by arbor."""
    data = path.read_bytes()
    end = data.index(b"\n\n")
    fields = {}
    for line in data[:end].decode().splitlines()[1:]:
        if line.startswith("#"):
            continue
        key, _, value = line.partition(":=") if ":=" in line else line.partition(": ")
        fields[key.strip()] = value.strip()
    body = data[end + 2:]
    if fields["encoding"] == "gzip":
        body = gzip.decompress(body)
    dtype = {"uint8": "u1", "int8": "i1", "uint16": "<u2", "int16": "<i2", "uint32": "<u4",
             "int32": "<i4", "float": "<f4", "double": "<f8"}[fields["type"]]
    nx, ny, nz = map(int, fields["sizes"].split())
    return fields, np.frombuffer(body, dtype=dtype).reshape(nz, ny, nx)


def nrrd_vectors(text):
    return [list(map(float, v.strip("()").split(","))) for v in text.split()]


def convert(source, name, *extra):
    out = SCRATCH / f"{name}.nrrd"
    _, _, err = arbor("convert", source, "-o", out, *extra)
    fields, voxels = read_nrrd(out)
    return fields, voxels, err


class Expected:
    """A series read with pydicom and stacked by the documented rules."""

    def __init__(self, datasets, padding=True):
        first = datasets[0]
        iop = np.array(first.ImageOrientationPatient, float)
        self.row, self.col = iop[:3], iop[3:]
        self.normal = np.cross(self.row, self.col)
        z = np.array([np.dot(np.array(d.ImagePositionPatient, float), self.normal) for d in datasets])
        order = np.argsort(z, kind="stable")
        z = z[order]
        frames = np.stack([datasets[i].pixel_array.astype(np.float64) for i in order])
        self.padded = np.zeros(frames.shape, bool)
        pad = getattr(first, "PixelPaddingValue", None)
        if padding and pad is not None:
            self.padded = frames == pad
        self.origin = np.array(datasets[order[0]].ImagePositionPatient, float)
        ps = [float(v) for v in first.PixelSpacing]
        gaps = np.diff(z)
        typical = np.sort(gaps)[len(gaps) // 2] if len(gaps) else 1.0
        self.exact = []  # per output slice: True when taken as it is
        if len(gaps) and np.any(np.abs(gaps - typical) > max(0.005, 0.02 * typical)):
            extent = z[-1] - z[0]
            m = int(np.round(extent / typical)) + 1
            self.spacing_z = extent / (m - 1)
            slices, masks = [], []
            for k in range(m):
                zk = z[0] + k * self.spacing_z
                j = min(max(np.searchsorted(z, zk, side="right") - 1, 0), len(z) - 2)
                t = min(max((zk - z[j]) / (z[j + 1] - z[j]), 0.0), 1.0)
                if t < 1e-6 or t > 1 - 1e-6:
                    i = j if t < 1e-6 else j + 1
                    slices.append(frames[i]), masks.append(self.padded[i]), self.exact.append(True)
                else:
                    slices.append((1 - t) * frames[j] + t * frames[j + 1])
                    masks.append(self.padded[j] | self.padded[j + 1]), self.exact.append(False)
            frames, self.padded = np.stack(slices), np.stack(masks)
        else:
            self.spacing_z = (z[-1] - z[0]) / (len(z) - 1) if len(z) > 1 else None
            self.exact = [True] * len(z)
        self.values = frames
        if self.padded.any():
            self.values = np.where(self.padded, frames[~self.padded].min(), frames)
        self.spacing = [ps[1], ps[0], self.spacing_z]

    def check(self, test, fields, voxels, exact_tolerance=0, interpolated_tolerance=1):
        test.assertEqual(voxels.shape, self.values.shape)
        directions = nrrd_vectors(fields["space directions"])
        for axis, unit in enumerate((self.row, self.col, self.normal)):
            length = np.linalg.norm(directions[axis])
            if self.spacing[axis] is not None:
                test.assertAlmostEqual(length, self.spacing[axis], places=4)
            np.testing.assert_allclose(np.array(directions[axis]) / length, unit, atol=1e-6)
        np.testing.assert_allclose(nrrd_vectors(fields["space origin"])[0], self.origin, atol=1e-4)
        for k, exact in enumerate(self.exact):
            diff = np.abs(voxels[k].astype(np.float64) - self.values[k])
            limit = exact_tolerance if exact else interpolated_tolerance
            test.assertLessEqual(diff.max(), limit + 1e-9, f"slice {k} ({'exact' if exact else 'interpolated'})")


def read_folder(folder):
    return [pydicom.dcmread(f) for f in sorted(folder.glob("*.dcm"))]


class DicomSeries(unittest.TestCase):
    """The two real multi-file series, against pydicom."""

    def test_head_ct_with_its_irregular_gap(self):
        fields, voxels, err = convert(CT_HEAD, "ct_head")
        expected = Expected(read_folder(CT_HEAD))
        self.assertEqual(voxels.shape, (108, 512, 512))
        self.assertEqual(sum(not e for e in expected.exact) > 0, True)
        expected.check(self, fields, voxels)
        self.assertEqual(fields["type"], "uint16")
        self.assertEqual(float(fields.get("arbor_value_scale", 1)), 1.0)
        self.assertEqual(float(fields["arbor_value_offset"]), -1024.0)
        self.assertEqual(fields["arbor_value_unit"], "HU")
        self.assertIn("irregular (106 gaps of 1.5 mm, 1 of 1 mm)", err)
        self.assertIn("resampled to 108 slices", err)

    def test_one_file_of_a_series_reads_alone_and_says_so(self):
        first = sorted(MR_TUMOR.glob("*.dcm"))[0]
        code, out, err = arbor("info", first, "--json")
        self.assertEqual(json.loads(out)["dims"], [512, 512, 1])
        self.assertIn("is 1 of 120 images of its series in this folder", err)

    def test_head_ct_refuses_irregular_gaps_when_asked(self):
        code, _, err = arbor("info", CT_HEAD, "--dicom.irregular-slices", "refuse", check=False)
        self.assertEqual(code, 1)
        self.assertIn("slice gaps are irregular", err)

    def test_mr_brain_with_tumour(self):
        fields, voxels, err = convert(MR_TUMOR, "mr_tumor")
        expected = Expected(read_folder(MR_TUMOR))
        self.assertTrue(all(expected.exact))
        expected.check(self, fields, voxels)
        self.assertAlmostEqual(float(nrrd_vectors(fields["space directions"])[2][2]), 1.5, places=4)
        self.assertEqual(err.strip(), "")

    def test_listing_of_the_real_series(self):
        listing = json.loads(arbor("dicom", "ls", CT_HEAD, "--json")[1])
        self.assertEqual(len(listing["series"]), 1)
        s = listing["series"][0]
        self.assertEqual((s["modality"], s["frames"], s["dims"]), ("CT", 108, [512, 512, 108]))
        self.assertEqual(s["patient_name"], "CT 0051 - InVesalius Sample")
        self.assertTrue(any("irregular" in n for n in s["notes"]))
        self.assertEqual(listing["not_dicom"], [str(CT_HEAD / "README.md")])
        table = arbor("dicom", "ls", MR_TUMOR)[1]
        for words in ("PATIENT", "STUDY", "SERIES", "MOD", "DESCRIPTION", "SLICES", "SIZE", "SPACING",
                      "MR", "120", "512x512x120", "0.410 x 0.410 x 1.500"):
            self.assertIn(words, table)

    def test_run_on_a_dicom_folder(self):
        uid = pydicom.dcmread(next(MR_TUMOR.glob("*.dcm")), stop_before_pixels=True).SeriesInstanceUID
        out = SCRATCH / "mr_run.png"
        arbor("run", MR_TUMOR, "--series", uid, "--filter", "gaussian:sigma=1", "--width", 128,
              "--height", 128, "-o", out)
        report = json.loads((SCRATCH / "mr_run.report.json").read_text())
        self.assertTrue(report["input"]["importer"].startswith("org.arbor.importer.dicom "))
        self.assertEqual(report["input"]["dims"], [512, 512, 120])
        self.assertGreater(out.stat().st_size, 1000)


class DicomCompressed(unittest.TestCase):
    """WG04 and pydicom samples in every transfer syntax, against the uncompressed copies."""

    def reference(self, path):
        return Expected([pydicom.dcmread(path)])

    def test_lossless_syntaxes_decode_to_the_reference(self):
        for kind in ("CT1", "MR1"):
            expected = self.reference(WG04 / f"{kind}_UNC.dcm")
            for syntax in ("UNC", "JPLL", "JLSL", "J2KR", "RLE"):
                with self.subTest(kind=kind, syntax=syntax):
                    fields, voxels, err = convert(WG04 / f"{kind}_{syntax}.dcm", f"{kind}_{syntax}")
                    expected.check(self, fields, voxels)
                    # CT1 marks the outside of its reconstruction circle as padding.
                    self.assertEqual(expected.padded.any(), kind == "CT1")
                    self.assertEqual("Pixel Padding Value -2000" in err, kind == "CT1")

    def test_near_lossless_and_lossy_stay_close(self):
        ct = self.reference(WG04 / "CT1_UNC.dcm")
        _, voxels, _ = convert(WG04 / "CT1_JLSN.dcm", "CT1_JLSN")
        real = ~ct.padded & (voxels > voxels.min())
        self.assertLessEqual(np.abs(voxels[real] - ct.values[real]).max(), 4)  # near-lossless bound
        mr = self.reference(WG04 / "MR1_UNC.dcm")
        _, voxels, _ = convert(WG04 / "MR1_JPLY.dcm", "MR1_JPLY")
        self.assertLess(np.abs(voxels - mr.values).mean(), 0.01 * np.ptp(mr.values))

    def test_jpeg_2000_lossy_stays_close(self):
        # README of the data: J2KI max abs error 352 (CT1) / 396 (MR1).
        for kind, bound in (("CT1", 352), ("MR1", 396)):
            fields, voxels, _ = convert(WG04 / f"{kind}_J2KI.dcm", f"{kind}_J2KI")
            # Exactly what pydicom (through Pillow's OpenJPEG) decodes...
            self.reference(WG04 / f"{kind}_J2KI.dcm").check(self, fields, voxels)
            # ...and within the documented error of the original.
            original = self.reference(WG04 / f"{kind}_UNC.dcm")
            real = ~original.padded & (voxels > voxels.min())
            diff = np.abs(voxels[real].astype(float) - original.values[real])
            self.assertLessEqual(diff.max(), bound, kind)

    def test_an_undecodable_syntax_is_refused_naming_it(self):
        from pydicom.encaps import encapsulate
        d = pydicom.dcmread(VARIANTS / "MR_small.dcm")
        d.file_meta.TransferSyntaxUID = "1.2.840.10008.1.2.4.100"  # MPEG2 video
        d.PixelData = encapsulate([b"\x00\x00\x01\xb3" + bytes(60)])
        d["PixelData"].VR = "OB"
        d.is_implicit_VR, d.is_little_endian = False, True
        path = SCRATCH / "mpeg2.dcm"
        d.save_as(path, write_like_original=False)
        code, _, err = arbor("info", path, check=False)
        self.assertEqual(code, 1)
        self.assertIn("MPEG2", err)
        self.assertIn("1.2.840.10008.1.2.4.100", err)
        self.assertIn("cannot decode", err)

    def test_byte_orders_and_syntaxes_of_the_small_images(self):
        mr = self.reference(VARIANTS / "MR_small.dcm")
        for name in ("MR_small_implicit", "MR_small_bigendian", "MR_small_expb", "MR_small_RLE",
                     "MR_small_jpeg_ls_lossless", "MR_small_jp2klossless", "MR_small_padded"):
            with self.subTest(name=name):
                fields, voxels, _ = convert(VARIANTS / f"{name}.dcm", name)
                mr.check(self, fields, voxels)
        frames = pydicom.dcmread(VARIANTS / "emri_small.dcm").pixel_array
        for name in ("emri_small", "emri_small_big_endian", "emri_small_RLE", "emri_small_jpeg_ls_lossless",
                     "emri_small_jpeg_2k_lossless"):
            with self.subTest(name=name):
                fields, voxels, _ = convert(VARIANTS / f"{name}.dcm", name)
                np.testing.assert_array_equal(voxels, frames)
                self.assertAlmostEqual(nrrd_vectors(fields["space directions"])[2][2], 1.2)

    def test_deflate_padding_and_jpeg_of_the_other_samples(self):
        fields, voxels, _ = convert(VARIANTS / "image_dfl.dcm", "image_dfl")
        np.testing.assert_array_equal(voxels[0], pydicom.dcmread(VARIANTS / "image_dfl.dcm").pixel_array)
        ct = self.reference(VARIANTS / "CT_small.dcm")
        fields, voxels, err = convert(VARIANTS / "CT_small.dcm", "CT_small")
        ct.check(self, fields, voxels)
        for name in ("JPEG-LL", "JPGExtended", "JPEG-lossy"):  # no JPEG decoder for pydicom here
            _, voxels, _ = convert(VARIANTS / f"{name}.dcm", name)
            self.assertEqual(voxels.shape, (1, 1024, 256))
            self.assertGreater(voxels.std(), 1.0)
        # pydicom decodes JPEG 2000 through Pillow: the NM image, lossy.
        nm = pydicom.dcmread(VARIANTS / "JPEG2000.dcm").pixel_array
        _, voxels, _ = convert(VARIANTS / "JPEG2000.dcm", "JPEG2000")
        np.testing.assert_array_equal(voxels[0], nm)


def small_series(count=12, step=2.0, name="series"):
    """A synthetic axial series from the real 64x64 MR_small image: slice k is the
    image plus 7 k, 2 mm apart, shuffled instance numbers.  Returns datasets."""
    base = pydicom.dcmread(VARIANTS / "MR_small.dcm")
    series_uid = generate_uid()
    pixels = base.pixel_array.astype(np.int16)
    out = []
    for k in range(count):
        d = copy.deepcopy(base)
        d.SOPInstanceUID = generate_uid()
        d.file_meta.MediaStorageSOPInstanceUID = d.SOPInstanceUID
        d.SeriesInstanceUID = series_uid
        d.SeriesDescription = name
        d.InstanceNumber = (k * 5) % count + 1
        d.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
        d.ImagePositionPatient = [-10.0, -20.0, 30.0 + step * k]
        d.PixelData = (pixels + 7 * k).astype(np.int16).tobytes()
        out.append(d)
    return out


def write_series(datasets, folder):
    if folder.exists():
        shutil.rmtree(folder)
    folder.mkdir(parents=True)
    for i, d in enumerate(datasets):
        d.save_as(folder / f"img{i:03d}.dcm", write_like_original=False)
    return folder


class DicomProblems(unittest.TestCase):
    """Series problems, each detected and corrected or refused by name."""

    def test_slices_are_ordered_by_position_not_by_instance_number(self):
        series = small_series()
        folder = write_series(series[::-1], SCRATCH / "ordered")
        fields, voxels, _ = convert(folder, "ordered")
        Expected(series).check(self, fields, voxels)
        self.assertEqual(voxels[5, 10, 10] - voxels[4, 10, 10], 7)

    def test_missing_slices_refused_then_interpolated(self):
        series = small_series()
        folder = write_series(series[:5] + series[7:], SCRATCH / "missing")
        code, _, err = arbor("info", folder, check=False)
        self.assertEqual(code, 1)
        self.assertIn("about 2 slice(s) missing", err)
        self.assertIn("missing-slices = interpolate", err)
        fields, voxels, err = convert(folder, "missing", "--dicom.missing-slices", "interpolate")
        self.assertEqual(voxels.shape[0], 12)
        self.assertIn("filled by linear interpolation", err)
        full = np.stack([d.pixel_array for d in series]).astype(float)
        np.testing.assert_allclose(voxels, full, atol=0.5)  # linear content: interpolation is exact

    def test_a_real_series_without_series_uid_reads_as_one(self):
        # Anonymisers and test exports drop Series Instance UID (type 1): the
        # real MR series with it removed from every file, beside a second,
        # synthetic series that lacks it too (another size and series number).
        real = read_folder(MR_TUMOR)
        synthetic = small_series()
        for d in real + synthetic:
            del d.SeriesInstanceUID
        for d in synthetic:
            d.SeriesNumber = 77
        folder = write_series(real + synthetic, SCRATCH / "no_series_uid")
        listing = json.loads(arbor("dicom", "ls", folder, "--json")[1])
        frames = sorted((s["frames"], s["dims"]) for s in listing["series"])
        self.assertEqual(frames, [(12, [64, 64, 12]), (120, [512, 512, 120])], "two series, not one per file")
        for s in listing["series"]:
            self.assertEqual(s["series_uid"], "")
            self.assertTrue(any("no Series Instance UID" in n for n in s["notes"]), s["notes"])
        row = 1 + [s["frames"] for s in listing["series"]].index(120)
        fields, voxels, err = convert(folder, "no_series_uid", "--series", row)
        self.assertIn("no Series Instance UID in 120 files", err)
        _, original, _ = convert(MR_TUMOR, "mr_tumor_with_uid")
        np.testing.assert_array_equal(voxels, original)

    def test_localizer_is_left_out_and_mixed_sizes_are_refused(self):
        series = small_series()
        scout = copy.deepcopy(series[0])
        scout.SOPInstanceUID = generate_uid()
        scout.ImageType = ["ORIGINAL", "PRIMARY", "LOCALIZER"]
        scout.ImageOrientationPatient = [0, 1, 0, 0, 0, -1]
        folder = write_series(series + [scout], SCRATCH / "localizer")
        fields, voxels, err = convert(folder, "localizer")
        self.assertEqual(voxels.shape, (12, 64, 64))
        self.assertIn("left out 1 localizer image(s)", err)

        odd = copy.deepcopy(series[0])
        odd.SOPInstanceUID = generate_uid()
        odd.ImagePositionPatient = [-10.0, -20.0, 100.0]
        odd.Rows = odd.Columns = 32
        odd.PixelData = np.zeros((32, 32), np.int16).tobytes()
        folder = write_series(series + [odd], SCRATCH / "mixed")
        code, _, err = arbor("info", folder, check=False)
        self.assertEqual(code, 1)
        self.assertIn("mixes image sizes, orientations or formats", err)
        self.assertIn("12 image(s) 64x64 axial", err)
        self.assertIn("1 image(s) 32x32 axial", err)

    def test_two_images_at_one_position_are_refused(self):
        series = small_series()
        twin = copy.deepcopy(series[3])
        twin.SOPInstanceUID = generate_uid()
        folder = write_series(series + [twin], SCRATCH / "twins")
        code, _, err = arbor("info", folder, check=False)
        self.assertEqual(code, 1)
        self.assertIn("1 slice position(s) hold more than one image", err)

    def test_gantry_tilt_is_corrected_exactly_for_whole_pixel_shifts(self):
        series = small_series()
        base = series[0].pixel_array.astype(np.int16)
        pixel = float(series[0].PixelSpacing[0])
        for k, d in enumerate(series):
            # The scanner tilted: slice k sees the anatomy k rows lower.
            shifted = np.full_like(base, base.min())
            shifted[k:] = base[:64 - k]
            d.PixelData = shifted.tobytes()
            d.ImagePositionPatient = [-10.0, -20.0 - k * pixel, 30.0 + 2.0 * k]
        folder = write_series(series, SCRATCH / "tilt")
        fields, voxels, err = convert(folder, "tilt")
        self.assertIn("gantry tilt of about 8.8807 degrees", err)
        for k in range(12):
            np.testing.assert_array_equal(voxels[k, :64 - k], base[:64 - k], f"slice {k}")
        np.testing.assert_allclose(nrrd_vectors(fields["space origin"])[0], [-10, -20, 30])
        code, _, err = arbor("info", folder, "--dicom.gantry-tilt", "refuse", check=False)
        self.assertEqual(code, 1)
        self.assertIn("gantry tilt", err)

    def test_monochrome1_is_inverted_and_physical_values_keep_their_meaning(self):
        series = small_series(count=4)
        for d in series:
            d.PhotometricInterpretation = "MONOCHROME1"
            d.RescaleSlope, d.RescaleIntercept = 2, -100
        folder = write_series(series, SCRATCH / "mono1")
        fields, voxels, err = convert(folder, "mono1")
        stored = np.stack([d.pixel_array for d in series]).astype(np.int64)
        np.testing.assert_array_equal(voxels, -1 - stored)  # signed 16-bit: inverted in range
        scale, offset = float(fields["arbor_value_scale"]), float(fields["arbor_value_offset"])
        np.testing.assert_allclose(voxels * scale + offset, stored * 2 - 100)
        self.assertIn("MONOCHROME1", err)

    def test_frames_with_different_rescale_become_physical_floats(self):
        series = small_series(count=4)
        series[2].RescaleSlope, series[2].RescaleIntercept = 0.5, 10
        folder = write_series(series, SCRATCH / "rescale")
        fields, voxels, err = convert(folder, "rescale")
        self.assertEqual(fields["type"], "float")
        self.assertEqual(float(fields.get("arbor_value_scale", 1)), 1.0)
        np.testing.assert_allclose(voxels[2], series[2].pixel_array * 0.5 + 10)
        np.testing.assert_allclose(voxels[1], series[1].pixel_array)
        self.assertIn("physical values as 32-bit floats", err)

    def test_enhanced_multi_frame_matches_the_classic_series(self):
        series = small_series(count=6)
        classic = write_series(series, SCRATCH / "classic6")
        _, classic_voxels, _ = convert(classic, "classic6")
        order = [3, 0, 5, 1, 4, 2]
        enhanced = copy.deepcopy(series[0])
        enhanced.SOPClassUID = "1.2.840.10008.5.1.4.1.1.4.1"  # Enhanced MR Image Storage
        enhanced.file_meta.MediaStorageSOPClassUID = enhanced.SOPClassUID
        for tag in ("ImagePositionPatient", "ImageOrientationPatient", "PixelSpacing", "SliceThickness"):
            if tag in enhanced:
                delattr(enhanced, tag)
        enhanced.NumberOfFrames = 6
        enhanced.PixelData = b"".join(series[i].PixelData for i in order)
        shared = Dataset()
        measures, orientation = Dataset(), Dataset()
        measures.PixelSpacing = series[0].PixelSpacing
        measures.SliceThickness = 2.0
        orientation.ImageOrientationPatient = [1, 0, 0, 0, 1, 0]
        shared.PixelMeasuresSequence = Sequence([measures])
        shared.PlaneOrientationSequence = Sequence([orientation])
        enhanced.SharedFunctionalGroupsSequence = Sequence([shared])
        frames = []
        for i in order:
            position, item = Dataset(), Dataset()
            position.ImagePositionPatient = series[i].ImagePositionPatient
            item.PlanePositionSequence = Sequence([position])
            frames.append(item)
        enhanced.PerFrameFunctionalGroupsSequence = Sequence(frames)
        folder = write_series([enhanced], SCRATCH / "enhanced")
        fields, voxels, _ = convert(folder, "enhanced")
        np.testing.assert_array_equal(voxels, classic_voxels)
        np.testing.assert_allclose(nrrd_vectors(fields["space origin"])[0], [-10, -20, 30])


class DicomRobustness(unittest.TestCase):
    """Broken files: clear messages, no crash, and the rest of a folder still loads."""

    def test_every_malformed_file_gets_a_clear_answer(self):
        words = {
            "MR_truncated.dcm": "premature end",
            "badVR.dcm": "Number of Frames '1A' is not a number",
            "rtplan_truncated.dcm": "not readable as DICOM",
            "no_meta.dcm": "not readable as DICOM",
            "JPEG2000-embedded-sequence-delimiter.dcm": "corrupt JPEG 2000 header",
            "UN_sequence.dcm": "no DICOM images found",
            "meta_missing_tsyntax.dcm": "no DICOM images found",
            "emri_small_jpeg_2k_lossless_too_short.dcm": "Sequence Delimitation Item missing",
        }
        for path in sorted(MALFORMED.glob("*.dcm")):
            with self.subTest(file=path.name):
                code, _, err = arbor("info", path, check=False)
                self.assertIn(code, (0, 1), err)  # never a crash (negative: killed by a signal)
                if code == 1:
                    self.assertIn("error:", err)
                if path.name in words:
                    self.assertEqual(code, 1)
                    self.assertIn(words[path.name], err)
        # The sound images among them read: a JPEG lossless CT with a broken
        # sequence, a JPEG 2000 CT whose elements are VR UN, and one whose
        # codestream is unsigned where Pixel Representation says signed (read
        # as pydicom reads it).
        self.assertEqual(info_dims(MALFORMED / "bad_sequence.dcm"), [512, 512, 1])
        for name in ("explicit_VR-UN", "J2K_pixelrep_mismatch"):
            fields, voxels, _ = convert(MALFORMED / f"{name}.dcm", name)
            expected = pydicom.dcmread(MALFORMED / f"{name}.dcm").pixel_array
            np.testing.assert_array_equal(voxels[0], expected, name)

    def test_listing_a_malformed_folder_names_every_unreadable_file(self):
        listing = json.loads(arbor("dicom", "ls", MALFORMED, "--json")[1])
        unreadable = {pathlib_name(u["path"]) for u in listing["unreadable"]}
        self.assertTrue({"MR_truncated.dcm", "badVR.dcm", "rtplan_truncated.dcm"} <= unreadable, unreadable)
        readable = [s for s in listing["series"] if s["readable"]]
        self.assertTrue(any(s["modality"] == "CT" for s in readable))
        refused = [s for s in listing["series"] if not s["readable"]]
        self.assertTrue(all(s["problem"] for s in refused))

    def test_broken_and_foreign_files_do_not_stop_the_rest_of_the_folder(self):
        series = small_series(count=9)
        folder = write_series(series[:7], SCRATCH / "damaged")
        series[7].save_as(folder / "truncated.dcm", write_like_original=False)
        del series[8].PixelData
        series[8].save_as(folder / "no-pixels.dcm", write_like_original=False)
        data = (folder / "truncated.dcm").read_bytes()
        (folder / "truncated.dcm").write_bytes(data[:len(data) - 3000])
        (folder / "notes.txt").write_text("scanned on Tuesday\n")
        (folder / "garbage.dcm").write_bytes(bytes(range(256)) * 8)
        shutil.copy(MALFORMED / "rtplan_truncated.dcm", folder / "plan.dcm")
        fields, voxels, err = convert(folder, "damaged")
        self.assertEqual(voxels.shape, (7, 64, 64))
        self.assertIn("could not be read and were left out", err)
        self.assertIn("truncated.dcm", err)
        self.assertIn("left out 1 object(s) without an image, first no-pixels.dcm", err)
        listing = json.loads(arbor("dicom", "ls", folder, "--json")[1])
        self.assertIn(str(folder / "notes.txt"), listing["not_dicom"])
        self.assertIn(str(folder / "garbage.dcm"), listing["not_dicom"])

    def test_names_in_other_character_sets_are_listed_in_utf8(self):
        series = small_series(count=2)
        for d in series:
            d.SpecificCharacterSet = "ISO_IR 100"
            d.PatientName = "M\u00fcller^J\u00fcrgen"
            d.SeriesDescription = "Sch\u00e4del nativ"
        folder = write_series(series, SCRATCH / "latin1")
        self.assertIn(b"M\xfcller", (folder / "img000.dcm").read_bytes())  # stored as Latin-1
        listing = json.loads(arbor("dicom", "ls", folder, "--json")[1])
        self.assertEqual(listing["series"][0]["patient_name"], "M\u00fcller^J\u00fcrgen")
        self.assertEqual(listing["series"][0]["description"], "Sch\u00e4del nativ")
        self.assertIn("M\u00fcller^J\u00fcrgen", arbor("dicom", "ls", folder)[1])

    def test_series_selection(self):
        code, _, err = arbor("info", VARIANTS, check=False)
        self.assertEqual(code, 1)
        self.assertIn("series with images; choose one with --series", err)
        uid = pydicom.dcmread(VARIANTS / "CT_small.dcm", stop_before_pixels=True).SeriesInstanceUID
        self.assertEqual(info_dims(VARIANTS, "--series", uid), [128, 128, 1])
        code, _, err = arbor("info", VARIANTS, "--series", "1.2.3.4", check=False)
        self.assertEqual(code, 1)
        self.assertIn("no series '1.2.3.4'", err)
        code, _, err = arbor("info", DATA / "tooth/tooth.nhdr", "--series", "1", check=False)
        self.assertEqual(code, 2)  # a flag the importer does not take: a wrong command line
        self.assertIn("tooth.nhdr is read by org.arbor.importer.nrrd, which has no parameter 'series' (from --series)",
                      err)


def info_dims(*args):
    return json.loads(arbor("info", *args, "--json")[1])["dims"]


def pathlib_name(path):
    return path.rsplit("/", 1)[-1]


if __name__ == "__main__":
    unittest.main()
