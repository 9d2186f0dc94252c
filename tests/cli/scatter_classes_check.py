"""scatter_classes_check.py METRICS.json N: `scatter --metrics --json` of a set of N classes holds
a "classes" array of N entries, each with points, no pair closer than its own spacing, and its own
spectrum, measured like the union's (windows averaged, so a noise floor below 0 dB, and power in
every annulus)."""
import json
import sys

metrics = json.load(open(sys.argv[1], encoding="utf-8"))
classes = metrics.get("classes", [])
if len(classes) != int(sys.argv[2]):
    sys.exit(f"scatter_classes_check: {len(classes)} classes in {sys.argv[1]}; expected {sys.argv[2]}")
for k, c in enumerate(classes):
    if c["count"] <= 0 or c["close_pairs"] != 0 or not c["class_spacing_m"] > 0:
        sys.exit(f"scatter_classes_check: class {k}: {c['count']} points, {c['close_pairs']} pairs closer than "
                 f"{c['class_spacing_m']} m")
    spectrum = c.get("spectrum")
    # (The noise floor is -10 log10(windows): below 0 dB whenever windows >= 2, so not checked again.)
    if not spectrum or spectrum["windows"] < 2 or not spectrum["power"] or \
            not all(p > 0 for p in spectrum["power"]):
        sys.exit(f"scatter_classes_check: class {k}: no spectrum of its own (spectrum {spectrum is not None}, "
                 f"noise floor {c['anisotropy_noise_floor_db']} dB)")
print("classes", " ".join(f"{c['count']}:{c['rho']:.3f}" for c in classes), "union", metrics["count"])
