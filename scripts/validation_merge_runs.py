"""Replace the (case, resolution) runs of runs.json by the reruns in the given JSON files, in
place."""
import json
import sys

path = sys.argv[1]
runs = json.load(open(path))
new = {}
for f in sys.argv[2:]:
    for r in json.load(open(f)):
        new[(r["case"], float(r["resolution"]))] = r
seen = set()
for i, r in enumerate(runs):
    key = (r["case"], float(r["resolution"]))
    if key in new:
        old = r
        rerun = new[key]
        runs[i] = rerun
        seen.add(key)
        print(f"{key}: dp {old['dp']:.6g} -> {rerun['dp']:.6g}, "
              f"particles {old['n_particles']} -> {rerun['n_particles']}, "
              f"wall {old['wall_s']:.1f} -> {rerun['wall_s']:.1f}, "
              f"cpu {old['cpu_s']:.1f} -> {rerun['cpu_s']:.1f}, "
              f"status {rerun['status']}, errors {old['errors']} -> {rerun['errors']}")
missing = set(new) - seen
assert not missing, missing
with open(path, "w") as fh:
    json.dump(runs, fh, indent=1)
    fh.write("\n")
