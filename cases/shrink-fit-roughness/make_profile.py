#!/usr/bin/env python3
"""Synthetic roughness profiles for cases/shrink-fit-roughness (run once; the CSV is shipped).

Two independent Gaussian random profiles, the ground shaft (Rz 4 um) and the reamed hub bore
(Rz 6.3 um), each with a self-affine spectrum (Hurst exponent 0.8) between wavelengths of
0.25 mm (roll-off) and 5 um (cut-off), sampled every 1 um over the ISO 4288 evaluation length of
4 mm (5 sampling lengths of 0.8 mm). Each is scaled to its Rz (ISO 4287: the mean over the five
sampling lengths of the highest peak plus the deepest valley about the mean line). The file
holds their sum, the combined surface that the Greenwood-Williamson model takes (one rough
surface against a flat), in mm, one height per line.
"""
import numpy as np

DX = 1e-3          # mm
N = 4000           # 4 mm
LONG, SHORT, HURST = 0.25, 5e-3, 0.8

def profile(rng):
    k = np.fft.rfftfreq(N, DX) * 2 * np.pi
    kl, ks = 2 * np.pi / LONG, 2 * np.pi / SHORT
    psd = np.where(k < kl, 1.0, (np.maximum(k, kl) / kl) ** (-(1 + 2 * HURST)))
    psd[(k > ks) | (k == 0)] = 0.0
    phase = rng.uniform(0, 2 * np.pi, k.size)
    amp = np.sqrt(psd) * rng.standard_normal(k.size)
    z = np.fft.irfft(amp * np.exp(1j * phase), N)
    return z - z.mean()

def rz(z):
    parts = z.reshape(5, -1)
    return float(np.mean(parts.max(axis=1) - parts.min(axis=1)))

rng = np.random.default_rng(20261124)
shaft, hub = profile(rng), profile(rng)
shaft *= 4.0e-3 / rz(shaft)
hub *= 6.3e-3 / rz(hub)
both = shaft + hub
print(f"Rz shaft {rz(shaft)*1e3:.2f} um, hub {rz(hub)*1e3:.2f} um, combined {rz(both)*1e3:.2f} um, "
      f"Rq combined {both.std()*1e3:.3f} um")
with open("profile.csv", "w") as f:
    f.write("# combined surface of the shaft (Rz 4.0 um) and the hub bore (Rz 6.3 um), mm, every 1 um\n")
    for v in both:
        f.write(f"{v:.6e}\n")
