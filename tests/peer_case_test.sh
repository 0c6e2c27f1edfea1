#!/usr/bin/env bash
# scripts/peer_case.py on a small 2D tank: the .bi4 it writes is read back here with a reader of
# its own (the JBinaryData layout described in the script) and must hold every particle of the
# snapshot, walls first, positions (x, 0, y), velocities and densities as in the CSV, ids 0..n-1,
# self-consistent section sizes; the .xml must give the same counts, dp, h and B = c0^2 rho0 /
# gamma. A two-level run is refused with a message naming the level.
#   tests/peer_case_test.sh VRSPH_BINARY REPO_ROOT
set -euo pipefail
[ $# -eq 2 ] || { echo "usage: peer_case_test.sh VRSPH_BINARY REPO_ROOT" >&2; exit 2; }
vrsph=$1; root=${2%/}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

"$vrsph" run "$root/cases/hydrostatic_2d.toml" --out "$tmp/run" --quiet --threads 1 \
  --set resolution.dp=0.02 --set 'fluid_block.0.min=[0.02,0.02]' \
  --set 'fluid_block.0.max=[0.98,0.5]' --set case.end_time=1e-9 --set output.interval=1 \
  --set 'output.formats=["csv"]' || fail "vrsph run exited $?"
python3 "$root/scripts/peer_case.py" "$tmp/run" "$tmp/Tank" > "$tmp/pc.log" ||
  fail "peer_case.py exited $?: $(cat "$tmp/pc.log")"

python3 - "$tmp/run/particles_0000.csv" "$tmp/Tank.bi4" "$tmp/Tank.xml" "$tmp/run/case.toml" <<'PY'
import csv, json, struct, sys, tomllib
import xml.etree.ElementTree as ET
snap, bi4, xmlf, toml = sys.argv[1:]
rows = list(csv.DictReader(open(snap)))
walls = [r for r in rows if r["kind"] == "wall"]
fluid = [r for r in rows if r["kind"] == "fluid"]
order = walls + fluid
d = open(bi4, "rb").read()
assert d.startswith(b"#FileJBD JPartDataBi4"), "header"
def text(p):
    n = struct.unpack_from("<i", d, p)[0]
    return d[p + 4:p + 4 + n], p + 4 + n
pos, items, arrays = 64, [], {}
while pos < len(d):
    size = struct.unpack_from("<i", d, pos)[0]
    tag, p = text(pos + 4)
    if tag == b"\nITEM\n":
        name, p = text(p); p += 8; _, p = text(p); _, p = text(p)
        na, ni, vsize = struct.unpack_from("<iii", d, p); p += 12
        assert p - pos - 4 == size, f"item header size {size} against {p - pos - 4}"
        tag, q = text(p)
        assert tag == b"\nVALUES", tag
        items.append((name.decode(), na, ni))
        pos = p + vsize
    else:
        assert tag == b"\nARRAY", tag
        name, p = text(p)
        _, code, count, nbytes = struct.unpack_from("<iiII", d, p); p += 16
        assert p - pos - 4 == size, f"array header size {size} against {p - pos - 4}"
        arrays[name.decode()] = (code, count, d[p:p + nbytes])
        pos = p + nbytes
assert pos == len(d), "trailing bytes"
assert items == [("JPartDataBi4", 0, 1), ("PART_0000", 4, 0)], items
n = len(order)
for name, code, width in (("Idp", 8, 4), ("Posd", 23, 24), ("Vel", 22, 12), ("Rhop", 11, 4)):
    c, count, raw = arrays[name]
    assert (c, count, len(raw)) == (code, n, n * width), (name, c, count, len(raw))
ids = struct.unpack(f"<{n}I", arrays["Idp"][2])
posd = struct.unpack(f"<{3 * n}d", arrays["Posd"][2])
rho = struct.unpack(f"<{n}f", arrays["Rhop"][2])
assert list(ids) == list(range(n)), "ids"
for k, r in enumerate(order):
    assert posd[3 * k:3 * k + 3] == (float(r["x"]), 0.0, float(r["y"])), (k, r)
    assert abs(rho[k] - float(r["rho"])) <= 1e-4 * float(r["rho"]), (k, rho[k], r["rho"])
case = tomllib.load(open(toml, "rb"))
root = ET.parse(xmlf).getroot()
parts = root.find("execution/particles")
assert (int(parts.get("np")), int(parts.get("nb"))) == (n, len(walls)), parts.attrib
assert int(parts.find("fluid").get("count")) == len(fluid)
const = root.find("execution/constants")
dp = case["resolution"]["dp"]
b = json.load(open(toml.replace("case.toml", "summary.json")))["c0"] ** 2 * case["fluid"]["density"] / case["eos"]["gamma"]
assert float(const.find("dp").get("value")) == dp
assert float(const.find("h").get("value")) == case["resolution"]["h_over_dp"] * dp
assert abs(float(const.find("b").get("value")) - b) <= 1e-12 * b
assert const.find("data2d").get("value") == "true"
print(f"peer_case_test: {len(walls)} walls + {len(fluid)} fluid read back")
PY

"$vrsph" run "$root/cases/droplet_vr_2d.toml" --out "$tmp/vr" --quiet --threads 1 \
  --set resolution.dp=2e-4 --set case.end_time=1e-9 --set output.interval=1 \
  --set 'output.formats=["csv"]' || fail "vrsph run (two levels) exited $?"
if python3 "$root/scripts/peer_case.py" "$tmp/vr" "$tmp/Vr" > "$tmp/vr.log" 2>&1; then
  fail "a two-level run was accepted"
fi
grep -q "refinement\|of level 1" "$tmp/vr.log" || fail "bad message: $(cat "$tmp/vr.log")"
echo "peer_case_test: ok"
