#!/usr/bin/env bash
# SPDX-License-Identifier: MIT
# The Hertz block (bench/contact/hertz_bench.cpp) at several accuracy levels — uniform, graded
# in-plane with the power-law vertical grading, and graded in-plane with the vertical grading
# "contact" — frictionless and with friction (normal load without friction, then the tangential
# shift: a two-step loading program), for this build and optionally a previous frictopt's
# hertz_bench, run alternately configuration by configuration (so both see the same machine
# load), REPEATS times each. Prints one markdown table with the medians and the ratios
# new / previous (docs/contact.md §7).
#
#   bench/contact/run_hertz.sh [SET] [REPEATS] [PREVIOUS_BENCH]
#     SET = accuracy (default: uniform 24/32/40 cells with layers = cells/3; graded 32 cells with
#           16/22 power-law layers; graded 28 × 16, 30 × 18 and 32 × 18 with "contact" layers:
#           docs/contact-validation.md §1b, §1c), large (80 × 80 × 11 uniform: 19,683 contact
#           unknowns), or a quoted list of hertz_bench argument lists separated by commas.
#     PREVIOUS_BENCH: e.g. /tmp/frictopt-966f3ca/build/bench/contact/hertz_bench (966f3ca with
#           this file's hertz_bench.cpp added; it uses only the API that version already had).
#           Configurations with key=value options (fine_depth, program) need API the previous
#           version lacks and run with the new build only.
# OPENBLAS_NUM_THREADS is passed through (unset: OpenBLAS's default).
set -euo pipefail
here=$(cd "$(dirname "$0")/../.." && pwd)
new="${HERTZ_BENCH:-$here/build/bench/contact/hertz_bench}"
set_name="${1:-accuracy}"
repeats="${2:-1}"
previous="${3:-}"
case "$set_name" in
  accuracy)
    configs=""
    for mu in "0 0" "0.3 0.002"; do
      program=""
      [[ $mu == "0 0" ]] || program="program=1"
      for grid in "24 8 1" "32 11 1" "40 13 1" "32 16 1.2" "32 22 1.2"; do configs+="$grid $mu $program,"; done
      # In-plane grading toward [0.34, 0.66]² and contact layers down to 0.16 m (§1c):
      # "CELLS LAYERS GROWTH | VERTICAL_GROWTH".
      for grid in "28 16 1.5|1.5" "30 18 1.4|1.4" "32 18 1.3|1.4"; do
        configs+="${grid%|*} $mu 12000 1 1 0.34 0.66 fine_depth=0.16 vertical_growth=${grid#*|} $program,"
      done
    done
    configs=${configs%,} ;;
  large) configs="80 11 1 0 0,80 11 1 0.3 0.002" ;;
  *) configs="$set_name" ;;
esac
out=$(mktemp)
IFS=',' read -ra list <<< "$configs"
for config in "${list[@]}"; do
  for ((r = 0; r < repeats; ++r)); do
    for which in previous new; do
      bin=$new
      if [[ $which == previous ]]; then [[ -n $previous && $config != *=* ]] || continue; bin=$previous; fi
      # shellcheck disable=SC2086
      line=$("$bin" $config 2>/dev/null || true)
      echo "which=$which $line" >> "$out"
      echo "$which $config: $line" >&2
    done
  done
done
python3 - "$out" <<'PY'
import statistics, sys
rows = [dict(kv.split("=", 1) for kv in line.split()) for line in open(sys.argv[1]) if "unknowns=" in line]
# The previous version prints neither fine_depth nor program: power-law grid, one step.
def key(r): return (r["cells"], r["layers"], r["growth"], r.get("fine_depth", "0"), r.get("vertical_growth", "1.2"), r["mu"], r.get("program", "0"))
def grid_name(k):
    name = "uniform" if float(k[2]) == 1 else "graded " + k[2]
    return name + (f", contact layers to {k[3]} m (×{k[4]})" if float(k[3]) > 0 else "")
keys = []
for r in rows:
    k = key(r)
    if k not in keys: keys.append(k)
def med(rs, f): return statistics.median(float(r[f]) for r in rs)
# CPU seconds (the previous version does not print them): with the assembly, see hertz_bench.cpp.
def cpu(rs, f): return f"{med(rs, f):.2f}" if f in rs[0] else "–"
def cpu_ratio(rs): return f"{statistics.median(float(r['state_cpu_s']) / float(r['floor_cpu_s']) for r in rs):.2f}" if "state_cpu_s" in rs[0] else "–"
print("| grid | cells | mu | unknowns | contact unknowns | loaded nodes | version | floor [s] | factorization [s] | state [s] | state / floor | state / factorization | floor CPU [s] | state CPU [s] | state CPU / floor CPU | subgradient [s] | subgradient / state | QP its | peak RSS [MB] | a fit err | a moment err | p apex err | p fit err | KKT |")
print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
for k in keys:
    for which in ("previous", "new"):
        rs = [r for r in rows if key(r) == k and r["which"] == which]
        if not rs: continue
        r0 = rs[0]
        print(f"| {grid_name(k)} | {k[0]}×{k[0]}×{k[1]} | {k[5]}{' (2 steps)' if k[6] == '1' else ''} | {r0['unknowns']} | {r0['contact_unknowns']} | {r0['loaded_nodes']} | {which} | "
              f"{med(rs,'floor_s'):.2f} | {med(rs,'factorization_s'):.2f} | {med(rs,'state_s'):.2f} | {med(rs,'state_over_floor'):.2f} | {med(rs,'state_over_factorization'):.2f} | "
              f"{cpu(rs,'floor_cpu_s')} | {cpu(rs,'state_cpu_s')} | {cpu_ratio(rs)} | "
              f"{med(rs,'subgradient_s'):.2f} | {med(rs,'subgradient_over_state'):.3f} | {int(med(rs,'qp_its'))} | {med(rs,'peak_rss_MB'):.0f} | "
              f"{r0['a_fit_err']} | {r0['a_moment_err']} | {r0['p_apex_err']} | {r0['p_fit_err']} | {r0['kkt']} |")
    new = [r for r in rows if key(r) == k and r["which"] == "new"]
    old = [r for r in rows if key(r) == k and r["which"] == "previous"]
    if new and old:
        print(f"| | | | | | | new / previous | | | {med(new,'state_s')/med(old,'state_s'):.2f} | | | | | | {med(new,'subgradient_s')/med(old,'subgradient_s'):.2f} | | | {med(new,'peak_rss_MB')/med(old,'peak_rss_MB'):.2f} | | | | | |")
print(f"\n({len(rows)} runs; medians over the repeats of each configuration)")
PY
rm -f "$out"
