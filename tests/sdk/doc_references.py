#!/usr/bin/python3
"""Every file the installed SDK's documents name must be in the installed SDK:
a third party has the SDK, not Arbor's sources.  Reads the guides in
share/arbor/sdk/docs and the examples' READMEs, takes every `quoted` path
(headers, sources, folders, documents; <arbor/...> includes too) and looks
for it in the installed tree: share/arbor/sdk (examples/, docs/), include/
(include/arbor/, <arbor/...>, a bare header name) and lib/cmake/ArborSDK.

    doc_references.py <install prefix>
"""
import pathlib
import re
import sys

prefix = pathlib.Path(sys.argv[1])
sdk = prefix / "share" / "arbor" / "sdk"
roots = [sdk, sdk / "docs", prefix, prefix / "include", prefix / "include" / "arbor", prefix / "lib" / "cmake" / "ArborSDK"]
documents = sorted((sdk / "docs").glob("*.md")) + sorted((sdk / "examples").glob("*/README.md"))
assert documents, f"no documents under {sdk}"

FILE = re.compile(r"^<?[\w./-]+\.(h|hpp|c|cpp|md|cmake|txt|map|py)>?$")
FOLDER = re.compile(r"^[\w.-]+(/[\w.-]+)*/$")

missing = []
checked = 0
for doc in documents:
    text = doc.read_text()
    for token in re.findall(r"`([^`\n]+)`", text):
        token = token.strip()
        if not (FILE.match(token) or FOLDER.match(token)):
            continue
        name = token.strip("<>")
        here = [doc.parent / name] + [r / name for r in roots]
        checked += 1
        if not any(p.exists() for p in here):
            missing.append(f"{doc.relative_to(prefix)}: `{token}`")

if missing:
    print("documents name files the installed SDK does not contain:\n  " + "\n  ".join(missing))
    sys.exit(1)
print(f"{checked} file references in {len(documents)} documents, all in the installed SDK")
