"""Replace the (case, resolution, settings) runs of runs.json by the reruns in the given JSON
files, in place; a run runs.json does not hold yet goes after its case's last run at a lower
resolution, and the runs of a case runs.json does not hold yet go at its end. The settings are
a run's numerical --set items (details.settings; none for the default numerics)."""
import json
import sys


def key_of(r):
    settings = (r.get("details") or {}).get("settings") or {}
    return (r["case"], float(r["resolution"]), json.dumps(settings, sort_keys=True))


path = sys.argv[1]
runs = json.load(open(path))
new = {}
for f in sys.argv[2:]:
    for r in json.load(open(f)):
        new[key_of(r)] = r
seen = set()
for i, r in enumerate(runs):
    key = key_of(r)
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
for key in sorted(set(new) - seen, key=lambda k: k[1]):
    same_case = [i for i, r in enumerate(runs) if r["case"] == key[0]]
    if same_case:
        at = max((i for i in same_case if float(runs[i]["resolution"]) < key[1]),
                 default=same_case[0] - 1)
        runs.insert(at + 1, new[key])
    else:
        runs.append(new[key])
    print(f"{key}: added, dp {new[key]['dp']:.6g}, particles {new[key]['n_particles']}, "
          f"cpu {new[key]['cpu_s']:.1f}, status {new[key]['status']}, errors {new[key]['errors']}")
with open(path, "w") as fh:
    json.dump(runs, fh, indent=1)
    fh.write("\n")
