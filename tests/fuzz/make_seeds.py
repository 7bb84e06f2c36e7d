#!/usr/bin/env python3
"""Seed corpora for the fuzz harnesses, made from the real files in
../shared/data (see tests/fuzz/README.md).

Volumes are cropped to a few voxels and written again in each encoding their
format has, so that every seed is small and runs fast; DICOM files are taken
as they are (the small ones), or cropped and re-positioned with pydicom into
short series; sessions and transfer-function files are written by the
`arbor` command on the nucleon volume.  Everything is deterministic (gzip
without time stamps, fixed crops), so runs are comparable.

    make_seeds.py --shared ../shared --arbor build/bin/arbor --out SEEDS
writes SEEDS/<harness>/<seed> for every harness, replacing what was there.
"""
import argparse
import base64
import copy
import gzip
import io
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import zlib

CROP = (6, 5, 4)  # voxels kept from the middle of each volume
DICOM_CROP = 16   # rows and columns kept of DICOM images
SERIES_SEPARATOR = b"ARBOR-FUZZ-NEXT-FILE"  # dicom_series.cpp


def gzip_bytes(data):
    out = io.BytesIO()
    with gzip.GzipFile(fileobj=out, mode="wb", mtime=0) as f:
        f.write(data)
    return out.getvalue()


def crop(data, dims, element, size=CROP):
    """The middle size[0] x size[1] x size[2] block of a volume (x fastest)."""
    start = [(d - s) // 2 for d, s in zip(dims, size)]
    out = bytearray()
    for z in range(size[2]):
        for y in range(size[1]):
            row = ((start[2] + z) * dims[1] + start[1] + y) * dims[0] + start[0]
            out += data[row * element:(row + size[0]) * element]
    return bytes(out)


class Seeds:
    def __init__(self, root):
        self.root = root
        self.count = {}

    def write(self, harness, name, data):
        folder = os.path.join(self.root, harness)
        os.makedirs(folder, exist_ok=True)
        with open(os.path.join(folder, name), "wb") as f:
            f.write(data if isinstance(data, bytes) else data.encode())
        self.count[harness] = self.count.get(harness, 0) + 1


# --- NRRD ---------------------------------------------------------------------

def nrrd_header(lines, sizes, encoding, extra=()):
    """A header from another's lines: sizes and encoding replaced, its data file dropped."""
    out = []
    for line in lines:
        key = line.split(":", 1)[0].strip().lower().replace(" ", "")
        if key in ("sizes", "encoding", "datafile", "content"):
            continue
        out.append(line)
    out.insert(1, "sizes: " + " ".join(str(s) for s in sizes))
    out.append("encoding: " + encoding)
    out.extend(extra)
    return "\n".join(out) + "\n\n"


def ascii_values(data, fmt):
    n = len(data) // struct.calcsize(fmt)
    return " ".join(repr(v) if isinstance(v, float) else str(v) for v in struct.unpack("<%d%s" % (n, fmt[-1]), data)) + "\n"


def nrrd_seeds(shared, seeds):
    data = os.path.join(shared, "data")
    # nucleon: detached header, uchar.
    lines = open(os.path.join(data, "nucleon/nucleon.nrrd")).read().splitlines()
    voxels = crop(open(os.path.join(data, "nucleon/nucleon.raw"), "rb").read(), (41, 41, 41), 1)
    seeds.write("nrrd", "nucleon_raw.nrrd", nrrd_header(lines, CROP, "raw").encode() + voxels)
    seeds.write("nrrd", "nucleon_gzip.nrrd", nrrd_header(lines, CROP, "gzip").encode() + gzip_bytes(voxels))
    seeds.write("nrrd", "nucleon_ascii.nrrd", nrrd_header(lines, CROP, "ascii") + ascii_values(voxels, "B"))
    seeds.write("nrrd", "nucleon_skips.nrrd",
                nrrd_header(lines, CROP, "raw", ["line skip: 1", "byte skip: 2"]).encode() + b"skipped\n--" + voxels)
    # The header naming its own file (the harness writes input.nrrd), data at its end.
    seeds.write("nrrd", "nucleon_self.nrrd",
                nrrd_header(lines, CROP, "raw", ["data file: input.nrrd", "byte skip: -1"]).encode() + voxels)
    # tooth: 16-bit big endian.
    lines = open(os.path.join(data, "tooth16_bigendian/tooth.nhdr")).read().splitlines()
    with open(os.path.join(data, "tooth16_bigendian/tooth.raw"), "rb") as f:
        voxels = crop(f.read(), (103, 94, 161), 2)
    seeds.write("nrrd", "tooth16_raw.nrrd", nrrd_header(lines, CROP, "raw").encode() + voxels)
    seeds.write("nrrd", "tooth16_gzip.nrrd", nrrd_header(lines, CROP, "gzip").encode() + gzip_bytes(voxels))
    # pyradiomics: NRRD0004 with space directions, origin, kinds, gzip.
    for name in ("brain1_label.nrrd", "brain1_image.nrrd"):
        with open(os.path.join(data, "mr_brain_tumor_pyradiomics", name), "rb") as f:
            raw = f.read()
        end = raw.index(b"\n\n") + 2
        lines = raw[:end].decode().strip("\n").splitlines()
        sizes = [int(s) for s in next(l for l in lines if l.startswith("sizes:")).split()[1:]]
        kind = next(l for l in lines if l.startswith("type:")).split(":", 1)[1].strip()
        element = {"int": 4, "short": 2, "unsigned char": 1, "uchar": 1}[kind]
        voxels = crop(zlib.decompress(raw[end:], 15 + 32), sizes, element)
        stem = name.split(".")[0]
        seeds.write("nrrd", stem + "_gzip.nrrd", nrrd_header(lines, CROP, "gzip").encode() + gzip_bytes(voxels))
        seeds.write("nrrd", stem + "_ascii.nrrd",
                    nrrd_header(lines, CROP, "ascii") + ascii_values(voxels, "i" if element == 4 else "h"))
    # Detached headers as they are (their data files are not beside the input).
    for path in ("neghip/neghip.nhdr", "tooth/tooth.nhdr", "bucky/bucky.nhdr", "walnut/walnut.nhdr"):
        with open(os.path.join(data, path), "rb") as f:
            seeds.write("nrrd", os.path.basename(path), f.read())


# --- MetaImage ------------------------------------------------------------------

def mha(fields, data):
    return "".join("%s = %s\n" % kv for kv in fields).encode() + data


def replace_fields(fields, **changes):
    out = [(k, changes.pop(k) if k in changes else v) for k, v in fields]
    out = [(k, v) for k, v in out if v is not None]
    last = out.pop()  # ElementDataFile stays last
    return out + list(changes.items()) + [last]


def metaimage_seeds(shared, seeds):
    data = os.path.join(shared, "data")
    with open(os.path.join(data, "ct_chest_lidc2/LIDC2.mha"), "rb") as f:
        raw = f.read()
    end = raw.index(b"ElementDataFile = LOCAL\n") + len(b"ElementDataFile = LOCAL\n")
    fields = [tuple(s.strip() for s in l.split("=", 1)) for l in raw[:end].decode().splitlines()]
    dims = [int(s) for s in dict(fields)["DimSize"].split()]
    voxels = crop(zlib.decompress(raw[end:]), dims, 1)
    size = " ".join(str(s) for s in CROP)
    packed = zlib.compress(voxels, 9)
    seeds.write("metaimage", "lidc2_zlib.mha",
                mha(replace_fields(fields, DimSize=size, CompressedDataSize=str(len(packed))), packed))
    seeds.write("metaimage", "lidc2_zlib_unsized.mha",
                mha(replace_fields(fields, DimSize=size, CompressedDataSize=None), packed))
    seeds.write("metaimage", "lidc2_raw.mha",
                mha(replace_fields(fields, DimSize=size, CompressedData="False", CompressedDataSize=None), voxels))
    seeds.write("metaimage", "lidc2_at_end.mha",
                mha(replace_fields(fields, DimSize=size, CompressedData="False", CompressedDataSize=None,
                                   HeaderSize="-1"), b"padding" + voxels))
    # HeadMRVolume: a detached header; made local, raw and as text.
    with open(os.path.join(data, "mr_head_lowres/HeadMRVolume.mhd"), "rb") as f:
        header = f.read()
    seeds.write("metaimage", "HeadMRVolume.mhd", header)
    fields = [tuple(s.strip() for s in l.split("=", 1)) for l in header.decode().splitlines() if "=" in l]
    dims = [int(s) for s in dict(fields)["DimSize"].split()]
    with open(os.path.join(data, "mr_head_lowres/HeadMRVolume.raw"), "rb") as f:
        voxels = crop(f.read(), dims, 1)
    seeds.write("metaimage", "head_local.mha", mha(replace_fields(fields, DimSize=size, ElementDataFile="LOCAL"), voxels))
    seeds.write("metaimage", "head_ascii.mha",
                mha(replace_fields(fields, DimSize=size, BinaryData="False", ElementDataFile="LOCAL"),
                    ascii_values(voxels, "B").encode()))
    seeds.write("metaimage", "head_self.mha",
                mha(replace_fields(fields, DimSize=size, HeaderSize="-1", ElementDataFile="input.mha"), voxels))


# --- NIfTI ---------------------------------------------------------------------

def nifti1_to_nifti2(header, data):
    """The same image with a NIfTI-2 header (nifti2.h layout), voxels at 544."""
    u = lambda fmt, at: struct.unpack_from("<" + fmt, header, at)
    h = bytearray(544)
    struct.pack_into("<i", h, 0, 540)
    h[4:12] = b"n+2\0\r\n\x1a\n"
    struct.pack_into("<hh", h, 12, *u("hh", 70))
    struct.pack_into("<8q", h, 16, *u("8h", 40))
    struct.pack_into("<3d", h, 80, *u("3f", 56))
    struct.pack_into("<8d", h, 104, *u("8f", 76))
    struct.pack_into("<q", h, 168, 544)
    struct.pack_into("<6d", h, 176, *u("2f", 112), *u("4f", 124))
    struct.pack_into("<2q", h, 224, u("h", 74)[0], u("h", 120)[0])
    h[240:320] = header[148:228]
    h[320:344] = header[228:252]
    struct.pack_into("<2i", h, 344, *u("2h", 252))
    struct.pack_into("<6d", h, 352, *u("6f", 256))
    struct.pack_into("<12d", h, 400, *u("12f", 280))
    struct.pack_into("<3i", h, 496, header[122], header[123], u("h", 68)[0])
    h[508:524] = header[328:344]
    h[524] = header[39]
    return bytes(h) + data


def nifti_seeds(shared, seeds):
    data = os.path.join(shared, "data")
    for path in ("mr_brain_colin27/ch2.nii.gz", "ct_angio_avm/CT_AVM.nii.gz"):
        with gzip.open(os.path.join(data, path)) as f:
            raw = f.read()
        if struct.unpack_from("<i", raw, 0)[0] != 348:
            sys.exit("make_seeds: %s is not a little-endian NIfTI-1 file" % path)
        dims = struct.unpack_from("<8h", raw, 40)
        bitpix = struct.unpack_from("<h", raw, 72)[0]
        offset = int(struct.unpack_from("<f", raw, 108)[0])
        header = bytearray(raw[:offset])
        struct.pack_into("<8h", header, 40, 3, *CROP, 1, 1, 1, 1)
        voxels = crop(raw[offset:], dims[1:4], bitpix // 8)
        stem = os.path.basename(path).split(".")[0]
        seeds.write("nifti", stem + ".nii", bytes(header) + voxels)
        seeds.write("nifti", stem + ".nii.gz", gzip_bytes(bytes(header) + voxels))
        seeds.write("nifti", stem + "_nifti2.nii", nifti1_to_nifti2(bytes(header[:348]), voxels))


# --- VTK -----------------------------------------------------------------------

def legacy_seeds(shared, seeds):
    with open(os.path.join(shared, "data/ironprot/ironProt.vtk"), "rb") as f:
        raw = f.read()
    marker = b"LOOKUP_TABLE default\n"
    end = raw.index(marker) + len(marker)
    voxels = crop(raw[end:end + 68 ** 3], (68, 68, 68), 1)
    head = raw[:end].decode()
    head = head.replace("DIMENSIONS 68 68 68", "DIMENSIONS %d %d %d" % CROP)
    head = head.replace("POINT_DATA %d" % 68 ** 3, "POINT_DATA %d" % len(voxels))
    seeds.write("vtk_image", "ironprot_binary.vtk", head.encode() + voxels + b"\n")
    seeds.write("vtk_image", "ironprot_ascii.vtk", head.replace("BINARY", "ASCII") + ascii_values(voxels, "B"))
    field = head[:head.index("SCALARS")] + "FIELD FieldData 1\ndensity 1 %d unsigned_char\n" % len(voxels)
    seeds.write("vtk_image", "ironprot_field.vtk", field.encode() + voxels + b"\n")


def vtk_blocks(data, header_type):
    """VTK's compressed-data layout: a header of block counts and sizes, then zlib blocks."""
    packed = zlib.compress(data, 9)
    h = "<4I" if header_type == "UInt32" else "<4Q"
    return struct.pack(h, 1, 32768, len(data), len(packed)), packed


def vti(attributes, array_type, name, extent, array, appended=None):
    out = ['<?xml version="1.0"?>',
           '<VTKFile type="ImageData" version="1.0" byte_order="LittleEndian" %s>' % attributes,
           '  <ImageData WholeExtent="%s" Origin="0 0 0" Spacing="1 1 1">' % extent,
           '  <Piece Extent="%s">' % extent,
           '    <PointData Scalars="%s">' % name,
           '      <DataArray type="%s" Name="%s" %s' % (array_type, name, array),
           '    </PointData>', '    <CellData>', '    </CellData>', '  </Piece>', '  </ImageData>']
    text = "\n".join(out) + "\n"
    if appended is None:
        return (text + "</VTKFile>\n").encode()
    encoding, data = appended
    return (text + '  <AppendedData encoding="%s">\n   _' % encoding).encode() + data + b"\n  </AppendedData>\n</VTKFile>\n"


def xml_seeds(shared, seeds):
    data = os.path.join(shared, "data")
    extent = "0 %d 0 %d 0 %d" % tuple(s - 1 for s in CROP)
    # hydrogen: Float32 inline, base64, zlib, UInt32 headers.
    text = open(os.path.join(data, "hydrogen_orbital/hydrogen.vti")).read()
    encoded = re.search(r'<DataArray[^>]*format="binary"[^>]*>\s*([A-Za-z0-9+/=]+)', text).group(1)
    blocks = struct.unpack_from("<I", base64.b64decode(encoded[:8]), 0)[0]
    header_length = 4 * math.ceil((3 + blocks) * 4 / 3)
    header = struct.unpack("<%dI" % (3 + blocks), base64.b64decode(encoded[:header_length])[:(3 + blocks) * 4])
    packed = base64.b64decode(encoded[header_length:])
    raw, at = b"", 0
    for size in header[3:]:
        raw += zlib.decompress(packed[at:at + size])
        at += size
    voxels = crop(raw, (64, 64, 64), 4)
    h, z = vtk_blocks(voxels, "UInt32")
    zlib32 = 'header_type="UInt32" compressor="vtkZLibDataCompressor"'
    seeds.write("vtk_image", "hydrogen_zlib.vti",
                vti(zlib32, "Float32", "density", extent,
                    'format="binary">\n        %s\n      </DataArray>' %
                    (base64.b64encode(h) + base64.b64encode(z)).decode()))
    seeds.write("vtk_image", "hydrogen_binary.vti",
                vti('header_type="UInt32"', "Float32", "density", extent,
                    'format="binary">\n        %s\n      </DataArray>' %
                    base64.b64encode(struct.pack("<I", len(voxels)) + voxels).decode()))
    seeds.write("vtk_image", "hydrogen_ascii.vti",
                vti('header_type="UInt32"', "Float32", "density", extent,
                    'format="ascii">\n        %s      </DataArray>' % ascii_values(voxels, "f")))
    # engine: UInt8 appended raw, zlib, UInt64 headers.
    with open(os.path.join(data, "engine/engine.vti"), "rb") as f:
        raw = f.read()
    at = raw.index(b"_", raw.index(b"<AppendedData")) + 1
    blocks, _, _ = struct.unpack_from("<3Q", raw, at)
    sizes = struct.unpack_from("<%dQ" % blocks, raw, at + 24)
    at += 24 + 8 * blocks
    plain = b""
    for size in sizes:
        plain += zlib.decompress(raw[at:at + size])
        at += size
    voxels = crop(plain, (256, 256, 128), 1)
    h, z = vtk_blocks(voxels, "UInt64")
    appended = 'format="appended" offset="0">\n      </DataArray>'
    zlib64 = 'header_type="UInt64" compressor="vtkZLibDataCompressor"'
    seeds.write("vtk_image", "engine_appended_zlib.vti",
                vti(zlib64, "UInt8", "ImageFile", extent, appended, ("raw", h + z)))
    seeds.write("vtk_image", "engine_appended_raw.vti",
                vti('header_type="UInt64"', "UInt8", "ImageFile", extent, appended,
                    ("raw", struct.pack("<Q", len(voxels)) + voxels)))
    seeds.write("vtk_image", "engine_appended_base64.vti",
                vti(zlib64, "UInt8", "ImageFile", extent, appended,
                    ("base64", base64.b64encode(h) + base64.b64encode(z))))


# --- DICOM ---------------------------------------------------------------------

def dicom_bytes(ds):
    out = io.BytesIO()
    ds.save_as(out, write_like_original=False)
    return out.getvalue()


def cropped(ds, frames=1):
    """`ds` with its first `frames` frames cut to DICOM_CROP x DICOM_CROP pixels."""
    ds = copy.deepcopy(ds)
    rows, columns, size = ds.Rows, ds.Columns, ds.BitsAllocated // 8
    r0, c0 = (rows - DICOM_CROP) // 2, (columns - DICOM_CROP) // 2
    pixels = bytearray()
    for f in range(frames):
        for r in range(r0, r0 + DICOM_CROP):
            at = ((f * rows + r) * columns + c0) * size
            pixels += ds.PixelData[at:at + DICOM_CROP * size]
    ds.Rows = ds.Columns = DICOM_CROP
    ds.PixelData = bytes(pixels)
    if "NumberOfFrames" in ds:
        ds.NumberOfFrames = frames
    return ds


def placed(ds, position, number):
    ds = copy.deepcopy(ds)
    ds.ImagePositionPatient = [round(p, 4) for p in position]
    ds.InstanceNumber = number
    ds.SOPInstanceUID = "%s.%d" % (ds.SOPInstanceUID, number)
    return ds


def series(seeds, name, policy, datasets):
    seeds.write("dicom_series", name, bytes([policy]) + SERIES_SEPARATOR.join(dicom_bytes(d) for d in datasets))


def enhanced(base, frames):
    """An Enhanced-MR-like object: per-frame positions in functional groups."""
    from pydicom.dataset import Dataset
    from pydicom.sequence import Sequence
    ds = copy.deepcopy(base)
    shared, measures, plane = Dataset(), Dataset(), Dataset()
    measures.PixelSpacing = ds.PixelSpacing
    measures.SliceThickness = 2
    plane.ImageOrientationPatient = ds.ImageOrientationPatient
    shared.PixelMeasuresSequence = Sequence([measures])
    shared.PlaneOrientationSequence = Sequence([plane])
    ds.SharedFunctionalGroupsSequence = Sequence([shared])
    per_frame = []
    for f in range(frames):
        item, position = Dataset(), Dataset()
        position.ImagePositionPatient = [ds.ImagePositionPatient[0], ds.ImagePositionPatient[1],
                                         ds.ImagePositionPatient[2] + 2 * f]
        item.PlanePositionSequence = Sequence([position])
        per_frame.append(item)
    ds.PerFrameFunctionalGroupsSequence = Sequence(per_frame)
    for tag in ("ImagePositionPatient", "ImageOrientationPatient", "PixelSpacing"):
        delattr(ds, tag)
    ds.NumberOfFrames = frames
    ds.PixelData = ds.PixelData * frames
    return ds


def dicom_seeds(shared, seeds):
    import pydicom
    data = os.path.join(shared, "data")
    # dicom_file: the small files as they are, the broken ones included.
    for folder in ("dicom_pydicom_variants", "dicom_malformed", "dicom_compressed_wg04"):
        for name in sorted(os.listdir(os.path.join(data, folder))):
            path = os.path.join(data, folder, name)
            if name.endswith(".dcm") and os.path.getsize(path) <= 128 * 1024:
                with open(path, "rb") as f:
                    seeds.write("dicom_file", folder + "_" + name, f.read())
    variants = os.path.join(data, "dicom_pydicom_variants")
    mr = pydicom.dcmread(os.path.join(variants, "MR_small.dcm"))
    small = cropped(mr)
    seeds.write("dicom_file", "enhanced_mr.dcm", dicom_bytes(enhanced(small, 3)))

    # dicom_series: short series of cropped images placed along the normal.
    o = [float(v) for v in small.ImageOrientationPatient]
    normal = [o[1] * o[5] - o[2] * o[4], o[2] * o[3] - o[0] * o[5], o[0] * o[4] - o[1] * o[3]]
    base = [float(v) for v in small.ImagePositionPatient]
    at = lambda z, shift=0.0: [base[a] + z * normal[a] + shift * o[a] for a in range(3)]
    stack = lambda zs, shifts=None: [placed(small, at(z, (shifts or [0] * len(zs))[i]), i + 1)
                                     for i, z in enumerate(zs)]
    series(seeds, "regular", 0, stack([0, 2, 4]))
    series(seeds, "irregular", 0, stack([0, 2, 5, 7]))
    series(seeds, "irregular_refused", 1, stack([0, 2, 5, 7]))
    series(seeds, "missing_interpolated", 2, stack([0, 2, 4, 8]))
    series(seeds, "tilted", 0, stack([0, 2, 4], [0, 0.5, 1.0]))
    series(seeds, "tilt_refused", 4, stack([0, 2, 4], [0, 0.5, 1.0]))
    no_geometry = stack([0, 2, 4])
    for ds in no_geometry:
        del ds.ImagePositionPatient
        del ds.ImageOrientationPatient
    series(seeds, "no_geometry", 0, no_geometry)
    padded = stack([0, 2])
    for ds in padded:
        ds.PhotometricInterpretation = "MONOCHROME1"
        ds.add_new(0x00280120, "US", 0)  # Pixel Padding Value
    series(seeds, "monochrome1_padding", 0, padded)
    series(seeds, "enhanced", 0, [enhanced(small, 3)])
    emri = pydicom.dcmread(os.path.join(variants, "emri_small.dcm"))
    series(seeds, "multiframe", 0, [cropped(emri, 3)])
    with open(os.path.join(variants, "MR_small_jp2klossless.dcm"), "rb") as f:
        jp2k = f.read()
    with open(os.path.join(variants, "MR_small_RLE.dcm"), "rb") as f:
        rle = f.read()
    seeds.write("dicom_series", "same_instance_three_syntaxes",
                b"\0" + SERIES_SEPARATOR.join([dicom_bytes(mr), jp2k, rle]))

    # jpeg2000: every JPEG 2000 frame of the small files, after its size.
    from pydicom.encaps import generate_pixel_data_frame
    for folder, name in (("dicom_pydicom_variants", "MR_small_jp2klossless.dcm"),
                         ("dicom_pydicom_variants", "JPEG2000.dcm"),
                         ("dicom_pydicom_variants", "emri_small_jpeg_2k_lossless.dcm"),
                         ("dicom_compressed_wg04", "CT1_J2KI.dcm"), ("dicom_compressed_wg04", "MR1_J2KI.dcm"),
                         ("dicom_malformed", "JPEG2000-embedded-sequence-delimiter.dcm")):
        ds = pydicom.dcmread(os.path.join(data, folder, name))
        frames = int(ds.get("NumberOfFrames", 1) or 1)
        for i, frame in enumerate(generate_pixel_data_frame(ds.PixelData, frames)):
            if i == 2:
                break
            seeds.write("jpeg2000", "%s_%d.j2k" % (name[:-4], i), struct.pack("<HH", ds.Columns, ds.Rows) + frame)

    # multipart: WADO-RS answers carrying small DICOM files.
    with open(os.path.join(variants, "image_dfl.dcm"), "rb") as f:
        deflated = f.read()
    part = lambda boundary, body: b"--" + boundary + b"\r\nContent-Type: application/dicom\r\n\r\n" + body + b"\r\n"
    seeds.write("multipart", "two_parts",
                b'multipart/related; type="application/dicom"; boundary=abc123\n' +
                part(b"abc123", rle) + part(b"abc123", deflated) + b"--abc123--\r\n")
    seeds.write("multipart", "quoted_preamble_epilogue",
                b'multipart/related; boundary="x y"; type="application/dicom"\n'
                b"preamble\r\n" + part(b"x y", deflated) + b"--x y--\r\nepilogue")


# --- sessions and transfer functions (written by `arbor`) -------------------

def arbor_seeds(shared, arbor, seeds):
    nucleon = os.path.abspath(os.path.join(shared, "data/nucleon/nucleon.nrrd"))
    with tempfile.TemporaryDirectory() as tmp:
        def run(*args):
            subprocess.run([arbor] + list(args), check=True, cwd=tmp, stdout=subprocess.DEVNULL)

        small = ["--width", "32", "--height", "32", "--keep", "4", "--no-cache"]
        run("run", nucleon, "-o", "a.png", *small, "--save-session", "plain.json")
        run("run", nucleon, "-o", "b.png", *small, "--filter", "gaussian:sigma=1", "--azimuth", "30",
            "--save-session", "filtered.json")
        run("run", "--phantom", "head", "--phantom-size", "16", "-o", "c.png", *small,
            "--save-session", "phantom.json")
        run("tf", nucleon, "--keep", "4", "--lut-size", "16", "--no-cache", "-o", "tf.json")
        run("tf", nucleon, "--keep", "4", "--lut-size", "16", "--relation", "neighbour", "--select", "1",
            "--no-cache", "-o", "tf_neighbour.json")
        for name in ("plain.json", "filtered.json", "phantom.json"):
            with open(os.path.join(tmp, name)) as f:
                session = json.load(f)
            # The session names its input relative to its own folder; the
            # harness reads it from another, so it names it in full.
            if "path" in session["input"]:
                session["input"]["path"] = nucleon
            seeds.write("session", name, json.dumps(session, indent=2) + "\n")
        for name in ("tf.json", "tf_neighbour.json"):
            with open(os.path.join(tmp, name), "rb") as f:
                seeds.write("transfer_functions", name, f.read())


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--shared", required=True, help="the shared folder (with data/INDEX.md)")
    parser.add_argument("--arbor", required=True, help="the arbor command (writes session and TF seeds)")
    parser.add_argument("--out", required=True, help="folder for <harness>/<seed>")
    args = parser.parse_args()
    if not os.path.exists(os.path.join(args.shared, "data/INDEX.md")):
        sys.exit("make_seeds: no data/INDEX.md under %s" % args.shared)
    shutil.rmtree(args.out, ignore_errors=True)
    seeds = Seeds(args.out)
    nrrd_seeds(args.shared, seeds)
    metaimage_seeds(args.shared, seeds)
    nifti_seeds(args.shared, seeds)
    legacy_seeds(args.shared, seeds)
    xml_seeds(args.shared, seeds)
    dicom_seeds(args.shared, seeds)
    arbor_seeds(args.shared, args.arbor, seeds)
    for harness in sorted(seeds.count):
        print("%-20s %3d seeds" % (harness, seeds.count[harness]))


if __name__ == "__main__":
    main()
