#!/usr/bin/python3
"""Result identity of two frictopt builds (a refactor must change no result).

Each folder holds, per case NAME, what `solve`, `check-gradient`, `optimize` and `certify`
wrote: solve-NAME/ (summary.json, NAME.vtu), grad-NAME.log, opt-NAME/ (final_design.json, the
VTU series, certificate.json) and opt-NAME.log, cert-NAME.log. Prints per case the largest
relative difference max|b − a| / max|a| of Θ and ξ (check-gradient), λ (contact pressure) and
u (displacement) of the solve's VTU, every number of summary.json, every array of every VTU,
the final design and the certificate, and whether the logs are equal once timings, column
widths and the output folder's name are ignored.
    /usr/bin/python3 bench/compare_runs.py BEFORE_DIR AFTER_DIR      (needs python3-vtk, numpy)
"""
import glob, json, math, os, re, sys
import vtk
from vtk.util.numpy_support import vtk_to_numpy
import numpy as np

a, b = sys.argv[1], sys.argv[2]   # a = before (reference), b = after

def read_vtu(path):
    r = vtk.vtkXMLUnstructuredGridReader(); r.SetFileName(path); r.Update()
    g = r.GetOutput(); pd = g.GetPointData(); out = {"points": vtk_to_numpy(g.GetPoints().GetData())}
    for i in range(pd.GetNumberOfArrays()):
        out[pd.GetArrayName(i)] = vtk_to_numpy(pd.GetArray(i))
    cd = g.GetCellData()
    for i in range(cd.GetNumberOfArrays()):
        out["cell:" + cd.GetArrayName(i)] = vtk_to_numpy(cd.GetArray(i))
    out["connectivity"] = vtk_to_numpy(g.GetCells().GetConnectivityArray())
    return out

def rel(x, y):
    x = np.nan_to_num(np.asarray(x, float)); y = np.nan_to_num(np.asarray(y, float))
    if x.shape != y.shape: return float("inf")
    s = np.max(np.abs(y)) if y.size else 0.0
    d = np.max(np.abs(x - y)) if y.size else 0.0
    return 0.0 if d == 0 else d / (s if s > 0 else 1.0)

def numbers(obj, prefix=""):
    if isinstance(obj, dict):
        for k, v in obj.items():
            if "seconds" in k or k in ("time", "wall_time"): continue
            yield from numbers(v, prefix + "." + k)
    elif isinstance(obj, list):
        for i, v in enumerate(obj): yield from numbers(v, f"{prefix}[{i}]")
    elif isinstance(obj, (int, float)) and not isinstance(obj, bool):
        yield prefix, float(obj)

NUM = re.compile(r"[-+]?\d+\.\d+(?:e[-+]?\d+)?|[-+]?\d+e[-+]?\d+")
def log_numbers(path):
    vals = []
    for line in open(path, errors="replace"):
        line = re.sub(r"\d+(\.\d+)? ?s\b|time\S*|seconds", "", line)  # timings are not results
        line = line.replace(os.path.dirname(path), "RUN")                # the output folder's name
        vals.append(" ".join(line.split()))                               # column widths follow timings
    return vals

rows = []
for sa in sorted(glob.glob(os.path.join(a, "solve-*"))):
    if not os.path.isdir(sa): continue
    case = os.path.basename(sa)[6:]; sb = os.path.join(b, os.path.basename(sa))
    row = {"case": case}
    ja = json.load(open(os.path.join(sa, "summary.json"))); jb = json.load(open(os.path.join(sb, "summary.json")))
    na, nb = dict(numbers(ja)), dict(numbers(jb))
    row["summary"] = max([rel(nb.get(k, math.inf), v) for k, v in na.items()] + [0.0])
    va = glob.glob(os.path.join(sa, "*.vtu")); 
    if va:
        A = read_vtu(va[0]); B = read_vtu(os.path.join(sb, os.path.basename(va[0])))
        row["u"] = rel(B["displacement"], A["displacement"])
        row["lambda"] = rel(B["contact_pressure"], A["contact_pressure"]) if "contact_pressure" in A else 0.0
        row["all_vtu"] = max(rel(B.get(k, []), v) for k, v in A.items())
    rows.append(row)
for ga in sorted(glob.glob(os.path.join(a, "grad-*.log"))):
    case = os.path.basename(ga)[5:-4]; gb = os.path.join(b, os.path.basename(ga))
    la, lb = log_numbers(ga), log_numbers(gb)
    theta = xi = 0.0; same_text = la == lb
    for x, y in zip(la, lb):
        nx, ny = [float(v) for v in NUM.findall(x)], [float(v) for v in NUM.findall(y)]
        if len(nx) != len(ny): xi = math.inf; continue
        r = rel(ny, nx)
        if "Θ" in x: theta = max(theta, r)
        elif re.match(r"^\d+\s", x): xi = max(xi, r)
    r = next((r for r in rows if r["case"] == case), None)
    if r is None: r = {"case": case}; rows.append(r)
    r.update({"theta": theta, "xi": xi, "grad_log_identical": same_text})
for oa in sorted(glob.glob(os.path.join(a, "opt-*"))):
    if not os.path.isdir(oa): continue
    case = os.path.basename(oa)[4:]; ob = os.path.join(b, os.path.basename(oa))
    fa, fb = os.path.join(oa, "final_design.json"), os.path.join(ob, "final_design.json")
    r = next((r for r in rows if r["case"] == case), None)
    if os.path.exists(fa) and os.path.exists(fb):
        na, nb = dict(numbers(json.load(open(fa)))), dict(numbers(json.load(open(fb))))
        r["final_design"] = max([rel(nb.get(k, math.inf), v) for k, v in na.items()] + [0.0])
    # every VTU of the run (the design series) and the certificate's numbers
    worst = 0.0
    for va in glob.glob(os.path.join(oa, "*.vtu")):
        vb = os.path.join(ob, os.path.basename(va))
        if not os.path.exists(vb): worst = math.inf; continue
        A, B = read_vtu(va), read_vtu(vb)
        worst = max([worst] + [rel(B.get(k, []), v) for k, v in A.items()])
    r["opt_vtu_series"] = worst
    ca, cb = os.path.join(oa, "certificate.json"), os.path.join(ob, "certificate.json")
    if os.path.exists(ca) and os.path.exists(cb):
        na, nb = dict(numbers(json.load(open(ca)))), dict(numbers(json.load(open(cb))))
        r["certificate"] = max([rel(nb.get(k, math.inf), v) for k, v in na.items()] + [0.0])
    for kind in ("opt", "cert"):
        la, lb = os.path.join(a, f"{kind}-{case}.log"), os.path.join(b, f"{kind}-{case}.log")
        if os.path.exists(la) and os.path.exists(lb):
            r[kind + "_log_identical"] = log_numbers(la) == log_numbers(lb)
keys = ["case", "theta", "lambda", "u", "xi", "summary", "all_vtu", "grad_log_identical", "final_design", "opt_vtu_series", "certificate", "opt_log_identical", "cert_log_identical"]
print("| " + " | ".join(keys) + " |"); print("|" + "---|" * len(keys))
for r in rows:
    print("| " + " | ".join((f"{r[k]:.2e}" if isinstance(r.get(k), float) else str(r.get(k, "-"))) for k in keys) + " |")
