#!/usr/bin/python3
"""What the default `arbor run` gives on real scans, measured and shown.

For each volume: `arbor run` with no flags but a size, then from its report
every branch's visibility share, the framing (how much of the shorter image
side the visible content spans) and the goals of issue 13:
  - every kept non-root branch >= 1 % visibility,
  - the outermost structure (the root branch) <= 40 %,
  - on CT the branch holding the bone among the three most visible,
  - on brain1 the branch of the tumour (given by its mask) among the three most
    visible, by default and with that branch selected (--select, as a click in
    the workstation would);
then a sheet per volume: Arbor's default beside 3D Slicer's one-click presets
rendered by VTK's CPU ray caster on the same view (../shared/tools/slicer_preset.py),
and one sheet of all of them (README.md shows it).

usage: image_quality.py [--arbor build/bin/arbor] [--out build/bench-image-quality] [--size 384] [--only NAME]
Run under xvfb-run (VTK needs X).  Not a test: it prints a table and writes PNGs.
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import time

import numpy as np
from PIL import Image, ImageDraw

ROOT = pathlib.Path(__file__).resolve().parents[2]
SHARED = ROOT.parent / "shared"
DATA = SHARED / "data"
SLICER = SHARED / "tools" / "slicer_preset.py"

CT_PRESETS = ("CT-Chest-Contrast-Enhanced", "CT-Bone")
MR_PRESETS = ("MR-Default",)

# name: (input arguments, presets, what "the structure that matters" is)
VOLUMES = {
    "phantom": (["--phantom", "head", "--phantom-noise", "6", "--phantom-blobs", "12"], MR_PRESETS, None),
    "ct_head_0051": ([str(DATA / "dicom_ct_head_0051")], CT_PRESETS, "bone"),
    "ct_chest_lidc2": ([str(DATA / "ct_chest_lidc2/LIDC2.mha")], MR_PRESETS, None),
    "ct_angio_avm": ([str(DATA / "ct_angio_avm/CT_AVM.nii.gz")], MR_PRESETS, None),
    "mr_brain_colin27": ([str(DATA / "mr_brain_colin27/ch2.nii.gz")], MR_PRESETS, None),
    "mr_brain1_tumour": ([str(DATA / "mr_brain_tumor_pyradiomics/brain1_image.nrrd")], MR_PRESETS,
                         str(DATA / "mr_brain_tumor_pyradiomics/brain1_label.nrrd")),
    "mr_vs_tumour_dicom": ([str(DATA / "dicom_mr_brain_vs_tumor")], MR_PRESETS, None),
}


def run(cmd, **kw):
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if p.returncode != 0:
        raise RuntimeError(f"{' '.join(map(str, cmd))} failed:\n{p.stderr}")
    return p


def framing(png):
    """The visible content's extent (alpha > 0.05 of the brightest pixel, over black)
    as a fraction of the shorter image side."""
    a = np.asarray(Image.open(png).convert("RGB")).astype(float).sum(axis=2)
    mask = a > 0.05 * a.max() if a.max() > 0 else a > 0
    if not mask.any():
        return 0.0
    ys, xs = np.nonzero(mask)
    return max(xs.max() - xs.min() + 1, ys.max() - ys.min() + 1) / min(a.shape)


def label_over(img, text):
    d = ImageDraw.Draw(img)
    d.rectangle([0, img.height - 18, img.width, img.height], fill=(30, 30, 30))
    d.text((6, img.height - 16), text, fill=(235, 235, 235))
    return img


def sheet(tiles, columns):
    w = max(t.width for t in tiles)
    h = max(t.height for t in tiles)
    rows = (len(tiles) + columns - 1) // columns
    out = Image.new("RGB", (columns * w, rows * h), (20, 20, 20))
    for i, t in enumerate(tiles):
        out.paste(t, ((i % columns) * w, (i // columns) * h))
    return out


def ordinal(n):
    return f"{n}{'st' if n == 1 else 'nd' if n == 2 else 'rd' if n == 3 else 'th'}"


def tumour_label(report, labels_nrrd, mask_nrrd):
    """The kept label holding most of the tumour mask's voxels."""
    import gzip
    def read(path):
        b = pathlib.Path(path).read_bytes()
        i = b.index(b"\n\n")
        h = dict(l.split(": ", 1) for l in b[:i].decode().splitlines()[1:] if ": " in l and not l.startswith("#"))
        data = b[i + 2:]
        if h.get("encoding") == "gzip":
            data = gzip.decompress(data)
        t = {"uint8": np.uint8, "uint16": np.uint16, "int16": np.int16, "short": np.int16, "int32": np.int32,
             "uint32": np.uint32, "int": np.int32, "unsigned int": np.uint32}[h["type"]]
        return np.frombuffer(data, dtype=np.dtype(t).newbyteorder("<"))
    labels, mask = read(labels_nrrd), read(mask_nrrd)
    counts = np.bincount(labels[mask > 0], minlength=len(report["branches"]))
    return int(np.argmax(counts))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--arbor", default=str(ROOT / "build/bin/arbor"))
    ap.add_argument("--out", default=str(ROOT / "build/bench-image-quality"))
    ap.add_argument("--size", type=int, default=384)
    ap.add_argument("--only", action="append", default=[])
    ap.add_argument("--extra", default="", help="extra arbor run flags, e.g. '--filter none'")
    args = ap.parse_args()
    out = pathlib.Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    size = str(args.size)
    overview = []
    print(f"{'volume':20} {'branches':>8} {'kept':>4} {'frame':>6} {'root':>6} {'min':>6} {'goal':>24}  seconds")
    for name, (inputs, presets, target) in VOLUMES.items():
        if args.only and not any(o in name for o in args.only):
            continue
        png = out / f"{name}-arbor.png"
        start = time.monotonic()
        run([args.arbor, "run", *inputs, "--width", size, "--height", size, "-o", png,
             "--labels", out / f"{name}-labels.nrrd", *args.extra.split()])
        seconds = time.monotonic() - start
        report = json.loads((out / f"{name}-arbor.report.json").read_text())
        shares = [b["visibility"] for b in report["branches"]]
        order = sorted(range(len(shares)), key=lambda b: -shares[b])
        goals = []
        non_root = shares[1:]
        goals.append("all>=1%" if all(v >= 0.01 for v in non_root) else "some<1%")
        goals.append("root<=40%" if shares[0] <= 0.40 else "root>40%")
        if target == "bone":
            bone = [b for b in range(len(shares)) if report["branches"][b].get("tissues") == ["bone"] or
                    (report["branches"][b].get("hu_range", [0, 0])[0] >= 300)]
            goals.append("bone top3" if any(b in order[:3] for b in bone) else "bone not top3")
        elif target:
            t = tumour_label(report, out / f"{name}-labels.nrrd", target)
            goals.append(f"tumour={t} top3" if t in order[:3] else f"tumour={t} not top3")
            # As a radiologist would look at it: the tumour's branch selected
            # (a click in the workstation, --select here) is brought forward.
            selected_png = out / f"{name}-arbor-selected.png"
            run([args.arbor, "run", *inputs, "--width", size, "--height", size, "-o", selected_png,
                 "--select", t, *args.extra.split()])
            selected = [b["visibility"] for b in
                        json.loads((out / f"{name}-arbor-selected.report.json").read_text())["branches"]]
            rank = 1 + sum(v > selected[t] for v in selected)
            goals.append(f"selected: {ordinal(rank)} {100 * selected[t]:.1f}%")
        frame = framing(png)
        print(f"{name:20} {report['simplification']['branches_before']:>8} {len(shares):>4} {frame:6.2f} "
              f"{100 * shares[0]:5.1f}% {100 * min(non_root or [0]):5.1f}% {' '.join(goals):>24}  {seconds:.1f}")
        print("    visibility by label: " + " ".join(f"{b}:{100 * shares[b]:.1f}%" for b in order))
        # Slicer's presets on the same view, from the same (filtered) volume.
        tiles = [label_over(Image.open(png).convert("RGB"), f"Arbor default: {name}")]
        if target and target != "bone":
            tiles.append(label_over(Image.open(out / f"{name}-arbor-selected.png").convert("RGB"),
                                    "Arbor, the tumour selected"))
        nrrd = out / f"{name}.nrrd"
        run([args.arbor, "convert", *inputs, "-o", nrrd])
        for preset in presets:
            p = out / f"{name}-{preset}.png"
            try:
                run([sys.executable, SLICER, nrrd, preset, p, "--size", size])
                tiles.append(label_over(Image.open(p).convert("RGB"), f"Slicer {preset}"))
            except RuntimeError as e:
                print(f"    {preset}: {e}")
        row = sheet(tiles, len(tiles))
        row.save(out / f"{name}-sheet.png")
        overview.append(sheet(tiles + [Image.new("RGB", tiles[0].size, (20, 20, 20))] * max(0, 3 - len(tiles)), 3))
    if overview:
        sheet(overview, 1).save(out / "defaults-sheet.png")
        print(f"\nsheets: {out}/<volume>-sheet.png, all: {out}/defaults-sheet.png")


if __name__ == "__main__":
    main()
