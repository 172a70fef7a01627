"""The cnoidal and stream-function laws in the coarse cnoidal-range flume of
tests/test_wave_laws.py (d = 0.2 m, T = 3 s, H = 0.08 m, Ursell number 171, dp = 0.04 m so
H/dp = 2, gauge at 0.3 L): the mean zero-crossing height of the waves after the ramp.

    RAYON_NUM_THREADS=1 python3 scripts/cnoidal_flume.py cnoidal stream_function
"""

import math
import sys
import time

import watersim as ws
from watersim import analysis
from watersim import wave_theory as wt

depth, period, height, dp = 0.2, 3.0, 0.08, 0.04
G = 9.81
length = float(wt.wavelength(period, depth))
flume = ws.Flume(length=round(1.6 * length, 2), depth=depth,
                 damping=ws.DampingZone(length=round(0.6 * length, 2)))
x = round(0.3 * length, 2)
for theory in sys.argv[1:] or ("cnoidal", "stream_function"):
    sim = flume.simulation(ws.RegularWave(height=height, period=period, theory=theory),
                           paddle=ws.Piston(order=2, ramp_periods=1.0), dp=dp,
                           gauges=[ws.ElevationGauge(x)], coefsound=10.0,
                           until=3.5 * period + x / math.sqrt(G * depth))
    t0 = time.time()
    sim.run()
    t = sim.gauges.t
    steady = t >= period + x / math.sqrt(G * depth)
    waves = analysis.zero_crossing_waves(sim.gauges.elevation[steady, 0], t[steady])
    print(f"{theory}: heights {waves.heights.round(4).tolist()} m, mean {waves.mean_height:.4f} m "
          f"({waves.mean_height / height - 1:+.1%}); {sim.steps} steps, {time.time() - t0:.0f} s")
