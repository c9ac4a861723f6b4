"""The "Strain" section of report.md and its plots (docs/strain.md, coupling/studies/continuum/strain_report.cc),
shared by check_output.py and check_study.py. Sane means: the section is there and names the
reference time, the number of outputs that are in grid_strain/ and each definition's valid
cells as the last file has them; the three plots are PNG images of a reasonable size that
the section links; the medians it prints lie in the range of the last file's valid cells;
the mesh output strain_mesh/strain.pvd holds every output at its time, each naming the
strain fields."""
import os
import re
import xml.etree.ElementTree as ET

import h5py
import numpy as np

PLOTS = ("strain_ln_J.png", "strain_shear.png", "strain_final_map.png")


def check_strain_report(folder="."):
    report = open(os.path.join(folder, "report.md")).read()
    assert "\n## Strain\n" in report, "report.md has no Strain section"
    section = report.split("\n## Strain\n", 1)[1].split("\n## ", 1)[0]
    files = sorted(f for f in os.listdir(os.path.join(folder, "grid_strain")) if f.endswith(".h5"))
    assert f"{len(files)} outputs in `grid_strain/`" in section, section
    for p in PLOTS:
        path = os.path.join(folder, p)
        assert os.path.exists(path), p
        with open(path, "rb") as f:
            assert f.read(8) == b"\x89PNG\r\n\x1a\n", p
        assert os.path.getsize(path) > 10000, (p, os.path.getsize(path))
        assert f"![{p}]({p})" in section, p
    with h5py.File(os.path.join(folder, "grid_strain", files[-1]), "r") as h:
        assert f"t0 = {h.attrs['reference_time']:.4g} s" in section, section
        cells = int(np.prod(h["/grid/n"][:]))
        for d, label in (("best_fit", "best fit"), ("tessellation", "tessellation")):
            if d not in h:
                continue
            valid = h[d]["F_valid"][:].reshape(-1) == 1
            row = [line for line in section.splitlines() if line.startswith(f"| {label} |")]
            assert len(row) == 1, (label, section)
            assert f"| {int(valid.sum())} of {cells} |" in row[0], (row[0], int(valid.sum()))
            if valid.any():
                ln_j = h[d]["ln_J"][:].reshape(-1)[valid]
                median = float(re.search(r"\| ([-0-9.e+]+) \[", row[0]).group(1))
                assert ln_j.min() - 1e-3 * max(1.0, abs(ln_j).max()) <= median <= ln_j.max() + 1e-3 * max(
                    1.0, abs(ln_j).max()), (row[0], ln_j.min(), ln_j.max())
        definitions = [d for d in ("best_fit", "tessellation") if d in h]
    # Every output on the deal.II mesh: strain.pvd lists one record per file at its time, and
    # ParaView finds ln J and the equivalent shear strain of each definition as cell data.
    pvd = ET.parse(os.path.join(folder, "strain_mesh", "strain.pvd")).getroot()
    sets = list(pvd.iter("DataSet"))
    assert len(sets) == len(files), (len(sets), len(files))
    for ds, f in zip(sets, files):
        with h5py.File(os.path.join(folder, "grid_strain", f), "r") as h:
            assert float(ds.get("timestep")) == float(h.attrs["time"]), (ds.get("timestep"), f)
        pvtu = open(os.path.join(folder, "strain_mesh", ds.get("file"))).read()
        for d in definitions:
            for field in ("ln_J", "equivalent_shear_strain", "F_valid"):
                assert f'Name="{d}_{field}"' in pvtu, (ds.get("file"), d, field)
    assert "strain_mesh/strain.pvd" in section
    return len(files)
