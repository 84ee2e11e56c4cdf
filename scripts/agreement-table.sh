#!/usr/bin/env bash
# The README table "Agreement with the reference" from the agreement tests' own output:
#   (cd build && ctest -L agreement -V > /tmp/agreement.log); scripts/agreement-table.sh /tmp/agreement.log
# One Markdown row per engine x case x law: tolerances against the chain and the beam reference, then
# the measured errors (impacts per cycle as a difference, the others in %).
set -euo pipefail
# the engines in their registration order (adapters/CMakeLists.txt, the one line that names them)
engines=$(sed -n 's/^set(impactbench_all_engines \(.*\))$/\1/p' "$(dirname "$0")/../adapters/CMakeLists.txt")
[[ -n $engines ]] || { echo "agreement-table.sh: no engine list in adapters/CMakeLists.txt (set(impactbench_all_engines ...))" >&2; exit 2; }
grep -o 'agreement: engine=.*' "$1" | sort -u | awk -v engines="$engines" '
function pct(x) { return sprintf("%+.1f", 100 * x) }
function tp(x) { return sprintf("%g", 100 * x) }
{ for (i = 2; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] }
  k = v["engine"] "|" v["case"] "|" v["law"]; if (!(k in step)) { order[++n] = k }
  step[k] = v["step_s"]; m = v["metric"]
  if (m == "impacts_per_cycle") cell = sprintf("%g / %g | %+.4f / %+.4f", v["chain_tolerance"], v["beam_tolerance"], v["chain_error"], v["beam_error"])
  else cell = sprintf("%s / %s | %s / %s", tp(v["chain_tolerance"]), tp(v["beam_tolerance"]), pct(v["chain_error"]), pct(v["beam_error"]))
  c[k, m] = cell }
END {
  ne = split(engines, en, " "); for (i = 1; i <= ne; ++i) eo[en[i]] = i; co["resonance"] = 1; co["pre_resonance"] = 2; co["post_resonance"] = 3; co["free_vibration"] = 4
  lo["hertz"] = 1; lo["viscoelastic"] = 2; lo["newton"] = 3
  for (i = 1; i <= n; ++i) { split(order[i], p, "|"); key[i] = eo[p[1]] * 100 + co[p[2]] * 10 + lo[p[3]] }
  for (i = 1; i <= n; ++i) for (j = i + 1; j <= n; ++j) if (key[j] < key[i]) { t = key[i]; key[i] = key[j]; key[j] = t; t = order[i]; order[i] = order[j]; order[j] = t }
  for (i = 1; i <= n; ++i) { k = order[i]; split(k, p, "|")
    a = ((k, "impacts_per_cycle") in c) ? c[k, "impacts_per_cycle"] : "skipped | -"
    b = c[k, "frame1_sensor_peak"]
    d = ((k, "contact_duration_mean") in c) ? c[k, "contact_duration_mean"] : "skipped | -"
    printf("| %s | %s | %s | %s | %s | %s | %s |\n", p[1], p[2], p[3], step[k], a, b, d) } }'
