"""A parameter sweep from Python: the demo scene's hierarchical render at several visibility
thresholds, each compared with the naive mode (the hierarchy's accuracy target), plotted against
the share of pixels gathered. Usage (docs/python.md):

    PYTHONPATH=build/python /usr/bin/python3 examples/python/sweep.py out/sweep.png [SCENE]
"""

import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import penumbra  # noqa: E402

output = sys.argv[1] if len(sys.argv) > 1 else "sweep.png"
scene_file = sys.argv[2] if len(sys.argv) > 2 else os.path.join(
    os.path.dirname(__file__), "..", "..", "scenes", "demo.scene")
size = (128, 128)
thresholds = [0.005, 0.01, 0.02, 0.05, 0.1, 0.2]

scene = penumbra.load_scene(scene_file)
renderer = penumbra.Renderer(scene, size=size)
target = renderer.render(mode="naive")
errors, shares = [], []
for threshold in thresholds:
    result = renderer.render(visibility_threshold=threshold, statistics=True)
    statistics = result["statistics"]
    errors.append(penumbra.compare(result["radiance"], target)["rmse"])
    shares.append(statistics["samples_gathered"] / statistics["full_resolution_samples"])
    print(f"threshold {threshold}: rmse {errors[-1]:.4g}, gathered {100 * shares[-1]:.1f}%")

figure, error_axis = plt.subplots(figsize=(6, 4))
error_axis.plot(thresholds, errors, "o-", color="tab:red")
error_axis.set_xscale("log")
error_axis.set_xlabel("visibility threshold (fraction of the VPLs)")
error_axis.set_ylabel("RMSE against the naive mode", color="tab:red")
share_axis = error_axis.twinx()
share_axis.plot(thresholds, [100 * share for share in shares], "s--", color="tab:blue")
share_axis.set_ylabel("samples gathered (% of full resolution)", color="tab:blue")
figure.tight_layout()
figure.savefig(output, dpi=120)
print(f"wrote {output}")
