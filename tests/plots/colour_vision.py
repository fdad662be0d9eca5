"""Colour maths for the palette test: sRGB, CIELAB, CIEDE2000, simulated colour vision, WCAG contrast.

The conventions are the ones ``kfcourse.plots.palette`` states in its docstring:

- sRGB (IEC 61966-2-1) decoded to linear RGB, CIE XYZ and CIELAB with the D65 white (Y = 1);
- colour difference: CIEDE2000 (Sharma, Wu & Dalal 2005) with kL = kC = kH = 1;
- colour vision deficiency: Machado, Oliveira & Fernandes (2009), severity 1.0, their matrix applied to
  linear RGB and the result clipped to [0, 1] (what a screen can show);
- contrast: WCAG 2 relative luminance, (L1 + 0.05) / (L2 + 0.05).
"""

import numpy as np

# Machado, Oliveira & Fernandes (2009), severity 1.0, for linear RGB.
MACHADO = {
    "protan": np.array(
        [
            [0.152286, 1.052583, -0.204868],
            [0.114503, 0.786281, 0.099216],
            [-0.003882, -0.048116, 1.051998],
        ]
    ),
    "deutan": np.array(
        [
            [0.367322, 0.860646, -0.227968],
            [0.280085, 0.672501, 0.047413],
            [-0.011820, 0.042940, 0.968881],
        ]
    ),
    "tritan": np.array(
        [
            [1.255528, -0.076749, -0.178779],
            [-0.078411, 0.930809, 0.147602],
            [0.004733, 0.691367, 0.303900],
        ]
    ),
}
VISIONS = ("normal", "protan", "deutan", "tritan")

# linear sRGB -> CIE XYZ (D65), IEC 61966-2-1
SRGB_TO_XYZ = np.array(
    [
        [0.4124, 0.3576, 0.1805],
        [0.2126, 0.7152, 0.0722],
        [0.0193, 0.1192, 0.9505],
    ]
)
D65 = np.array([0.95047, 1.0, 1.08883])  # the CIE D65 white, Y = 1


def hex_to_srgb(colour: str) -> np.ndarray:
    """'#rrggbb' -> sRGB in [0, 1]."""
    return np.array([int(colour[i : i + 2], 16) for i in (1, 3, 5)]) / 255.0


def srgb_to_linear(c):
    c = np.asarray(c, dtype=float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def linear_to_srgb(c):
    c = np.clip(np.asarray(c, dtype=float), 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def simulate(linear_rgb, vision: str) -> np.ndarray:
    """Linear RGB (..., 3) as seen with ``vision``, clipped to what a screen shows."""
    if vision == "normal":
        return np.asarray(linear_rgb, dtype=float)
    return np.clip(np.asarray(linear_rgb, dtype=float) @ MACHADO[vision].T, 0.0, 1.0)


def linear_to_lab(linear_rgb) -> np.ndarray:
    """Linear sRGB (..., 3) -> CIELAB (..., 3), D65 white."""
    xyz = np.asarray(linear_rgb, dtype=float) @ SRGB_TO_XYZ.T / D65
    eps, kappa = 216 / 24389, 24389 / 27
    f = np.where(xyz > eps, np.cbrt(xyz), (kappa * xyz + 16) / 116)
    L = 116 * f[..., 1] - 16
    a = 500 * (f[..., 0] - f[..., 1])
    b = 200 * (f[..., 1] - f[..., 2])
    return np.stack([L, a, b], axis=-1)


def lab(colour: str, vision: str = "normal") -> np.ndarray:
    """CIELAB of a '#rrggbb' colour as seen with ``vision``."""
    return linear_to_lab(simulate(srgb_to_linear(hex_to_srgb(colour)), vision))


def ciede2000(lab1, lab2) -> float:
    """CIEDE2000 colour difference, Sharma, Wu & Dalal (2005), equations (1)-(23), kL = kC = kH = 1."""
    L1, a1, b1 = map(float, lab1)
    L2, a2, b2 = map(float, lab2)
    # (2)-(5): a' stretches the a axis near neutral
    C_mean = (np.hypot(a1, b1) + np.hypot(a2, b2)) / 2
    G = 0.5 * (1 - np.sqrt(C_mean**7 / (C_mean**7 + 25.0**7)))
    a1p, a2p = (1 + G) * a1, (1 + G) * a2
    C1p, C2p = np.hypot(a1p, b1), np.hypot(a2p, b2)
    h1p = np.degrees(np.arctan2(b1, a1p)) % 360 if C1p else 0.0
    h2p = np.degrees(np.arctan2(b2, a2p)) % 360 if C2p else 0.0
    # (8)-(10): differences
    dLp = L2 - L1
    dCp = C2p - C1p
    if C1p * C2p == 0:
        dhp = 0.0
    elif abs(h2p - h1p) <= 180:
        dhp = h2p - h1p
    elif h2p - h1p > 180:
        dhp = h2p - h1p - 360
    else:
        dhp = h2p - h1p + 360
    dHp = 2 * np.sqrt(C1p * C2p) * np.sin(np.radians(dhp / 2))
    # (12)-(14): means
    Lp = (L1 + L2) / 2
    Cp = (C1p + C2p) / 2
    if C1p * C2p == 0:
        hp = h1p + h2p
    elif abs(h1p - h2p) <= 180:
        hp = (h1p + h2p) / 2
    elif h1p + h2p < 360:
        hp = (h1p + h2p + 360) / 2
    else:
        hp = (h1p + h2p - 360) / 2
    # (15)-(21): weights and the rotation term
    T = (
        1
        - 0.17 * np.cos(np.radians(hp - 30))
        + 0.24 * np.cos(np.radians(2 * hp))
        + 0.32 * np.cos(np.radians(3 * hp + 6))
        - 0.20 * np.cos(np.radians(4 * hp - 63))
    )
    d_theta = 30 * np.exp(-(((hp - 275) / 25) ** 2))
    R_C = 2 * np.sqrt(Cp**7 / (Cp**7 + 25.0**7))
    S_L = 1 + 0.015 * (Lp - 50) ** 2 / np.sqrt(20 + (Lp - 50) ** 2)
    S_C = 1 + 0.045 * Cp
    S_H = 1 + 0.015 * Cp * T
    R_T = -np.sin(np.radians(2 * d_theta)) * R_C
    # (22)
    return float(np.sqrt((dLp / S_L) ** 2 + (dCp / S_C) ** 2 + (dHp / S_H) ** 2 + R_T * (dCp / S_C) * (dHp / S_H)))


def difference(colour1: str, colour2: str, vision: str = "normal") -> float:
    """CIEDE2000 between two '#rrggbb' colours as seen with ``vision``."""
    return ciede2000(lab(colour1, vision), lab(colour2, vision))


def relative_luminance(colour: str) -> float:
    """WCAG 2 relative luminance of a '#rrggbb' colour."""
    return float(srgb_to_linear(hex_to_srgb(colour)) @ np.array([0.2126, 0.7152, 0.0722]))


def contrast(colour1: str, colour2: str) -> float:
    """WCAG 2 contrast ratio, 1 to 21."""
    high, low = sorted((relative_luminance(colour1), relative_luminance(colour2)), reverse=True)
    return (high + 0.05) / (low + 0.05)
