#!/usr/bin/env python3
"""The layers of docs/architecture.md ("Folders") are the code's.

Reads the two tables of that section: the folders of dem/ with the folders each includes, and
the targets outside dem/ with what each depends on. Fails, naming each file and line, when
- a file of dem/ includes a header of a dem/ folder its row does not list, or any header of
  fem/, upscale/ or coupling/, or deal.II;
- a row of the dem/ table lists a folder no file of it includes (the table says more than the
  code), or a folder not above it (the layers are in the table's order, so none is a cycle);
- dem/CMakeLists.txt links a folder's target (USES dem_...) to other folders than its row;
- a file of upscale/, fem/ or coupling/ includes a project header of a target that its own
  target does not depend on, directly or through others.
"""
import fnmatch
import glob
import os
import re
import sys

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
DOC = os.path.join(ROOT, "docs", "architecture.md")
EXTERNAL = {"deal.II", "Trilinos", "CGAL", "Eigen", "MPI", "HDF5"}
INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^">]+)[">]')


def section(text, title):
    start = text.index("## " + title + "\n")
    end = text.find("\n## ", start + 1)
    return text[start:end if end >= 0 else len(text)]


def table_rows(text):
    """The rows of every Markdown table in `text`, each a list of cells, headers excluded."""
    rows = []
    lines = text.splitlines()
    for k, line in enumerate(lines):
        if not line.startswith("|") or re.match(r"^\|[-| ]+\|$", line):
            continue
        if k + 1 < len(lines) and re.match(r"^\|[-| ]+\|$", lines[k + 1]):
            rows.append(None)  # a header: the next rows start a new table
            continue
        rows.append([c.strip() for c in line.strip().strip("|").split("|")])
    tables, current = [], None
    for r in rows:
        if r is None:
            current = []
            tables.append(current)
        else:
            current.append(r)
    return tables


def spans(cell):
    return re.findall(r"`([^`]+)`", cell)


def names(cell):
    """`core, scene, shape` -> ["core", "scene", "shape"]; an em dash is none."""
    out = []
    for part in cell.split(","):
        part = part.strip().strip("`").strip()
        if part and part != "—":
            out.append(part.split()[0])
    return out


def dem_layer(path):
    """The dem/ folder of `path` (a path below dem/): its first folder, or the stem of a file
    at dem/'s top (dem/time_step.h -> time_step)."""
    rest = path[len("dem/"):]
    if "/" in rest:
        return rest.split("/")[0]
    return rest.split(".")[0]


def sources(folder):
    for ext in ("h", "cc"):
        yield from glob.glob(os.path.join(ROOT, folder, "**", "*." + ext), recursive=True)


def includes(path):
    with open(path, encoding="utf-8") as f:
        for number, line in enumerate(f, 1):
            m = INCLUDE.match(line)
            if m:
                yield number, m.group(1)


def main():
    text = section(open(DOC, encoding="utf-8").read(), "Folders")
    dem_table, outside_table = table_rows(text)[:2]
    errors = []

    # The dem/ table, in order.
    allowed, order = {}, []
    for row in dem_table:
        layer = spans(row[0])[0].removeprefix("dem/").rstrip("/").split(".")[0]  # core/, time_step.*
        deps = names(row[1])
        for d in deps:
            if d not in order:
                errors.append(f"docs/architecture.md: {layer}/ includes {d}, which is not a folder above it")
        allowed[layer] = set(deps)
        order.append(layer)

    # Every include of dem/ against it.
    used = {layer: set() for layer in allowed}
    for path in sources("dem"):
        rel = os.path.relpath(path, ROOT)
        layer = dem_layer(rel)
        if layer not in allowed:
            errors.append(f"{rel}: folder {layer}/ is not in the table of docs/architecture.md")
            continue
        for number, header in includes(path):
            where = f"{rel}:{number}: includes {header}"
            if header.startswith(("fem/", "upscale/", "coupling/", "deal.II/")):
                errors.append(f"{where}: dem/ includes nothing outside it")
            elif header.startswith("dem/"):
                target = dem_layer(header)
                if target == layer:
                    continue
                used[layer].add(target)
                if target not in allowed[layer]:
                    errors.append(f"{where}: {layer}/ may include only {', '.join(sorted(allowed[layer])) or 'none'}"
                                  " (docs/architecture.md, \"Folders\")")
    for layer in order:
        for d in sorted(allowed[layer] - used[layer]):
            errors.append(f"docs/architecture.md: {layer}/ lists {d}, which none of its files includes")

    # The CMake targets link what the table says.
    cmake = open(os.path.join(ROOT, "dem", "CMakeLists.txt"), encoding="utf-8").read()
    linked = {}
    for m in re.finditer(r"upgrain_dem_folder\((\w+)(.*?)\)", cmake, re.S):
        uses = re.search(r"USES(.*?)(SOURCES|$)", m.group(2), re.S)
        linked[m.group(1)] = {u[len("dem_"):] for u in (uses.group(1).split() if uses else []) if u.startswith("dem_")}
    for layer in order:
        if layer not in linked:
            errors.append(f"dem/CMakeLists.txt: no target for {layer}/ (upgrain_dem_folder)")
        elif linked[layer] != allowed[layer]:
            errors.append(f"dem/CMakeLists.txt: dem_{layer} links {', '.join(sorted(linked[layer])) or 'none'}, "
                          f"docs/architecture.md lists {', '.join(sorted(allowed[layer])) or 'none'}")
    for layer in sorted(set(linked) - set(order)):
        errors.append(f"dem/CMakeLists.txt: dem_{layer} is no folder of docs/architecture.md")

    # Outside dem/: targets by folder, and what each depends on.
    # A target's files: its folders (path prefixes) and patterns (with *, such as a study's
    # `coupling/studies/*/*_checks.*` in the input layer); a file is the target's whose prefix or
    # pattern is the longest that matches it.
    folder_of, depends = {}, {}
    for row in outside_table:
        target = spans(row[0])[0].removeprefix("upgrain::")
        folder_of[target] = spans(row[1])
        depends[target] = [d for d in names(row[2]) if d not in EXTERNAL]
    folder_of["dem"] = ["dem/"]
    depends["dem"] = []
    for layer in order:  # a dem/ folder may be named alone (fem: `dem/files/`)
        folder_of["dem/" + layer + "/"] = ["dem/" + layer + "/"]
        depends["dem/" + layer + "/"] = []
    for target, deps in depends.items():
        for d in deps:
            if d not in depends and d != "all":
                errors.append(f"docs/architecture.md: {target} depends on {d}, which is not a target of the tables")

    def target_of(path):
        best, best_length = None, -1
        for t, patterns in folder_of.items():
            for p in patterns:
                matches = fnmatch.fnmatch(path, p) if "*" in p else path.startswith(p)
                if matches and len(p) > best_length:
                    best, best_length = t, len(p)
        return best

    def reach(target):
        seen, todo = set(), [target]
        while todo:
            t = todo.pop()
            for d in depends.get(t, []):
                if d not in seen:
                    seen.add(d)
                    todo.append(d)
        return seen

    for top in ("upscale", "fem", "coupling"):
        for path in sources(top):
            rel = os.path.relpath(path, ROOT)
            own = target_of(rel)
            if own is None:
                errors.append(f"{rel}: in no target of docs/architecture.md")
                continue
            may = reach(own)
            for number, header in includes(path):
                theirs = target_of(header)
                if theirs is None or theirs == own or "all" in may or theirs in may:
                    continue
                if theirs.startswith("dem/") and "dem" in may:
                    continue
                errors.append(f"{rel}:{number}: includes {header}, of {theirs}; {own} depends on "
                              f"{', '.join(sorted(may)) or 'nothing'} (docs/architecture.md, \"Folders\")")

    for e in errors:
        print(e)
    print(f"checked the includes of dem/, upscale/, fem/ and coupling/ against {len(order)} dem/ folders and "
          f"{len(outside_table)} targets: {len(errors)} problems")
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())
