#!/usr/bin/env python3
"""Every source path a docs page names exists.

Reads docs/*.md, README.md and examples/*/README.md, takes each `code span` that names a path
under one of the project's folders (dem/, upscale/, fem/, coupling/, tests/, bench/,
examples/, scripts/, docs/, cmake/), expands the brace and star forms the pages use
(`dem/io/run_recorder.{h,cc}`, `dem/io/run_recorder.*`, `upscale/strain/`), and fails,
listing each page and path, when one names nothing in the tree. Paths of files that a run
writes (`snapshots/...`, `fem/column.pvtu`, `bench/results/bed_N.data`) are told apart by
their extension and are not checked. The same for the paths that the comments of the C++
sources name (`// ... (dem/engine/relaxation.h)`), which may also be relative to the file's
folder or to its top folder (`contact/warm_newton.h` in dem/).
"""
import glob
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
OUTPUTS = (".pvtu", ".vtu", ".pvd", ".h5", ".xdmf", ".data", ".png", ".bin")
FOLDERS = ("dem/", "upscale/", "fem/", "coupling/", "tests/", "bench/", "examples/", "scripts/", "docs/",
           "cmake/")


def expand(path):
    m = re.search(r"\{([^}]*)\}", path)
    if m:
        out = []
        for alt in m.group(1).split(","):
            out += expand(path[:m.start()] + alt.strip() + path[m.end():])
        return out
    return [path]


def exists(path):
    full = os.path.join(ROOT, path)
    if any(c in path for c in "*?["):
        return bool(glob.glob(full))
    return os.path.exists(full)


def main():
    pages = glob.glob(os.path.join(ROOT, "docs", "*.md")) + [os.path.join(ROOT, "README.md")] + \
        glob.glob(os.path.join(ROOT, "examples", "*", "README.md")) + \
        glob.glob(os.path.join(ROOT, "bench", "README.md"))
    missing = []
    for page in sorted(pages):
        text = open(page, encoding="utf-8").read()
        for span in re.findall(r"`([^`\n]+)`", text):
            for token in span.split():
                token = token.strip("(),;:")
                if not token.startswith(FOLDERS) or "<" in token or "=" in token or token.endswith(OUTPUTS):
                    continue
                token = re.sub(r"[:#].*$", "", token)  # file:line, file#anchor
                for path in expand(token):
                    if not exists(path):
                        missing.append((os.path.relpath(page, ROOT), path))
    sources = [f for top in FOLDERS for ext in ("h", "cc")
               for f in glob.glob(os.path.join(ROOT, top, "**", "*." + ext), recursive=True)]
    for source in sorted(sources):
        rel = os.path.relpath(source, ROOT)
        for number, line in enumerate(open(source, encoding="utf-8", errors="replace"), 1):
            k = line.find("//")
            if k < 0 or "#include" in line:
                continue
            for token in re.findall(r"(?<![\w/.])((?:%s)[\w./{},*-]*[\w}*])" % "|".join(FOLDERS), line[k:]):
                token = re.sub(r"[:#].*$", "", token)
                if "<" in token or token.endswith(OUTPUTS):
                    continue
                for path in expand(token):
                    if not any(exists(p) for p in (path, os.path.join(os.path.dirname(rel), path),
                                                   os.path.join(rel.split("/")[0], path))):
                        missing.append((f"{rel}:{number}", path))
    for page, path in missing:
        print(f"{page}: names {path}, which does not exist")
    print(f"checked {len(pages)} pages and {len(sources)} sources' comments: {len(missing)} missing paths")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())
