"""A frame of the arm for ``render_mode="rgb_array"``: the two links at their joint angles with
the target pose dashed (metres, the shoulder at the origin), and the muscles' tendon forces over
f_max as bars, each panel with its title, axis labels and legend. Needs matplotlib (Agg, no
display; in the ``gym`` extra)."""

from __future__ import annotations

import numpy as np

#: Drawn link lengths, m (humerus, forearm with hand): for the picture only.
LINKS = (0.30, 0.27)


def _points(angles: np.ndarray) -> np.ndarray:
    """Shoulder, elbow and hand in the sagittal plane, the arm hanging down at angles 0."""
    a1 = angles[0]
    a2 = angles[0] + angles[1]
    p0 = np.zeros(2)
    p1 = p0 + LINKS[0] * np.array([np.sin(a1), -np.cos(a1)])
    p2 = p1 + LINKS[1] * np.array([np.sin(a2), -np.cos(a2)])
    return np.stack([p0, p1, p2])


def arm_frame(last: dict, target: np.ndarray, muscles: list[str], f_max: np.ndarray) -> np.ndarray:
    try:
        import matplotlib

        matplotlib.use("Agg", force=False)
        from matplotlib.backends.backend_agg import FigureCanvasAgg
        from matplotlib.figure import Figure
    except ImportError as e:  # pragma: no cover - depends on the environment
        raise ImportError(
            "render_mode='rgb_array' needs matplotlib: pip install 'muscle_actuator[gym]' (or matplotlib)"
        ) from e
    fig = Figure(figsize=(6.4, 3.2), dpi=100)
    canvas = FigureCanvasAgg(fig)
    ax, bars = fig.add_subplot(1, 2, 1), fig.add_subplot(1, 2, 2)
    p = _points(np.asarray(last["joint.position"]))
    q = _points(np.asarray(target))
    ax.plot(q[:, 0], q[:, 1], "--", color="0.6", lw=2, label="target")
    ax.plot(p[:, 0], p[:, 1], "-o", color="tab:blue", lw=4, label="arm")
    ax.set_xlim(-0.6, 0.6)
    ax.set_ylim(-0.6, 0.6)
    ax.set_aspect("equal")
    ax.set_title("arm (shoulder at 0, sagittal plane)", fontsize=9)
    ax.set_xlabel("horizontal (m)", fontsize=8)
    ax.set_ylabel("vertical (m)", fontsize=8)
    ax.tick_params(labelsize=7)
    ax.legend(loc="lower left", fontsize=7)
    force = np.asarray(last["force"]) / f_max
    bars.bar(range(len(muscles)), force, color="tab:red", label="tendon force")
    bars.axhline(1.0, color="0.5", lw=1, ls=":", label="f_max")
    bars.set_xticks(range(len(muscles)), muscles, rotation=45, fontsize=7)
    bars.set_ylim(0, 1.2)
    bars.set_title("muscle forces", fontsize=9)
    bars.set_xlabel("muscle", fontsize=8)
    bars.set_ylabel("tendon force / f_max (1)", fontsize=8)
    bars.tick_params(labelsize=7)
    bars.legend(loc="upper right", fontsize=7)
    fig.tight_layout()
    canvas.draw()
    return np.asarray(canvas.buffer_rgba())[:, :, :3].copy()
