"""The quick stress matrix's dam-break and tank runs (``watersim.stress.quick_matrix``) with
modified-DBC walls (``boundary = "mdbc"``), two at a time; writes the records to the JSON file
given and prints each run's status, largest density error and energy drift.

    RAYON_NUM_THREADS=1 python3 scripts/stress_mdbc.py stress_mdbc.json
"""
import dataclasses
import json
import sys

from watersim import stress

if __name__ == "__main__":
    specs = [dataclasses.replace(s, params={**s.params, "boundary": "mdbc"})
             for s in stress.quick_matrix() if s.case in ("dambreak", "tank")]
    records = stress.run_matrix(specs, jobs=2, progress=False)
    with open(sys.argv[1], "w", encoding="utf-8") as f:
        json.dump(records, f, indent=1)
    for r in records:
        print(r["name"], r["status"], r.get("kind"), r.get("max_density_error"),
              r.get("energy_drift"))
