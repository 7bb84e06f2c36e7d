"""The records of the ABI headers, read from their text: what freeze_abi.py
and padding_asserts.py both need.

    records(folder) -> {name: [field, ...]}, in header order
"""
import pathlib
import re


def fields(body):
    """The field names of a struct body, in order (function pointers by name)."""
    body = re.sub(r"/\*.*?\*/", "", body, flags=re.S)
    names = []
    for decl in body.split(";"):
        decl = " ".join(decl.split())
        if not decl:
            continue
        fp = re.search(r"\(\s*\*\s*(\w+)\s*\)", decl)
        if fp:
            names.append(fp.group(1))
            continue
        for part in decl.split(","):
            names.append(re.search(r"(\w+)\s*(\[[^\]]*\])?\s*$", part.strip()).group(1))
    return names


# Headers of helpers that are not part of the ABI (the host never sees their
# records; their layout may depend on the includer's settings).
HELPERS = {"param_check.h"}


def record_bodies(folder):
    """{name: body} of every struct in the ABI headers of `folder`, in header order."""
    structs = {}
    for header in sorted(pathlib.Path(folder).glob("*.h")):
        if header.name in HELPERS:
            continue
        text = header.read_text()
        for m in re.finditer(r"typedef struct (\w+) \{(.*?)\} \1;", text, re.S):
            structs[m.group(1)] = m.group(2)
        for m in re.finditer(r"\nstruct (\w+) \{(.*?)\};", text, re.S):
            structs[m.group(1)] = m.group(2)
    return structs


def records(folder):
    return {name: fields(body) for name, body in record_bodies(folder).items()}
