#!/usr/bin/env bash
# Times every input limit of `locbench --help` AT the limit (the goal: ≤ 10 s and ≤ 1 GB with the
# Release build of `make build`, -O1). Inputs are generated in a scratch folder (nothing from
# $LOCBENCH_DATA). Each line: the limit, the at-limit input, the exit code, wall and CPU seconds
# (CPU: what a loaded machine does not inflate) and the peak resident memory (/usr/bin/time -v). The
# hostile-input table keeps a row at and past each limit; the slowest at-limit shapes (spread-out
# histograms, MCL and grid Markov at their work limit) are timed only here, since the sanitizer test
# build runs them several times slower.
#
#   scripts/time_limits.sh [path/to/locbench]      (default build/dev/cli/locbench)
set -u
exe=$(realpath "${1:-build/dev/cli/locbench}")
src=$(cd "$(dirname "$0")/.." && pwd)
d=$(mktemp -d)
trap 'rm -rf "$d"' EXIT
cd "$d" || exit 1

timed() {  # name, then the command's arguments
  local name=$1
  shift
  /usr/bin/time -v -o time.txt "$exe" "$@" >out.txt 2>&1
  local rc=$?
  local s cpu kb
  s=$(awk -F': ' '/Elapsed \(wall clock\)/ {n = split($2, p, ":"); t = 0; for (i = 1; i <= n; ++i) t = t * 60 + p[i]; print t}' time.txt)
  cpu=$(awk -F': ' '/(User|System) time \(seconds\)/ {t += $2} END {print t}' time.txt)
  kb=$(awk -F': ' '/Maximum resident/ {print $2}' time.txt)
  printf '%-44s exit %d  %6.2f s wall  %6.2f s CPU  %5d MB\n' "$name" "$rc" "$s" "$cpu" $((kb / 1024))
}

# Histograms: 10,000 bins, 500 of them filled (spread out; contiguous with random counts).
python3 - <<'EOF'
import json, random
random.seed(1)
def write(name, counts):
    bins = len(counts)
    json.dump({"residual": "r", "unit": "deg", "edges": [i - bins // 2 for i in range(bins + 1)], "counts": counts},
              open(name, "w"))
c = [0] * 10000
for i in range(0, 10000, 20): c[i] = random.randint(1, 1000)
write("spread.json", c)
c = [0] * 10000
for i in range(4750, 5250): c[i] = random.randint(1, 900)
write("contiguous.json", c)
c = [0] * 10000
for i in range(4750, 5250): c[i] = 20000
write("count.json", c)  # 500 x 20,000 = 10^7 samples
EOF
timed "histogram 10,000 bins, 500 filled, spread" diagnose spread.json
timed "histogram 500 filled, contiguous, random" diagnose contiguous.json
timed "histogram total count 10^7" diagnose count.json

# Simulation: 10^4 s, 2·10^7 physics steps, 10^6 records of each sensor, 2·10^6 laser ranges.
cat >sim.json <<'EOF'
{"preset": "corridor", "motion": {"kind": "straight", "distance": 9999}, "drive": {"speed": 1.0, "pause": 0},
 "physics": {"step": 0.0005, "trajectory_rate": 100},
 "encoders": {"rate": 100}, "odometry": {"enabled": true, "rate": 100}, "compass": {"rate": 100},
 "truth": {"rate": 100}, "laser": {"enabled": true, "rate": 0.2, "beams": 999}}
EOF
timed "simulate at every sim limit at once" simulate sim.json -o sim.clf
rm -f sim.clf

# diagnose: 30,000 ENCODER records with TRUEPOS and COMPASS.
cat >d.json <<'EOF'
{"preset": "corridor", "motion": {"kind": "straight", "distance": 495}, "drive": {"speed": 1.0, "pause": 0},
 "encoders": {"rate": 60}, "compass": {"rate": 60}, "truth": {"rate": 60}}
EOF
"$exe" simulate d.json -o d.clf >/dev/null 2>&1
timed "diagnose $(grep -c '^ENCODER' d.clf) odometry records" diagnose d.clf

# Laser: 200 scans of 10,000 beams (2·10^6 ranges); agglomerative at 200 scans of 1,000 beams.
echo '{"preset": "corridor", "motion": {"kind": "straight", "distance": 1}, "laser": {"enabled": true, "beams": 10000}}' >l.json
"$exe" simulate l.json -o l.clf >/dev/null 2>&1
awk '/^FLASER/ {if (!scan) scan = $0; next} {print} END {n = split(scan, f, " "); for (k = 0; k < 200; ++k) {f[n] = f[n - 2] = 0.1 * k; line = f[1]; for (i = 2; i <= n; ++i) line = line " " f[i]; print line}}' l.clf >l200.clf
for m in eap split_and_merge rwht; do
  timed "match $m, 2*10^6 ranges" match --map "$src/examples/room_map.json" --log l200.clf --matcher "$m"
done
echo '{"preset": "corridor", "motion": {"kind": "straight", "distance": 10}, "laser": {"enabled": true, "beams": 1000}}' >a.json
"$exe" simulate a.json -o a.clf >/dev/null 2>&1
awk '/^FLASER/ && ++n > 200 {next} {print}' a.clf >a200.clf
timed "match agglomerative, 2*10^8 beams^2" match --map "$src/examples/room_map.json" --log a200.clf --matcher agglomerative

# localize: MCL at 2·10^8 = 10^6 particles x (20 beams + 80) x 2 updates without KLD; with a tiny
# kld_bin and 10^6 max_particles the set grows during the run, which stops (exit 2) at the limit;
# grid Markov at 8·10^8 = cells x (beams + 10) x updates.
awk '/^FLASER/ && ++n > 2 {next} {print}' a.clf >a2.clf
awk '/^FLASER/ && ++n > 9 {next} {print}' a.clf >a9.clf
echo '{"mcl": {"initial_particles": 1000000, "max_particles": 1000000, "kld": false, "update_min_distance": 0, "update_min_angle": 0}}' >mcl.json
timed "localize mcl, 10^6 particles, 2 updates" localize --method mcl --map "$src/examples/room_map.json" --log a2.clf --options mcl.json
echo '{"preset": "corridor", "motion": {"kind": "straight", "distance": 1}, "laser": {"enabled": true}}' >k.json
"$exe" simulate k.json --seed 3 -o k.clf >/dev/null 2>&1
echo '{"mcl": {"max_particles": 1000000, "kld_bin": [0.0001, 0.0001, 0.0001], "update_min_distance": 0, "update_min_angle": 0}}' >kld.json
timed "localize mcl, tiny kld_bin, stops at the limit" localize --method mcl --map "$src/examples/room_map.json" --log k.clf --options kld.json
echo '{"mcl": {"max_particles": 1000000, "field": {"beams": 1}, "kld_bin": [0.0001, 0.0001, 0.0001], "update_min_distance": 0, "update_min_angle": 0}}' >kld1.json
timed "localize mcl, tiny kld_bin, 1 beam, stops" localize --method mcl --map "$src/examples/room_map.json" --log k.clf --options kld1.json
echo '{"grid_markov": {"cell_size": 0.04, "update_min_distance": 0, "update_min_angle": 0}}' >grid.json
timed "localize grid_markov, near its work limit" localize --method grid_markov --map "$src/examples/room_map.json" --log a9.clf --options grid.json
echo '{"grid_markov": {"cell_size": 0.04, "field": {"beams": 1}, "update_min_distance": 0, "update_min_angle": 0}}' >grid1.json
awk '/^FLASER/ && ++n > 25 {next} {print}' a.clf >a25.clf
timed "localize grid_markov, 1 beam, 25 updates" localize --method grid_markov --map "$src/examples/room_map.json" --log a25.clf --options grid1.json
grep -o 'grid_markov: .*' out.txt | head -1  # the work, when refused

# Landmarks: noise/landmark_logs (every setting of its grid filters every observation) on a
# 100 s velocity (ODOM) log with a 10,000-landmark map and 10,000 observations.
echo '{"preset": "corridor", "motion": {"kind": "straight", "distance": 25}, "encoders": {"enabled": false}, "odometry": {"enabled": true, "rate": 10}}' >c25.json
"$exe" simulate c25.json -o c25.clf >/dev/null 2>&1
awk 'BEGIN{for (i = 1; i <= 10000; i++) printf "%d %.2f %.2f\n", i, (i % 100) * 0.3, int(i / 100) * 0.3}' >lm.txt
awk 'BEGIN{for (i = 0; i < 10000; i++) printf "%.6f %d 1.5 0.2\n", 0.5 + i * 9.5e-3, 1 + (i % 10000)}' >ob.txt
timed "noise/landmark_logs, 10^4 landmarks and obs" run noise/landmark_logs --log c25.clf --landmark-map lm.txt --landmark-observations ob.txt --out lm

# The likelihood field at 2.5·10^7 cells: 2.01 mm cells on the 8 m room (+ 1 m margins), 1 update.
echo '{"mcl": {"field": {"resolution": 0.00201}, "update_min_distance": 1e9}}' >field.json
timed "likelihood field, 2.5*10^7 cells" localize --method mcl --map "$src/examples/room_map.json" --log k.clf --options field.json

# run: 1,000 Monte-Carlo runs of the corridor.
timed "run odometry/sim_corridor --runs 1000" run odometry/sim_corridor --runs 1000 --out runs
