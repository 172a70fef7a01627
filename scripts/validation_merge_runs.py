"""Replace the (case, resolution) runs of runs.json by the reruns in the given JSON files, in place."""
import json, sys
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
        runs[i] = new[key]; seen.add(key)
        print(f"{key}: dp {old['dp']:.6g} -> {new[key]['dp']:.6g}, particles {old['n_particles']} -> {new[key]['n_particles']}, "
              f"wall {old['wall_s']:.1f} -> {new[key]['wall_s']:.1f}, cpu {old['cpu_s']:.1f} -> {new[key]['cpu_s']:.1f}, "
              f"status {new[key]['status']}, errors {old['errors']} -> {new[key]['errors']}")
missing = set(new) - seen
assert not missing, missing
with open(path, "w") as fh:
    json.dump(runs, fh, indent=1)
    fh.write("\n")
