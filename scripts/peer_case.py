#!/usr/bin/env python3
"""Write a DualSPHysics 5.x case (NAME.xml + NAME.bi4) holding exactly the particles of a vrsph run.

    scripts/peer_case.py RUN_DIR OUT_PREFIX [--snapshot N]

RUN_DIR is a vrsph output folder with its case.toml, summary.json and a CSV snapshot
(particles_NNNN.csv, the first by default), for example from

    vrsph run CASE.toml --out RUN_DIR --set case.end_time=1e-9 --set 'output.formats=["csv"]'

OUT_PREFIX.xml and OUT_PREFIX.bi4 are what GenCase would write: DualSPHysics runs them with
`DualSPHysics -cpu OUT_PREFIX OUTDIR ...`. The peer then starts from vrsph's own particles
(positions, velocities and densities, the hydrostatic start included), so a side-by-side speed
comparison needs no GenCase and holds the same particles in both codes at any size. The walls
become one block of fixed boundary particles (dynamic boundary conditions, as vrsph's walls),
the fluid one fluid block. Taken from case.toml: dimension, dp, h, rho0, gamma, gravity, CFL,
the artificial viscosity and the Fourtakas density diffusion delta; from summary.json the sound
speed c0 the run used (B = c0^2 rho0 / gamma). Only single-level runs (no refinement) with the
artificial viscosity map onto a peer case.

The .bi4 file is DualSPHysics' JBinaryData layout, little-endian: a 64-byte text header, then
items. An item is an int32 header size (not counting itself), the marker "\\nITEM\\n", its name,
two int32 flags, the float and double print formats, the counts of its arrays and sub-items and
the byte size of its value block; the value block is "\\nVALUES", an int32 count and (name, type
code, payload) triples; an array is an int32 header size, "\\nARRAY", its name, a hidden flag,
type code, element count and byte size, then the raw data. Every string is an int32 length and
its bytes. Only the Python standard library is used.
"""
import argparse
import csv
import json
import math
import os
import struct
import sys
import tomllib
from array import array

# JBinaryData type codes
TEXT, BOOL, INT, UINT, ULLONG, FLOAT, DOUBLE, FLOAT3, DOUBLE3 = 1, 2, 7, 8, 10, 11, 12, 22, 23


def fail(msg):
    sys.exit(f"peer_case.py: {msg}")


def s(text):
    raw = text.encode()
    return struct.pack("<i", len(raw)) + raw


def value(name, code, payload):
    if code == TEXT:
        body = s(payload)
    elif code in (BOOL, INT):
        body = struct.pack("<i", int(payload))
    elif code == UINT:
        body = struct.pack("<I", payload)
    elif code == ULLONG:
        body = struct.pack("<Q", payload)
    elif code == DOUBLE:
        body = struct.pack("<d", payload)
    elif code == DOUBLE3:
        body = struct.pack("<3d", *payload)
    else:
        raise ValueError(code)
    return s(name) + struct.pack("<i", code) + body


def item(name, values, arrays, n_items):
    block = s("\nVALUES") + struct.pack("<i", len(values)) + b"".join(values)
    head = (s("\nITEM\n") + s(name) + struct.pack("<ii", 0, 0) + s("%.7E") + s("%.15E") +
            struct.pack("<iii", len(arrays), n_items, len(block)))
    return struct.pack("<i", len(head)) + head + block + b"".join(arrays)


def array_block(name, code, count, data):
    raw = data.tobytes()
    head = s("\nARRAY") + s(name) + struct.pack("<iiII", 0, code, count, len(raw))
    return struct.pack("<i", len(head)) + head + raw


def read_particles(path, dim):
    """Walls first, then fluid; positions as 3D with DualSPHysics' axes (2D: x, z)."""
    walls, fluid = [], []
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            if row["level"] != "0" or row["kind"] == "buffer":
                fail(f"{path}: particle {row['id']} is of level {row['level']}, kind "
                     f"{row['kind']}: only single-level runs can be written as a peer case")
            if dim == 3:
                pos = (float(row["x"]), float(row["y"]), float(row["z"]))
                vel = (float(row["vx"]), float(row["vy"]), float(row["vz"]))
            else:
                pos = (float(row["x"]), 0.0, float(row["y"]))
                vel = (float(row["vx"]), 0.0, float(row["vy"]))
            (fluid if row["kind"] == "fluid" else walls).append((pos, vel, float(row["rho"])))
    return walls, fluid


def params(case, summary):
    try:
        dim = case["case"]["dimension"]
        dp = case["resolution"]["dp"]
        p = {
            "name": case["case"]["name"], "dim": dim, "dp": dp,
            "h": case["resolution"]["h_over_dp"] * dp, "rho0": case["fluid"]["density"],
            "gamma": case["eos"]["gamma"], "c0": summary["c0"],
            "gravity": case["fluid"]["gravity"], "cfl": case["numerics"]["cfl"],
        }
        visc = case["numerics"]["viscosity"]
        ddt = case["numerics"]["density_diffusion"]
    except KeyError as e:
        fail(f"case.toml or summary.json lacks {e}: write them with vrsph run (the run "
             "folder's copies are complete)")
    if case.get("refinement"):
        fail("case.toml has [[refinement]] levels: only single-level runs map onto one peer case")
    if visc.get("model") != "artificial":
        fail(f"numerics.viscosity.model = {visc.get('model')!r}: only 'artificial' is mapped")
    p["alpha"] = visc.get("alpha", 0.0)
    p["ddt"] = ddt.get("delta", 0.0) if ddt.get("model") == "fourtakas" else None
    if ddt.get("model") not in ("fourtakas", "none"):
        fail(f"numerics.density_diffusion.model = {ddt.get('model')!r}: only 'fourtakas' "
             "(DualSPHysics DensityDT 3) or 'none' are mapped")
    g = p["gravity"]
    p["g3"] = (g[0], g[1], g[2]) if dim == 3 else (g[0], 0.0, g[1])
    p["b"] = p["c0"] ** 2 * p["rho0"] / p["gamma"]  # Tait's B
    p["mass"] = p["rho0"] * dp ** dim  # of every particle, walls included
    return p


def bounds(parts):
    lo = [min(q[0][k] for q in parts) for k in range(3)]
    hi = [max(q[0][k] for q in parts) for k in range(3)]
    return lo, hi


def write_bi4(path, p, walls, fluid, lo, hi):
    parts = walls + fluid
    n, b, mass = len(parts), p["b"], p["mass"]
    head = [value("Piece", UINT, 0), value("Npiece", UINT, 1), value("RunCode", TEXT, ""),
            value("Date", TEXT, ""), value("AppName", TEXT, "vrsph scripts/peer_case.py"),
            value("CaseName", TEXT, p["name"]), value("Data2d", BOOL, p["dim"] == 2),
            value("Data2dPosY", DOUBLE, 0.0), value("MapPosMin", DOUBLE3, (0, 0, 0)),
            value("MapPosMax", DOUBLE3, (0, 0, 0)), value("PeriMode", INT, 0x60),
            value("PeriXinc", DOUBLE3, (0, 0, 0)), value("PeriYinc", DOUBLE3, (0, 0, 0)),
            value("PeriZinc", DOUBLE3, (0, 0, 0)), value("AxisDiv", INT, 99),
            value("CaseNp", ULLONG, n), value("CaseNfixed", ULLONG, len(walls)),
            value("CaseNmoving", ULLONG, 0), value("CaseNfloat", ULLONG, 0),
            value("CaseNfluid", ULLONG, len(fluid)), value("CasePosMin", DOUBLE3, lo),
            value("CasePosMax", DOUBLE3, hi), value("NpDynamic", BOOL, 0),
            value("ReuseIds", BOOL, 0), value("Dp", DOUBLE, p["dp"]), value("H", DOUBLE, p["h"]),
            value("B", DOUBLE, b), value("Rhop0", DOUBLE, p["rho0"]),
            value("Gamma", DOUBLE, p["gamma"]), value("MassBound", DOUBLE, mass),
            value("MassFluid", DOUBLE, mass)]
    part = [value("Cpart", UINT, 0), value("TimeStep", DOUBLE, 0.0), value("Npok", UINT, n),
            value("Nout", UINT, 0), value("Step", UINT, 0), value("RunTime", DOUBLE, 0.0),
            value("DomainMin", DOUBLE3, (0, 0, 0)), value("DomainMax", DOUBLE3, (0, 0, 0))]
    arrays = [array_block("Idp", UINT, n, array("I", range(n))),
              array_block("Posd", DOUBLE3, n, array("d", (c for q in parts for c in q[0]))),
              array_block("Vel", FLOAT3, n, array("f", (c for q in parts for c in q[1]))),
              array_block("Rhop", FLOAT, n, array("f", (q[2] for q in parts)))]
    if sys.byteorder != "little":
        for a in arrays:
            a.byteswap()
    text = b"#FileJBD JPartDataBi4".ljust(58) + b"\n"
    blob = (text.ljust(64, b"\0") + item("JPartDataBi4", head, [], 1) +
            item("PART_0000", part, arrays, 0))
    write_atomic(path, blob)


def write_xml(path, p, nb, nf):
    dim, dp, h = p["dim"], p["dp"], p["h"]
    coefh = h / (dp * math.sqrt(dim))
    b, mass = p["b"], p["mass"]
    g = p["g3"]
    ddt = (f'<parameter key="DensityDT" value="3" />\n'
           f'            <parameter key="DensityDTvalue" value="{p["ddt"]!r}" />'
           if p["ddt"] is not None else '<parameter key="DensityDT" value="0" />')
    d2 = ('<data2d value="true" />\n            <data2dposy value="0" />' if dim == 2
          else '<data2d value="false" />')
    xml = f"""<?xml version="1.0" encoding="UTF-8" ?>
<!-- Written by vrsph's scripts/peer_case.py from the run of case "{p["name"]}": the particles of
     that run's first snapshot, {nb} fixed boundary (mk 10) and {nf} fluid (mk 1). -->
<case>
    <casedef>
        <constantsdef>
            <hdp value="{h / dp!r}" />
        </constantsdef>
        <mkconfig boundcount="241" fluidcount="9" />
    </casedef>
    <execution>
        <parameters>
            <parameter key="SavePosDouble" value="0" />
            <parameter key="Boundary" value="1" />
            <parameter key="StepAlgorithm" value="2" />
            <parameter key="Kernel" value="2" />
            <parameter key="ViscoTreatment" value="1" />
            <parameter key="Visco" value="{p["alpha"]!r}" />
            <parameter key="ViscoBoundFactor" value="1" />
            {ddt}
            <parameter key="CoefDtMin" value="0.05" />
            <parameter key="DtAllParticles" value="0" />
            <parameter key="TimeMax" value="1" />
            <parameter key="TimeOut" value="1" />
            <parameter key="RhopOutMin" value="700" />
            <parameter key="RhopOutMax" value="1300" />
        </parameters>
        <particles np="{nb + nf}" nb="{nb}" nbf="{nb}" mkboundfirst="10" mkfluidfirst="1">
            <fixed mkbound="0" mk="10" begin="0" count="{nb}" />
            <fluid mkfluid="0" mk="1" begin="{nb}" count="{nf}" />
        </particles>
        <constants>
            {d2}
            <gravity x="{g[0]!r}" y="{g[1]!r}" z="{g[2]!r}" />
            <cflnumber value="{p["cfl"]!r}" />
            <gamma value="{p["gamma"]!r}" />
            <rhop0 value="{p["rho0"]!r}" />
            <dp value="{dp!r}" />
            <coefh value="{coefh!r}" />
            <h value="{h!r}" />
            <b value="{b!r}" />
            <massbound value="{mass!r}" />
            <massfluid value="{mass!r}" />
        </constants>
        <motion />
    </execution>
</case>
"""
    write_atomic(path, xml.encode())


def write_atomic(path, data):
    tmp = path + ".tmp"
    with open(tmp, "wb") as f:
        f.write(data)
    os.replace(tmp, path)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("run_dir")
    ap.add_argument("out_prefix")
    ap.add_argument("--snapshot", type=int, default=0)
    a = ap.parse_args()
    toml = os.path.join(a.run_dir, "case.toml")
    summary = os.path.join(a.run_dir, "summary.json")
    snap = os.path.join(a.run_dir, f"particles_{a.snapshot:04d}.csv")
    for f in (toml, summary, snap):
        if not os.path.isfile(f):
            fail(f"{f}: no such file (run vrsph with output.formats = [\"csv\"] first)")
    with open(toml, "rb") as f, open(summary) as g:
        p = params(tomllib.load(f), json.load(g))
    walls, fluid = read_particles(snap, p["dim"])
    if not fluid:
        fail(f"{snap}: no fluid particle")
    lo, hi = bounds(walls + fluid)
    write_bi4(a.out_prefix + ".bi4", p, walls, fluid, lo, hi)
    write_xml(a.out_prefix + ".xml", p, len(walls), len(fluid))
    print(f"peer_case.py: wrote {a.out_prefix}.xml/.bi4: {len(walls)} fixed boundary + "
          f"{len(fluid)} fluid particles, dp {p['dp']}, h {p['h']}")


if __name__ == "__main__":
    main()
