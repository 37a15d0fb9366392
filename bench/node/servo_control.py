"""python-control's forced_response of the same servo loop as the wasm
benchmark (bench/node/servo.bench.mjs), for the speed ratio.

Reads one JSON object on stdin: the axis parameters (kpp, kvp, kvi, c, j, j1),
dt, and the sampled inputs r (position reference, motor rad) and f (scaled
feedforward, rad/s). Prints {"nsPerStep": …, "steps": …, "version": …} or
{"skipped": "why"} when python-control is not installed.

The loop is the linear 3-state cascade of suzuki-best-kffp Fig. 11 (state
[θ, ω, I], inputs [r, f], as in src/servo/discrete.rs): python-control has no
torque saturation, so this is the linear part only, same states, same inputs,
same number of steps. Timing: the fastest of `runs` calls.
"""
import json
import sys
import time

try:
    import control
    import numpy as np
except ImportError as e:  # the Node side prints this and skips the ratio
    print(json.dumps({"skipped": f"python-control is not installed ({e})"}))
    sys.exit(0)

cfg = json.load(sys.stdin)
a = cfg["axis"]
jt = a["j"] + a["j1"]
kpp, kvp, kvi, c = a["kpp"], a["kvp"], a["kvi"], a["c"]
A = [[0, 1, 0], [-kvp * kpp / jt, -(kvp + c) / jt, kvi / jt], [-kpp, -1, 0]]
B = [[0, 0], [kvp * kpp / jt, kvp / jt], [kpp, 1]]
C = [[1, 0, 0], [0, 1, 0]]
sys_ = control.ss(A, B, C, [[0, 0], [0, 0]])
r = np.asarray(cfg["r"], dtype=float)
f = np.asarray(cfg["f"], dtype=float)
t = np.arange(len(r)) * cfg["dt"]
u = np.vstack([r, f])
best = float("inf")
for _ in range(cfg.get("runs", 3)):
    t0 = time.perf_counter()
    control.forced_response(sys_, T=t, U=u)
    best = min(best, time.perf_counter() - t0)
print(json.dumps({"nsPerStep": best * 1e9 / len(r), "steps": len(r), "version": control.__version__}))
