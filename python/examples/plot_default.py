"""The default scene (the paper's Figure 8 case: two copper balls, D = 20 mm, +1 / -1 m/s),
FE beside the analytical model: approach delta(t) and contact force F(delta), as a PNG.

    python python/examples/plot_default.py [OUT.png] [PATH=VALUE ...]

PATH=VALUE are scene overrides as `twoball run --set` takes them, e.g.
`ball1.velocity=[2,0,0]`.
"""

import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

import twoball  # noqa: E402


def main(argv):
    out = argv[0] if argv and "=" not in argv[0] else "default_scene.png"
    overrides = dict(a.split("=", 1) for a in argv if "=" in a)
    run = twoball.run(**overrides)
    h = run.history
    an = run.results["analytic"]
    fig, (ax_t, ax_f) = plt.subplots(1, 2, figsize=(10, 4))
    ax_t.plot(1e6 * h["t"], 1e6 * h["delta"], label="FE")
    ax_t.axhline(1e6 * an["delta_max"], color="k", ls="--", lw=0.8, label="analytical max")
    ax_t.set_xlabel("t [µs]")
    ax_t.set_ylabel("δ [µm]")
    ax_t.set_title(f"approach, e = {run.results['e']:.3f} (analytical {an['e']:.3f})")
    ax_t.legend()
    ax_f.plot(1e6 * h["delta"], 1e-3 * h["normal_force"])
    ax_f.set_xlabel("δ [µm]")
    ax_f.set_ylabel("F [kN]")
    ax_f.set_title("contact force against approach")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    print(f"wrote {out}")


if __name__ == "__main__":
    main(sys.argv[1:])
