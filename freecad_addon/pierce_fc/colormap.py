"""False colours for thickness maps: thin = red through yellow and green to thick = blue; thin
regions below a threshold in magenta; no thickness (ray escaped, no normal) in grey."""
import numpy as np

# Stops of the ramp from the low to the high end of the range.
RAMP = np.array([
    (0.85, 0.10, 0.10),  # red
    (1.00, 0.55, 0.00),  # orange
    (0.95, 0.90, 0.10),  # yellow
    (0.20, 0.75, 0.25),  # green
    (0.10, 0.45, 0.90),  # blue
])
THIN = (1.0, 0.0, 1.0)
NONE = (0.55, 0.55, 0.55)


def ramp(t):
    """Colours for t in [0, 1] (clipped), shape (N, 3)."""
    t = np.clip(np.asarray(t, dtype=float), 0.0, 1.0) * (len(RAMP) - 1)
    i = np.minimum(t.astype(int), len(RAMP) - 2)
    f = (t - i)[:, None]
    return RAMP[i] * (1.0 - f) + RAMP[i + 1] * f


def colours(values, lo, hi, thin_below=0.0):
    """RGB rows for values mapped over [lo, hi]; NaN grey; values < thin_below magenta."""
    v = np.asarray(values, dtype=float)
    span = hi - lo if hi > lo else 1.0
    out = ramp((np.nan_to_num(v, nan=lo) - lo) / span)
    out[np.isnan(v)] = NONE
    if thin_below > 0:
        out[np.nan_to_num(v, nan=np.inf) < thin_below] = THIN
    return out


def legend_stops(lo, hi, count=5):
    """(value, rgb) pairs along the range, for legends."""
    return [(lo + (hi - lo) * k / (count - 1), tuple(ramp([k / (count - 1)])[0])) for k in range(count)]
